"""The stiffness matrix exactly as printed in the paper (eq. 11-13), N = 3.

The printed coefficients follow from eq. (10), which claims that for three
equally spaced planets ``sum sin^2(theta_i -+ alpha_w) = sum cos^2(...) = 0``;
the true value is N/2 = 1.5.  Hence ``c_11 = c_22 = 0`` and ``c_55 = c_66 = c_r``
instead of ``1.5 c_sp`` and ``c_r + 1.5 c_rp``: the matrix is indefinite.  It
exists here to reproduce the published spectrum and to show that defect; use
:func:`lumped.network.stiffness_matrix` for physics.
"""
from __future__ import annotations

import math

import numpy as np

from .parameters import ParameterError, PlanetaryParameters


def printed_stiffness_matrix(params: PlanetaryParameters) -> np.ndarray:
    """Matrix C of eq. (11)-(13) [N/m] for three equally spaced planets."""
    if params.n_planets != 3 or not params.equally_spaced(1e-9):
        raise ParameterError(
            f"the printed matrix exists for N = 3 equally spaced planets only, got theta = {params.theta}"
        )
    if params.alpha_s != params.alpha_r:
        raise ParameterError(
            f"the printed matrix uses one working angle, got alpha_s = {params.alpha_s} "
            f"and alpha_r = {params.alpha_r} rad"
        )
    if params.c_s != 0:
        raise ParameterError(f"the printed matrix has a floating sun, got c_s = {params.c_s} N/m")
    if any(f != 1 for f in params.c_rp_factors):
        raise ParameterError(f"the printed matrix has one c_rp for all planets, got "
                             f"c_rp_factors = {params.c_rp_factors}")
    p = params
    sw, kw = math.sin(p.alpha_r), math.cos(p.alpha_r)
    C = np.zeros((18, 18))

    def c(i, j, value):  # 1-based indices as printed
        C[i - 1, j - 1] = C[j - 1, i - 1] = value

    c(3, 3, p.c_c + 3 * p.c_p)
    c(4, 4, p.c_c + 3 * p.c_p)
    c(5, 5, p.c_r)
    c(6, 6, p.c_r)
    c(7, 7, p.c_su + 3 * p.c_sp)
    c(8, 8, p.c_cu + 3 * p.c_p)
    c(9, 9, p.c_ru + 3 * p.c_rp)
    for i, th in enumerate(p.theta):
        b = 10 + 3 * i
        s2, k2 = math.sin(th), math.cos(th)
        s3, k3 = math.sin(th - p.alpha_r), math.cos(th - p.alpha_r)
        s4, k4 = math.sin(th + p.alpha_r), math.cos(th + p.alpha_r)
        c(b, b, p.c_p + (p.c_sp + p.c_rp) * kw**2)
        c(b + 1, b + 1, p.c_p + (p.c_sp + p.c_rp) * sw**2)
        c(b + 2, b + 2, p.c_sp + p.c_rp)
        c(1, b, p.c_sp * kw * s3); c(1, b + 1, p.c_sp * sw * s3); c(1, b + 2, -p.c_sp * s3)
        c(2, b, -p.c_sp * kw * k3); c(2, b + 1, -p.c_sp * sw * k3); c(2, b + 2, p.c_sp * k3)
        c(3, b, p.c_p * s2); c(3, b + 1, -p.c_p * k2)
        c(4, b, -p.c_p * k2); c(4, b + 1, -p.c_p * s2)
        c(5, b, p.c_rp * kw * s4); c(5, b + 1, -p.c_rp * sw * s4); c(5, b + 2, p.c_rp * s4)
        c(6, b, -p.c_rp * kw * k4); c(6, b + 1, p.c_rp * sw * k4); c(6, b + 2, -p.c_rp * k4)
        c(7, b, -p.c_sp * kw); c(7, b + 1, -p.c_sp * sw); c(7, b + 2, p.c_sp)
        c(8, b, -p.c_p)
        c(9, b, -p.c_rp * kw); c(9, b + 1, p.c_rp * sw); c(9, b + 2, -p.c_rp)
        c(b, b + 1, sw * kw * (p.c_sp - p.c_rp))
        c(b, b + 2, -kw * (p.c_sp - p.c_rp))
        c(b + 1, b + 2, -sw * (p.c_sp + p.c_rp))
    return C
