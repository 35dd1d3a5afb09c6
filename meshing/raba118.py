"""Raba 118/76 gears: what the paper gives and what is assumed.

From the paper: base diameters (sun 79.404, planet 58.026, ring 195.45 mm) and
the working pressure angle 25.28 deg, the same for both meshes.
Derived: with alpha = 20 deg these give z = 26 / 19 / 64 and m = 3.25 mm
(64 = 26 + 2 * 19), so both pairs have z-sum/difference 45, one centre
distance, and the same profile-shift sum ``x_s + x_p = x_r - x_p``.
ASSUMED (not in the paper): the split of that sum, x_p = 0.4, chosen so that
sun and planet tips are equally thick (0.50 m and 0.51 m); ISO 53 profile A
basic rack (h_a* = 1, h_f* = 1.25, rho_fP* = 0.38); face width 40 mm.
"""
from __future__ import annotations

import math

from .gear import SpurGear, involute

MODULE = 3.25e-3  # [m]
PRESSURE_ANGLE = math.radians(20.0)
WORKING_PRESSURE_ANGLE = math.radians(25.28)
TEETH = {"sun": 26, "planet": 19, "ring": 64}
PLANET_SHIFT = 0.4  # ASSUMED
FACE_WIDTH = 40e-3  # [m] ASSUMED


def shift_sum() -> float:
    """x_s + x_p (= x_r - x_p) that gives the paper's working angle [-]."""
    return (float(involute(WORKING_PRESSURE_ANGLE)) - float(involute(PRESSURE_ANGLE))) * (
        TEETH["sun"] + TEETH["planet"]) / (2 * math.tan(PRESSURE_ANGLE))


def sun() -> SpurGear:
    return SpurGear(TEETH["sun"], MODULE, PRESSURE_ANGLE, shift_sum() - PLANET_SHIFT,
                    face_width=FACE_WIDTH)


def planet() -> SpurGear:
    return SpurGear(TEETH["planet"], MODULE, PRESSURE_ANGLE, PLANET_SHIFT, face_width=FACE_WIDTH)


def ring() -> SpurGear:
    return SpurGear(TEETH["ring"], MODULE, PRESSURE_ANGLE, shift_sum() + PLANET_SHIFT,
                    face_width=FACE_WIDTH, internal=True)
