"""A zero-width crack in the ring gear: where it starts, which way it runs, how deep (SI).

A root crack starts at the critical fillet point of a tooth's +psi flank
(ISO 6336-3: where the fillet tangent makes 60 deg with the tooth axis of an
internal gear) and runs into the rim; a rim crack starts on the rim's outer
surface at the same polar angle and runs inwards.  ``angle`` turns the crack
away from the radial direction (positive counter-clockwise).  An optional kink
turns it by ``kink_angle`` after ``kink_fraction`` of the depth.  Depth is the
length along the path.  A root crack as deep as the rim is wide at its angle
(``Crack.through`` gives that depth) splits the rim.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .gear import GearGeometryError, rotation
from .ring_gear import RingGear

STARTS = ("root", "rim")
MAX_ANGLE = math.radians(60.0)
TIP_CLEARANCE = 1e-6  # [m] a crack tip this close to a boundary counts as touching it


@dataclass(frozen=True)
class Crack:
    """Crack parameters.

    Parameters
    ----------
    tooth : int
        Index of the tooth (0 .. z-1) at whose root the crack sits.
    depth : float
        Length along the path [m]; 0 means no crack.
    angle : float
        Direction of the first segment from the radial direction [rad], |angle| <= 60 deg.
    start : str
        ``"root"`` (tooth fillet, runs outwards) or ``"rim"`` (outer surface, runs inwards).
    kink_fraction : float
        Fraction of the depth before the kink, in (0, 1]; 1 means straight.
    kink_angle : float
        Change of direction at the kink [rad]; the second segment's direction
        from the radial must also stay within 60 deg.
    """

    tooth: int = 0
    depth: float = 0.0
    angle: float = 0.0
    start: str = "root"
    kink_fraction: float = 1.0
    kink_angle: float = 0.0

    def __post_init__(self):
        if self.start not in STARTS:
            raise GearGeometryError(f"crack.start = {self.start!r}, allowed: {', '.join(STARTS)}")
        if isinstance(self.tooth, bool) or not isinstance(self.tooth, int) or self.tooth < 0:
            raise GearGeometryError(f"crack.tooth = {self.tooth!r}, allowed integers >= 0")
        for name in ("depth", "angle", "kink_fraction", "kink_angle"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(
                    value):
                raise GearGeometryError(f"crack.{name} = {value!r} must be a finite number")
        if self.depth < 0:
            raise GearGeometryError(f"crack.depth = {self.depth!r} m, allowed >= 0")
        if not 0 < self.kink_fraction <= 1:
            raise GearGeometryError(f"crack.kink_fraction = {self.kink_fraction!r}, allowed (0, 1]")
        for name, value in (("angle", self.angle), ("angle + kink_angle",
                                                    self.angle + self.kink_angle)):
            if abs(value) > MAX_ANGLE:
                raise GearGeometryError(
                    f"crack.{name} = {math.degrees(value):.4g} deg, allowed -60..60 deg")

    @property
    def is_kinked(self) -> bool:
        return self.kink_fraction < 1 and self.kink_angle != 0

    def mouth(self, ring: RingGear) -> np.ndarray:
        """Point where the crack meets the surface it starts from [m]."""
        self._check_tooth(ring)
        point = ring.profile.critical_point()
        rot = rotation(ring.tooth_angle(self.tooth))
        if self.start == "root":
            return rot @ point
        angle = math.atan2(point[1], point[0]) + ring.tooth_angle(self.tooth)
        return ring.outer_radius * np.array([math.cos(angle), math.sin(angle)])

    def path(self, ring: RingGear) -> np.ndarray:
        """Polyline mouth -> (kink) -> tip [m], checked against the body.

        Raises GearGeometryError if the crack leaves the body; a root crack
        reaching the outer surface is snapped onto it (through-rim crack).
        """
        mouth = self.mouth(ring)
        through = self.through_depth(ring)
        if self.start == "root" and self.depth > through + TIP_CLEARANCE:
            raise GearGeometryError(
                f"crack.depth = {self.depth:.6g} m is deeper than the rim it cuts: allowed "
                f"0..{through:.6g} m (through-rim) for this direction")
        points = self._polyline(mouth, min(self.depth, through) if self.start == "root"
                                else self.depth)
        if self.start == "root" and self.depth >= through - TIP_CLEARANCE:
            tip = points[-1]
            points[-1] = tip / np.hypot(*tip) * ring.outer_radius
        if self.start == "rim":
            r_tip = float(np.hypot(*points[-1]))
            limit = self.rim_limit(ring)
            if self.depth > limit:
                raise GearGeometryError(
                    f"crack.depth = {self.depth:.6g} m runs out of the rim: a rim crack with "
                    f"this direction is allowed 0..{limit:.6g} m (tip radius {r_tip:.6g} m, "
                    f"root circle {ring.profile.root_radius:.6g} m)")
        return points

    def is_through(self, ring: RingGear) -> bool:
        return self.start == "root" and self.depth >= self.through_depth(ring) - TIP_CLEARANCE

    def through_depth(self, ring: RingGear) -> float:
        """Path length from a root crack's mouth to the outer surface [m]."""
        if self.start != "root":
            return math.inf
        mouth = self.mouth(ring)
        first, second = self._directions(mouth)
        reach = _ray_to_circle(mouth, first, ring.outer_radius)
        kink_at = self.kink_fraction * self.depth if self.is_kinked else math.inf
        if reach <= kink_at:
            return reach
        kink = mouth + kink_at * first
        return kink_at + _ray_to_circle(kink, second, ring.outer_radius)

    def rim_limit(self, ring: RingGear) -> float:
        """Deepest rim crack that keeps its tip TIP_CLEARANCE outside the root circle [m]."""
        r_min = ring.profile.root_radius + TIP_CLEARANCE
        low, high = 0.0, ring.rim_thickness / math.cos(MAX_ANGLE) * 2
        mouth = self.mouth(ring)
        for _ in range(200):
            mid = 0.5 * (low + high)
            if np.hypot(*self._polyline(mouth, mid)[-1]) > r_min:
                low = mid
            else:
                high = mid
        return low

    def _directions(self, mouth):
        inward = -1.0 if self.start == "rim" else 1.0
        radial = inward * mouth / np.hypot(*mouth)
        return rotation(self.angle) @ radial, rotation(self.angle + self.kink_angle) @ radial

    def _polyline(self, mouth, depth) -> np.ndarray:
        first, second = self._directions(mouth)
        if not self.is_kinked or depth <= self.kink_fraction * self.depth:
            return np.array([mouth, mouth + depth * first])
        kink = mouth + self.kink_fraction * self.depth * first
        return np.array([mouth, kink, kink + (depth - self.kink_fraction * self.depth) * second])

    def _check_tooth(self, ring: RingGear):
        if self.tooth >= ring.teeth:
            raise GearGeometryError(
                f"crack.tooth = {self.tooth}, but the ring has {ring.teeth} teeth: allowed "
                f"0..{ring.teeth - 1}")


