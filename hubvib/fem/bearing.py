"""Radial stiffness of a roller bearing, Palmgren line contact (SI units).

Each roller in line contact deflects (both raceways together)
``delta = 3.84e-5 Q^0.9 / l^0.8`` [mm] for a roller load Q [N] and effective
length l [mm] (Palmgren 1959; Harris & Kotzalas, Rolling Bearing Analysis,
5th ed., vol. 2, eq. 7.6 in SI form below).  With zero clearance and a
radial load F the rings approach by delta_r; roller j at angle psi_j from the
load carries ``Q_j = K (delta_r cos psi_j)^(10/9)`` when cos psi_j > 0, and
F = sum Q_j cos psi_j is solved for delta_r (the ring and housing are rigid).

The stiffness depends on the load: ``secant = F / delta_r`` and, since F is
homogeneous of degree 10/9 in delta_r, ``tangent = dF/d delta_r = secant / 0.9``.
Both are averaged over the roller positions (the cage turns).  The tangent
stiffness is the one for small vibrations about the operating load.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

EXPONENT = 0.9
PALMGREN = 3.84e-5  # [mm N^-0.9 mm^0.8]
POSITIONS = 32  # cage positions over one roller pitch


class BearingError(ValueError):
    """Bearing data outside the allowed range; the message names the field."""


@dataclass(frozen=True)
class RollerBearing:
    """Radial roller (or needle) bearing, zero clearance.

    Parameters
    ----------
    rollers : int
        Rollers per row Z, >= 3.
    roller_length : float
        Effective contact length l per roller [m] (all rows together).
    """

    rollers: int
    roller_length: float

    def __post_init__(self):
        if isinstance(self.rollers, bool) or not isinstance(self.rollers, int) or self.rollers < 3:
            raise BearingError(f"bearing.rollers = {self.rollers!r}, allowed integers >= 3")
        if not (isinstance(self.roller_length, (int, float)) and math.isfinite(self.roller_length)
                and 1e-4 <= self.roller_length <= 1.0):
            raise BearingError(f"bearing.roller_length = {self.roller_length!r} m, allowed "
                               "1e-4..1 m")

    def roller_deflection(self, load) -> np.ndarray:
        """Contact deflection of one roller [m] under ``load`` [N] (Palmgren)."""
        l_mm = self.roller_length * 1e3
        return PALMGREN * np.asarray(load, dtype=float) ** EXPONENT / l_mm ** 0.8 * 1e-3

    def _force_per_deflection(self, phase: float) -> float:
        """F / delta_r^(10/9) for the cage at ``phase`` [rad] (roller 0 at psi = phase)."""
        psi = phase + 2 * math.pi * np.arange(self.rollers) / self.rollers
        c = np.cos(psi)
        c = c[c > 0]
        stiffness = 1.0 / float(self.roller_deflection(1.0)) ** (1 / EXPONENT)  # Q = k delta^(10/9)
        return stiffness * float(np.sum(c ** (1 / EXPONENT) * c))

    def deflection(self, load: float) -> float:
        """Radial approach of the rings under a radial ``load`` [N], cage-averaged [m]."""
        self._check_load(load)
        phases = 2 * math.pi / self.rollers * np.arange(POSITIONS) / POSITIONS
        return float(np.mean([(load / self._force_per_deflection(p)) ** EXPONENT
                              for p in phases]))

    def stiffness(self, load: float) -> tuple[float, float]:
        """(tangent, secant) radial stiffness at the radial ``load`` [N/m], cage-averaged."""
        secant = load / self.deflection(load)
        return secant / EXPONENT, secant

    @staticmethod
    def _check_load(load):
        if not (isinstance(load, (int, float)) and math.isfinite(load) and load > 0):
            raise BearingError(f"bearing load = {load!r} N, allowed > 0 (an unloaded line "
                               "contact has zero stiffness)")
