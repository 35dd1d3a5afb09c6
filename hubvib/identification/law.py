"""How uncertain an identified natural frequency is (SI).

Closed form (Au 2014, "Uncertainty law in ambient modal identification - Part I:
Theory", Mech. Syst. Signal Process. 48, 15-33): for a well-separated mode with
small damping, high signal-to-noise ratio and a wide identification band, the
coefficient of variation of the identified frequency is ``sqrt(zeta / (2 pi N_c))``
with ``N_c = f T`` the record length in natural periods, so

    sigma_f = sqrt(zeta f / (2 pi T))   [Hz].

The method shipped by :mod:`.bfft` maximises the Whittle likelihood of the FFT
ordinates in the band ``f (1 +- kappa zeta)``; its asymptotic standard deviation
is the Cramer-Rao bound of that likelihood, :func:`fisher_sigma_hz`, which keeps
the finite band and the finite signal-to-noise ratio that the closed form drops
(it tends to the closed form as both grow).  Both are in Hz.
"""
from __future__ import annotations

import functools
import math

import numpy as np

#: half-width of the identification band in units of the half-power bandwidth zeta f [-]
KAPPA = 6.0


def au_sigma_hz(frequency_hz, damping_ratio, record_s):
    """Au's law ``sqrt(zeta f / (2 pi T))`` [Hz] (high SNR, wide band).

    Parameters
    ----------
    frequency_hz : float or ndarray
        Natural frequency f [Hz], > 0.
    damping_ratio : float or ndarray
        Modal damping ratio zeta [-], > 0.
    record_s : float or ndarray
        Record length T [s], > 0.
    """
    f, z, t = (np.asarray(v, dtype=float) for v in (frequency_hz, damping_ratio, record_s))
    return np.sqrt(z * f / (2 * math.pi * t))


def response_shape(frequency_hz, natural_hz: float, damping_ratio: float,
                   power: int = 0) -> np.ndarray:
    """``b^power |h|^2``, ``|h|^2 = 1 / ((1 - b^2)^2 + (2 zeta b)^2)``, ``b = f / f_n``:
    the response PSD of one mode to white force over its static value [-]; ``power`` 0
    for displacement, 4 for acceleration."""
    b = np.asarray(frequency_hz, dtype=float) / natural_hz
    return b ** power / ((1 - b * b) ** 2 + (2 * damping_ratio * b) ** 2)


def fisher_sigma_hz(frequency_hz: float, damping_ratio: float, record_s: float,
                    snr: float = math.inf, kappa: float = KAPPA, power: int = 0) -> float:
    """Cramer-Rao bound [Hz] of the frequency identified by :mod:`.bfft`.

    The FFT ordinates of a record of ``record_s`` seconds in the band
    ``f (1 +- kappa zeta)`` are independent complex Gaussians with variance
    ``D_k = S |h_k|^2 + S_e`` (Yuen, Katafygiotis & Beck 2002); the Fisher
    information of ``(f, zeta, S, S_e)`` is ``sum_k grad D_k grad D_k^T / D_k^2`` and
    the bound is the (f, f) entry of its inverse.

    Parameters
    ----------
    snr : float
        Modal signal-to-noise ratio ``S / (4 zeta^2 S_e)``: response PSD at resonance over
        the noise PSD [-] (Au's gamma); ``inf`` leaves the noise out.
    kappa : float
        Band half-width in units of ``zeta f`` [-].
    power : int
        0: displacement record (white noise on displacement); 4: acceleration record
        (white noise on acceleration), the response shape times ``b^4``.
    """
    f0, zeta, T = float(frequency_hz), float(damping_ratio), float(record_s)
    if not (f0 > 0 and zeta > 0 and T > 0 and snr > 0 and kappa > 0):
        raise ValueError(f"fisher_sigma_hz: frequency {f0:g} Hz, damping {zeta:g}, record "
                         f"{T:g} s, snr {snr:g}, kappa {kappa:g}; all must be > 0")
    return _fisher_sigma_hz(f0, zeta, T, float(snr), float(kappa), int(power))


@functools.lru_cache(maxsize=4096)
def _fisher_sigma_hz(f0: float, zeta: float, T: float, snr: float, kappa: float,
                     power: int) -> float:
    """:func:`fisher_sigma_hz` on checked floats, remembered: the detection study asks for
    the same (frequency, record) pair many times, and a 600 s record of a 10 kHz mode sums
    1.7e6 FFT ordinates.  ``power`` 0 skips the factor ``b^0 = 1`` (the same floats)."""
    df = 1.0 / T
    k = np.arange(math.ceil(f0 * (1 - kappa * zeta) / df), math.floor(
        f0 * (1 + kappa * zeta) / df) + 1)
    f = k * df
    f = f[f > 0]
    S = 1.0
    Se = 0.0 if math.isinf(snr) else S / (4 * zeta * zeta * snr)
    # the formulas of the Fisher information below, evaluated in place into the rows of G
    # (a band holds up to ~1e6 ordinates): each value the same floating-point operations
    # in the same order as the plain expressions in the comments, so the same digits
    b = f / f0
    bb = b * b
    one_minus = np.subtract(1, bb)                      # 1 - b*b
    g = one_minus ** 2                                  # g = (1-b*b)**2 + (2*zeta*b)**2
    two_zeta_b = 2 * zeta * b
    two_zeta_b **= 2
    g += two_zeta_b
    dg_db = -4 * b                                      # -4*b*(1-b*b) + 8*zeta*zeta*b
    dg_db *= one_minus
    dg_db += 8 * zeta * zeta * b
    g2 = g ** 2
    G = np.empty((4 if Se > 0 else 3, f.size))
    d_f0, d_zeta, h2 = G[0], G[1], G[2]                 # d/d S: h2
    np.multiply(dg_db, b, out=d_f0)
    d_f0 /= g2
    np.multiply(8 * zeta * b, b, out=d_zeta)           # -(8*zeta*b*b) / g**2
    np.negative(d_zeta, out=d_zeta)
    d_zeta /= g2
    if power == 0:
        np.divide(1, g, out=h2)                         # h2 = 1/g
        d_f0 *= S                                       # S * (dg_db*b/g**2) / f0
        d_f0 /= f0
        d_zeta *= S                                     # S * (-(8*zeta*b*b)/g**2)
    else:
        bp = b ** power
        np.divide(bp, g, out=h2)                        # h2 = bp/g
        np.multiply(bp, dg_db, out=d_f0)                # S*(bp*dg_db*b/g**2 - power*h2)/f0
        d_f0 *= b
        d_f0 /= g2
        d_f0 -= power * h2
        d_f0 *= S
        d_f0 /= f0
        np.multiply(S * bp, d_zeta, out=d_zeta)         # S*bp*(-(8*zeta*b*b)/g**2)
    D = S * h2 + Se
    G[:3] /= D
    if Se > 0:
        np.divide(1.0, D, out=G[3])                     # d/d Se: 1
    info = G @ G.T
    return float(math.sqrt(np.linalg.inv(info)[0, 0]))
