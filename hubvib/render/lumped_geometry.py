"""What a lumped mode does to each body, and the toothed outline the pictures draw it with
(numpy only: shared by the pyvista renders and the matplotlib picture, SI inside)."""
from __future__ import annotations

import math

import numpy as np

#: the largest displacement of a mode as drawn, as a fraction of the ring radius
AMPLITUDE = 0.08
#: each member's colour (planets: ``PLANET_COLOUR``)
COLOURS = {"sun": "#d95f02", "ring": "#7570b3", "carrier": "#666666"}
PLANET_COLOUR = "#1b9e77"


def toothed_outline(radius: float, teeth: int, depth: float) -> np.ndarray:
    """Closed polygon (n, 2) of a plate with ``teeth`` trapezoid teeth; outward if depth > 0."""
    per = 8
    phi = np.linspace(0, 2 * math.pi, teeth * per, endpoint=False)
    phase = (phi * teeth / (2 * math.pi)) % 1.0
    profile = np.clip(np.abs(phase - 0.5) * 4 - 0.5, 0, 1)  # trapezoid wave
    r = radius + depth * (0.5 - profile)
    return np.column_stack([r * np.cos(phi), r * np.sin(phi)])


def motion(params, shape: np.ndarray, member: str, r_c: float):
    """(dx, dy, angle) of a member for the mode ``shape`` (network coordinate order)."""
    if member == "sun":
        return shape[0], shape[1], shape[6] / (params.d_s / 2)
    if member == "ring":
        return shape[4], shape[5], shape[8] / (params.d_r / 2)
    if member == "carrier":
        return shape[2], shape[3], shape[7] / r_c
    i = int(member.split()[1]) - 1
    theta = params.theta[i]
    tau, eta, u = shape[9 + 3 * i: 12 + 3 * i]
    tangent = np.array([-math.sin(theta), math.cos(theta)])
    radial = np.array([math.cos(theta), math.sin(theta)])
    carrier_turn = shape[7] / r_c
    carried = np.array([shape[2], shape[3]]) + carrier_turn * r_c * tangent
    dx, dy = carried + tau * tangent + eta * radial
    return dx, dy, u / (params.d_p / 2)
