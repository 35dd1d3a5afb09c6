"""External gear body (sun, planet) on its shaft, for tooth-stiffness meshes (SI units).

Tooth k is centred on the polar angle ``2 pi k / z``, as on the ring; the
loaded flank is the ``+psi`` one.  The body is held at its bore (a shaft
press fit: the whole bore by default, or K arcs).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from .gear import GearGeometryError, SpurGear
from .profile import ShaperCutter
from .ring_gear import STEEL_DENSITY, Supports, ToothedBody


@dataclass(frozen=True)
class GearBody(ToothedBody):
    """External spur gear with a bore.

    Parameters
    ----------
    gear : SpurGear
        The toothing; must be external.
    bore_diameter : float
        Diameter of the shaft seat [m], 0 < d < root diameter.
    supports : Supports
        Held arcs of the bore; ``count = 0`` (default) holds all of it.
    fillet, fillet_radius
        Root fillet: the trochoid cut by the ISO 53 rack, or a circular one.
    working_pressure_angle : float or None
        Sets the load radius ``r_b / cos(alpha_w)`` [rad].
    density : float
        [kg/m^3]
    """

    gear: SpurGear
    bore_diameter: float
    supports: Supports = field(default_factory=lambda: Supports(count=0))
    fillet: str = "trochoid"
    fillet_radius: float | None = None
    working_pressure_angle: float | None = None
    density: float = STEEL_DENSITY
    cutter: ShaperCutter = field(default=ShaperCutter(), repr=False)  # unused: racks cut externals

    def __post_init__(self):
        if self.gear.internal:
            raise GearGeometryError("gear must be external (internal=False) for a gear body")
        root = 2 * self.profile.root_radius
        if not (isinstance(self.bore_diameter, (int, float)) and math.isfinite(self.bore_diameter)
                and 0 < self.bore_diameter < root):
            raise GearGeometryError(
                f"bore_diameter = {self.bore_diameter!r} m, allowed 0..{root:.6g} m (the root "
                "diameter)")
        self._check_density()
        if not self.profile.form_radius < self.load_radius < self.profile.tip_radius:
            raise GearGeometryError(
                f"working_pressure_angle puts the load point at r = {self.load_radius:.6g} m, "
                f"outside the involute ({self.profile.form_radius:.6g}.."
                f"{self.profile.tip_radius:.6g} m)")

    @property
    def held_radius(self) -> float:
        """The bore, where the shaft holds the gear [m]."""
        return self.bore_diameter / 2

    def area(self) -> float:
        """Exact area of the cross-section [m^2]."""
        return self.teeth * self.tooth_space_area() - math.pi * self.held_radius ** 2
