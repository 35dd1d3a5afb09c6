"""In-plane natural frequencies of a free circular ring, by curved-beam theory (SI units).

A ring of mean radius R, rectangular section h (radial) x b (axial), material E, G, rho.

- ``thick_ring_hz``: the Timoshenko curved beam -- extension, bending, shear (shear
  coefficient 10 (1 + nu) / (12 + 11 nu) of a rectangle, Cowper 1966) and rotary inertia.
  With ``u = U sin n theta`` (tangential), ``w = W cos n theta`` (radial) and the section
  rotation ``beta = B sin n theta``, the strains are ``eps = (n U + W) / R``,
  ``kappa = n B / R``, ``gamma = -((n W + U) / R + B)``; the energies give a 3 x 3
  generalised eigenproblem per n whose lowest root is the flexural mode (n >= 2), n = 0
  the breathing mode ``sqrt(E / rho) / R`` (extension only).
- ``thin_ring_hz``: the inextensional Euler-Bernoulli ring (Hoppe 1871),
  ``omega^2 = E I n^2 (n^2 - 1)^2 / (rho A R^4 (n^2 + 1))``; the thick ring's limit as
  h / R -> 0.
"""
from __future__ import annotations

import math

import numpy as np
import scipy.linalg as sla


def _check(radius, thickness, width, E, nu, density):
    for name, value in (("radius", radius), ("thickness", thickness), ("width", width),
                        ("E", E), ("density", density)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r}, allowed > 0")
    if not -1 < nu < 0.5:
        raise ValueError(f"nu = {nu!r}, allowed (-1, 0.5)")
    if thickness >= 2 * radius:
        raise ValueError(f"thickness = {thickness!r} m, allowed < 2 radius = {2 * radius!r} m")


def thin_ring_hz(n: int, radius: float, thickness: float, width: float, E: float,
                 density: float) -> float:
    """Inextensional flexural frequency of nodal-diameter count n >= 2 [Hz]."""
    _check(radius, thickness, width, E, 0.3, density)
    area, inertia = thickness * width, width * thickness ** 3 / 12
    omega2 = E * inertia * n ** 2 * (n ** 2 - 1) ** 2 / (density * area * radius ** 4 * (n ** 2 + 1))
    return math.sqrt(omega2) / (2 * math.pi)


def thick_ring_hz(n: int, radius: float, thickness: float, width: float, E: float, nu: float,
                  density: float) -> np.ndarray:
    """The three in-plane frequencies of nodal-diameter count n (flexural first) [Hz];
    n = 0: the breathing frequency alone (one value)."""
    _check(radius, thickness, width, E, nu, density)
    area, inertia = thickness * width, width * thickness ** 3 / 12
    shear = 10 * (1 + nu) / (12 + 11 * nu) * E / (2 * (1 + nu)) * area
    if n == 0:
        return np.array([math.sqrt(E / density) / radius / (2 * math.pi)])
    ext = np.array([n, 1.0, 0.0]) / radius           # eps per (U, W, B)
    bend = np.array([0.0, 0.0, n / radius])          # kappa
    gam = np.array([1.0 / radius, n / radius, 1.0])  # -gamma
    K = E * area * np.outer(ext, ext) + E * inertia * np.outer(bend, bend) + shear * np.outer(gam, gam)
    M = np.diag([density * area, density * area, density * inertia])
    omega2 = sla.eigh(K, M, eigvals_only=True)
    return np.sqrt(np.clip(omega2, 0.0, None)) / (2 * math.pi)
