"""One ratio's efficiency-optimal design of a ball/roller planetary gear (seed 001).

Chains :mod:`hubvib.companion.efficiency.core` (losses, optimal lift angle) and
:mod:`hubvib.companion.efficiency.track_geometry` (alpha2, R, A): the row of the paper's table for one
ratio, plus the link losses in W at a stated input power.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from hubvib.companion.efficiency.core import (PAPER_INPUT_POWER_W, Friction, LinkPower, Losses, Optimum, check_ratio,
                         losses, optimum)
from hubvib.companion.efficiency.track_geometry import SATELLITE_DIAMETER_M, TrackGeometry, track_geometry


@dataclass(frozen=True)
class GearDesign:
    """Losses, geometry and power balance of one gear at one driving-track lift angle.

    Attributes
    ----------
    friction : Friction
        Friction coefficients [-].
    optimum : Optimum
        Whole-degree and continuous optimal lift angles.
    at : Losses
        Losses at the evaluated lift angle (the whole-degree optimum unless one was given).
    tracks : tuple of TrackGeometry
        R and A [m] for each satellite size.
    power : LinkPower
        Link losses [W] at the input power.
    """

    friction: Friction
    optimum: Optimum
    at: Losses
    tracks: tuple[TrackGeometry, ...]
    power: LinkPower

    @property
    def ratio(self) -> int:
        return self.at.ratio

    @property
    def at_optimum(self) -> bool:
        """True when the evaluated lift angle is the whole-degree optimum."""
        return self.at.alpha1_rad == self.optimum.whole.alpha1_rad

    def to_dict(self) -> dict:
        return {"ratio": self.ratio, "z1": 1, "z2": self.at.z2,
                "friction": self.friction.to_dict(), "optimum": self.optimum.to_dict(),
                "at_optimum": self.at_optimum, **self.at.to_dict(),
                "tracks": [t.to_dict() for t in self.tracks], "power": self.power.to_dict()}


def gear_design(ratio: float, friction: Friction = Friction(), alpha1_rad: float | None = None,
                satellites: dict[str, float] | None = None,
                input_power_w: float = PAPER_INPUT_POWER_W) -> GearDesign:
    """Design of ratio ``ratio`` at ``alpha1_rad`` [rad] (default: the whole-degree optimum).

    Parameters
    ----------
    ratio : float
        Gear ratio i, a whole number >= 2.
    friction : Friction
        Friction coefficients [-].
    alpha1_rad : float, optional
        Driving-track lift angle [rad]; default the whole-degree optimum, as in the paper's table.
    satellites : dict, optional
        Satellite label -> diameter d_c [m]; default the paper's 15 mm ball and 10 mm roller.
    input_power_w : float
        Input power W1 for the link losses [W]; the paper's 1500 W by default.
    """
    i = check_ratio(ratio)
    best = optimum(i, friction)
    at = best.whole if alpha1_rad is None else losses(i, alpha1_rad, friction)
    chosen = SATELLITE_DIAMETER_M if satellites is None else satellites
    tracks = tuple(track_geometry(at.alpha1_rad, at.z2, d, name) for name, d in chosen.items())
    return GearDesign(friction, best, at, tracks, at.power(input_power_w))


def alpha1_label(design: GearDesign) -> str:
    """``"9 deg (optimum)"`` or ``"12 deg"``: the evaluated angle for reports."""
    text = f"{math.degrees(design.at.alpha1_rad):g} deg"
    return text + " (whole-degree optimum)" if design.at_optimum else text
