"""Raba 118/76 bearing data and loads for c_p and c_c (SI units).

The paper gives c_p = c_c = c_r = 1e8 N/m and no bearing data.  ASSUMED
here, and labelled so wherever printed: the operating sun torque, the planet
needle bearing and the carrier (wheel-hub) bearing.
"""
from __future__ import annotations

import math

from hubvib.meshing import raba118 as geometry

from .bearing import RollerBearing

SUN_TORQUE = 1000.0  # [N m] ASSUMED operating torque on the sun
PLANETS = 3
#: ASSUMED: planet needle bearing on a 26 mm pin in the 36 mm bore: 16 needles of 5 mm,
#: 30 mm effective length.
PLANET_BEARING = RollerBearing(rollers=16, roller_length=30e-3)
#: ASSUMED: the wheel-hub bearings that hold the carrier, as one radial roller row of
#: 2 x 20 rollers with 20 mm effective length, under a 25 kN wheel-load share.
CARRIER_BEARING = RollerBearing(rollers=40, roller_length=20e-3)
CARRIER_LOAD = 25e3  # [N] ASSUMED


def mesh_force(sun_torque: float = SUN_TORQUE) -> float:
    """Normal force of each sun-planet mesh [N] (equal load sharing)."""
    rb = geometry.sun().base_diameter / 2
    return sun_torque / (PLANETS * rb)


def planet_bearing_load(sun_torque: float = SUN_TORQUE) -> float:
    """Radial load on a planet bearing [N]: the sun and ring mesh forces on the planet
    have equal tangential parts, which add, and opposite radial parts, which cancel."""
    return 2 * mesh_force(sun_torque) * math.cos(geometry.WORKING_PRESSURE_ANGLE)


def bearing_stiffness(sun_torque: float = SUN_TORQUE) -> dict[str, dict]:
    """c_p and c_c, tangent and secant [N/m], with the loads they were computed at [N]."""
    out = {}
    for name, bearing, load in (("c_p", PLANET_BEARING, planet_bearing_load(sun_torque)),
                                ("c_c", CARRIER_BEARING, CARRIER_LOAD)):
        tangent, secant = bearing.stiffness(load)
        out[name] = {"tangent_N_m": tangent, "secant_N_m": secant, "load_N": load,
                     "rollers": bearing.rollers, "roller_length_m": bearing.roller_length}
    return out