def _ray_to_circle(origin, direction, radius) -> float:
    """Distance along a unit ray from a point inside a circle to the circle."""
    b = float(origin @ direction)
    c = float(origin @ origin) - radius ** 2
    return -b + math.sqrt(b * b - c)


FRONT_SHAPES = ("through", "semi_elliptic")
MIN_LIGAMENT = 0.5e-3  # [m] uncracked width kept between a part-width crack and a face


@dataclass(frozen=True)
class CrackFront:
    """How a crack runs across the face width (3D meshes only; z from one face).

    Parameters
    ----------
    shape : str
        ``"through"``: ``Crack.depth`` over the whole face width, the front a
        straight line.  ``"semi_elliptic"``: a part-width crack whose depth is
        ``Crack.depth * sqrt(1 - ((z - z_c) / half_length)^2)``, its front half
        an ellipse, its mouth ``2 half_length`` long on the surface it starts from.
    centre : float
        z_c, the deepest point, as a fraction of the face width, (0, 1).
    half_length : float
        Half the mouth length along the width [m] (semi-elliptic only).
    """

    shape: str = "through"
    centre: float = 0.5
    half_length: float = 5e-3

    def __post_init__(self):
        if self.shape not in FRONT_SHAPES:
            raise GearGeometryError(
                f"crack.front = {self.shape!r}, allowed: {', '.join(FRONT_SHAPES)}")
        for name in ("centre", "half_length"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(
                    value):
                raise GearGeometryError(f"crack.front_{name} = {value!r} must be a finite number")
        if not 0 < self.centre < 1:
            raise GearGeometryError(f"crack.front_centre = {self.centre!r}, allowed (0, 1)")
        if self.half_length <= 0:
            raise GearGeometryError(f"crack.front_half_length = {self.half_length!r} m, "
                                    "allowed > 0")

    def span(self, face_width: float) -> tuple[float, float]:
        """z range of a semi-elliptic crack's mouth [m], checked against the face width."""
        z_c = self.centre * face_width
        low, high = z_c - self.half_length, z_c + self.half_length
        if low < MIN_LIGAMENT or high > face_width - MIN_LIGAMENT:
            allowed = min(z_c, face_width - z_c) - MIN_LIGAMENT
            raise GearGeometryError(
                f"crack.front_half_length = {self.half_length:.6g} m does not fit in the face "
                f"width {face_width:.6g} m around z = {z_c:.6g} m: allowed 0..{allowed:.6g} m")
        return low, high

    def depth_at(self, crack: Crack, z, face_width: float) -> np.ndarray:
        """Crack depth at height z [m] (0 outside the mouth)."""
        z = np.asarray(z, dtype=float)
        if self.shape == "through":
            return np.full(z.shape, crack.depth)
        s = (z - self.centre * face_width) / self.half_length
        return crack.depth * np.sqrt(np.clip(1 - s * s, 0.0, None))
