"""The ring gear body: internal teeth, rim and the way the hub holds it (SI units).

Angles: tooth k is centred on the polar angle ``2 pi k / z``; its flank at
``+psi`` (counter-clockwise side) is the one the planets load.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from .gear import GearGeometryError, rotation, SpurGear
from .profile import ShaperCutter, ToothProfile

STEEL_DENSITY = 7850.0  # [kg/m^3]


@dataclass(frozen=True)
class Supports:
    """Where the hub holds the ring's outer surface.

    Parameters
    ----------
    count : int
        Number K of support arcs (spline teeth or bolt pads), equally spaced;
        0 means the whole outer surface is held.
    width : float
        Angular width of each arc [rad], 0 < width < 2 pi / K.
    first_angle : float
        Polar angle of the middle of arc 0 [rad].
    """

    count: int = 6
    width: float = math.radians(20.0)
    first_angle: float = 0.0

    def __post_init__(self):
        if isinstance(self.count, bool) or not isinstance(self.count, int) or not (
                0 <= self.count <= 360):
            raise GearGeometryError(f"supports.count = {self.count!r}, allowed integers 0..360")
        if self.count and not (0 < self.width < 2 * math.pi / self.count):
            raise GearGeometryError(
                f"supports.width = {math.degrees(self.width):.4g} deg, allowed (0, "
                f"{360 / self.count:.4g}) deg for {self.count} arcs")
        if not math.isfinite(self.first_angle):
            raise GearGeometryError(f"supports.first_angle = {self.first_angle!r} must be finite")

    def arcs(self) -> list[tuple[float, float]]:
        """(start, end) polar angles of each arc [rad], counter-clockwise."""
        return [(self.first_angle + 2 * math.pi * j / self.count - self.width / 2,
                 self.first_angle + 2 * math.pi * j / self.count + self.width / 2)
                for j in range(self.count)]


class ToothedBody:
    """What every meshed gear body shares: teeth, load points, exact measures.

    Subclasses are frozen dataclasses with ``gear``, ``fillet``, ``fillet_radius``,
    ``cutter``, ``working_pressure_angle`` and ``density``, and give ``area()``
    and ``held_radius`` (the circle their supports hold).
    """

    @functools.cached_property
    def profile(self) -> ToothProfile:
        return ToothProfile(self.gear, self.fillet, self.fillet_radius, self.cutter)

    @property
    def teeth(self) -> int:
        return self.gear.teeth

    @property
    def load_pressure_angle(self) -> float:
        return (self.gear.pressure_angle if self.working_pressure_angle is None
                else self.working_pressure_angle)

    @property
    def load_radius(self) -> float:
        """Working pitch radius, where the planets' mesh force is applied [m]."""
        return self.gear.base_diameter / 2 / math.cos(self.load_pressure_angle)

    def tooth_angle(self, k: int) -> float:
        """Polar angle of the centre line of tooth k [rad]."""
        return 2 * math.pi * k / self.teeth

    def load_point(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Point on tooth k's +psi flank at the load radius and the unit force direction there.

        The force of a planet on the ring acts along the line of action (the flank
        normal, tangent to the base circle), pushing into the tooth; its moment arm
        about the ring centre is the base radius exactly.
        """
        p = self.gear.flank([self.load_radius])[0]
        into_tooth = -self.gear.flank_normal(self.load_radius)
        rot = rotation(self.tooth_angle(k))
        return rot @ p, rot @ into_tooth

    # exact measures ----------------------------------------------------
    def tooth_space_area(self) -> float:
        """Area enclosed by the toothed inner boundary, per tooth pitch [m^2].

        Green's theorem, 1/2 int r^2 dpsi, on the exact pieces: tip arc and root
        land in closed form, the involute in closed form
        (``(r^2 - r_b^2)^{3/2} / (6 r_b)``), the fillet by adaptive quadrature
        (rtol 1e-13).  No mesh is involved.
        """
        from scipy.integrate import quad

        prof, g = self.profile, self.gear
        r_a, r_f, rb = prof.tip_radius, prof.root_radius, g.base_diameter / 2
        psi_tip = float(g.half_tooth_angle(r_a))
        tip_arc = 0.5 * r_a ** 2 * psi_tip
        involute = ((prof.form_radius ** 2 - rb ** 2) ** 1.5 - (r_a ** 2 - rb ** 2) ** 1.5) / (6 * rb)
        if not g.internal:  # psi grows towards the root on an external tooth
            involute = -involute

        def integrand(t):
            points, tangents = prof._fillet(t)
            (x, y), (dx, dy) = points[0], tangents[0]
            return -0.5 * (x * dy - y * dx)

        fillet = quad(integrand, 0.0, 1.0, epsabs=0, epsrel=1e-13, limit=200)[0]
        land = 0.5 * r_f ** 2 * (prof.space_angle - prof.root_land_angle)
        return 2 * (tip_arc + involute + fillet + land)

    def _check_density(self):
        if not (math.isfinite(self.density) and self.density > 0):
            raise GearGeometryError(f"density = {self.density!r}, but it must be > 0 [kg/m^3]")

    def mass(self) -> float:
        """Exact mass [kg] (area x face width x density)."""
        return self.area() * self.gear.face_width * self.density




@dataclass(frozen=True)
class RingGear(ToothedBody):
    """Internal spur gear with its rim.

    Parameters
    ----------
    gear : SpurGear
        The toothing; must be internal.
    outer_diameter : float
        Outer diameter of the rim [m], > root diameter.
    supports : Supports
    fillet, fillet_radius, cutter
        Root fillet and the shaper cutter that cuts it (and the root circle),
        see ``meshing.profile.ToothProfile``.
    working_pressure_angle : float or None
        Working pressure angle with the planets [rad]; sets the load radius
        ``r_b / cos(alpha_w)``.  Default: the reference pressure angle.
    density : float
        [kg/m^3]
    """

    gear: SpurGear
    outer_diameter: float
    supports: Supports = field(default_factory=Supports)
    fillet: str = "trochoid"
    fillet_radius: float | None = None
    cutter: ShaperCutter = ShaperCutter()
    working_pressure_angle: float | None = None
    density: float = STEEL_DENSITY

    def __post_init__(self):
        if not self.gear.internal:
            raise GearGeometryError("gear must be internal (internal=True) for a ring gear")
        if not (isinstance(self.outer_diameter, (int, float)) and math.isfinite(self.outer_diameter)
                and self.outer_diameter > 2 * self.profile.root_radius):
            raise GearGeometryError(
                f"outer_diameter = {self.outer_diameter!r} m, but it must exceed the root "
                f"diameter {2 * self.profile.root_radius:.6g} m (rim thickness > 0)")
        self._check_density()
        alpha = self.load_pressure_angle
        if not (math.radians(10) <= alpha <= math.radians(40)):
            raise GearGeometryError(
                f"working_pressure_angle = {math.degrees(alpha):.4g} deg, allowed 10..40 deg")
        if self.load_radius >= self.profile.form_radius:
            raise GearGeometryError(
                f"working_pressure_angle = {math.degrees(alpha):.4g} deg puts the load point at "
                f"r = {self.load_radius:.6g} m, beyond the involute (form radius "
                f"{self.profile.form_radius:.6g} m)")

    @property
    def outer_radius(self) -> float:
        return self.outer_diameter / 2

    @property
    def rim_thickness(self) -> float:
        """Outer radius minus root radius [m]."""
        return self.outer_radius - self.profile.root_radius

    @property
    def held_radius(self) -> float:
        """The rim's outer surface, where the supports hold the ring [m]."""
        return self.outer_radius

    def area(self) -> float:
        """Exact area of the ring's cross-section [m^2]."""
        return math.pi * self.outer_radius ** 2 - self.teeth * self.tooth_space_area()


def outer_diameter_for_mass(gear: SpurGear, mass: float, density: float = STEEL_DENSITY,
                            fillet: str = "trochoid",
                            cutter: ShaperCutter = ShaperCutter()) -> float:
    """Outer diameter [m] that gives the ring ``mass`` [kg] (exact geometry)."""
    probe = RingGear(gear, gear.root_diameter * 1.5, Supports(count=0), fillet, cutter=cutter,
                     density=density)
    inner = probe.teeth * probe.tooth_space_area()
    area = mass / (density * gear.face_width)
    outer_sq = (area + inner) / math.pi
    if outer_sq <= probe.profile.root_radius ** 2:
        raise GearGeometryError(
            f"mass = {mass} kg is less than the teeth alone weigh at face width "
            f"{gear.face_width} m")
    return 2 * math.sqrt(outer_sq)
