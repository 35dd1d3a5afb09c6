"""Linear elastic material (SI units)."""
from __future__ import annotations

import math
from dataclasses import dataclass


class MaterialError(ValueError):
    """Material constants outside their physical range; the message names the field."""


@dataclass(frozen=True)
class Material:
    """Isotropic linear elastic material.

    Parameters
    ----------
    E : float
        Young's modulus [Pa], > 0.
    nu : float
        Poisson's ratio [-], in (-1, 0.5).
    density : float
        [kg/m^3], > 0.
    """

    E: float = 210e9
    nu: float = 0.3
    density: float = 7850.0

    def __post_init__(self):
        for name, ok, allowed in (("E", lambda v: v > 0, "> 0 [Pa]"),
                                  ("nu", lambda v: -1 < v < 0.5, "in (-1, 0.5)"),
                                  ("density", lambda v: v > 0, "> 0 [kg/m^3]")):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                    math.isfinite(value) and ok(value)):
                raise MaterialError(f"material.{name} = {value!r}, allowed {allowed}")

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + nu)) [Pa]."""
        return self.E / (2 * (1 + self.nu))

    def lame(self, plane: str = "stress") -> tuple[float, float]:
        """(lambda, mu) [Pa]; for plane stress lambda* = 2 lambda mu / (lambda + 2 mu)."""
        mu = self.shear_modulus
        lam = self.E * self.nu / ((1 + self.nu) * (1 - 2 * self.nu))
        if plane == "stress":
            return 2 * lam * mu / (lam + 2 * mu), mu
        if plane == "strain":
            return lam, mu
        raise MaterialError(f"plane = {plane!r}, allowed 'stress' or 'strain'")


STEEL = Material()
