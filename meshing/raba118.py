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
from .ring_gear import RingGear, Supports, outer_diameter_for_mass

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


# ring body ----------------------------------------------------------------
RING_MASS = 6.8  # [kg] from the paper
#: ASSUMED: six clamped spline/bolt pads of 20 deg on the outer surface, the first at 0 deg.
RING_SUPPORTS = Supports(count=6, width=math.radians(20.0), first_angle=0.0)


def ring_gear(supports: Supports = RING_SUPPORTS, fillet: str = "trochoid") -> RingGear:
    """Raba 118/76 ring with its rim (outer diameter from the paper's 6.8 kg).

    ASSUMED (not in the paper): steel 7850 kg/m^3; face width 40 mm; the fillet
    and root circle cut by a 25-tooth shaper cutter (x0 = 0, h_a0* = 1.25,
    rho_a0* = 0.25); six clamped support arcs of 20 deg (spline/bolt pads) on
    the outer surface.  The outer diameter (272.8 mm, rim 24.5 mm below the
    root circle) follows from the mass with the exact tooth geometry.
    """
    gear = ring()
    return RingGear(gear, outer_diameter_for_mass(gear, RING_MASS, fillet=fillet), supports,
                    fillet=fillet, working_pressure_angle=WORKING_PRESSURE_ANGLE)


# external gear bodies (tooth stiffness) -------------------------------------
#: ASSUMED: bores of the sun's shaft seat and the planet's bearing seat [m].
BORES = {"sun": 30e-3, "planet": 36e-3}


def gear_body(name: str):
    """Sun or planet body with its bore (``name`` = ``"sun"`` or ``"planet"``).

    ASSUMED (not in the paper): the bores (sun 30 mm on its shaft, planet 36 mm
    on its needle bearing, whole bore held), the ISO 53 rack fillet, face width 40 mm.
    """
    from .gear_body import GearBody

    gears = {"sun": sun, "planet": planet}
    if name not in gears:
        raise ValueError(f"gear body {name!r}, allowed: {', '.join(gears)}")
    return GearBody(gears[name](), BORES[name], working_pressure_angle=WORKING_PRESSURE_ANGLE)
