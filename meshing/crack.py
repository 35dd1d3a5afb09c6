"""A zero-width crack in the ring gear: where it starts, which way it runs, how deep (SI).

A root crack starts at the critical fillet point of a tooth's +psi flank
(ISO 6336-3: where the fillet tangent makes 60 deg with the tooth axis of an
internal gear) and runs into the rim; a rim crack starts on the rim's outer
surface at the same polar angle and runs inwards (``meshing.crack_kinds``: each
start kind owns its mouth, allowed directions, depth checks and meshing hook).
``angle`` turns the crack away from the radial direction (positive
counter-clockwise).  An optional kink turns it by ``kink_angle`` after
``kink_fraction`` of the depth.  Depth is the length along the path.  A root crack
as deep as the rim is wide at its angle (``Crack.through_depth`` gives that depth)
splits the rim.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .crack_kinds import (FRONTS, START_KINDS, TIP_CLEARANCE, CrackStart, FrontShape,
                          front_shape, start_kind)
from .gear import GearGeometryError, rotation
from .ring_gear import RingGear

STARTS = tuple(START_KINDS)
#: the widest turn from the radial any start kind allows [rad]
MAX_ANGLE = max(max(abs(a) for a in k.angle_range) for k in START_KINDS.values())

__all__ = ["Crack", "CrackFront", "STARTS", "FRONT_SHAPES", "MAX_ANGLE", "TIP_CLEARANCE",
           "MIN_LIGAMENT"]


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
        Direction of the first segment from the radial direction [rad]: -90..60 deg
        for a root crack, -60..60 deg for a rim crack (``crack_kinds``).
    start : str
        ``"root"`` (tooth fillet, runs outwards) or ``"rim"`` (outer surface, runs inwards).
    kink_fraction : float
        Fraction of the depth before the kink, in (0, 1]; 1 means straight.
    kink_angle : float
        Change of direction at the kink [rad]; the second segment's direction
        from the radial must also stay within the start kind's range.
    """

    tooth: int = 0
    depth: float = 0.0
    angle: float = 0.0
    start: str = "root"
    kink_fraction: float = 1.0
    kink_angle: float = 0.0

    def __post_init__(self):
        kind = start_kind(self.start)
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
        kind.check_angle("angle", self.angle)
        kind.check_angle("angle + kink_angle", self.angle + self.kink_angle)

    @property
    def kind(self) -> CrackStart:
        """The start kind (``crack_kinds.START_KINDS[start]``)."""
        return START_KINDS[self.start]

    @property
    def is_kinked(self) -> bool:
        return self.kink_fraction < 1 and self.kink_angle != 0

    def mouth(self, ring: RingGear) -> np.ndarray:
        """Point where the crack meets the surface it starts from [m]."""
        self._check_tooth(ring)
        return self.kind.mouth(ring, self.tooth)

    def path(self, ring: RingGear) -> np.ndarray:
        """Polyline mouth -> (kink) -> tip [m], checked against the body.

        Raises GearGeometryError if the crack leaves the body; a root crack
        reaching the outer surface is snapped onto it (through-rim crack).
        """
        return self.kind.checked_path(self, ring)

    def is_through(self, ring: RingGear) -> bool:
        return self.kind.is_through(self, ring)

    def through_depth(self, ring: RingGear) -> float:
        """Path length from a root crack's mouth to the outer surface [m]."""
        return self.kind.through_depth(self, ring)

    def rim_limit(self, ring: RingGear) -> float:
        """Deepest rim crack that keeps its tip TIP_CLEARANCE outside the root circle [m]."""
        return self.kind.rim_limit(self, ring)

    def directions(self, mouth):
        """Unit directions of the first and second segment."""
        radial = self.kind.inward * mouth / np.hypot(*mouth)
        return rotation(self.angle) @ radial, rotation(self.angle + self.kink_angle) @ radial

    def polyline(self, mouth, depth) -> np.ndarray:
        """The path from ``mouth`` to length ``depth`` [m] (unchecked)."""
        first, second = self.directions(mouth)
        if not self.is_kinked or depth <= self.kink_fraction * self.depth:
            return np.array([mouth, mouth + depth * first])
        kink = mouth + self.kink_fraction * self.depth * first
        return np.array([mouth, kink, kink + (depth - self.kink_fraction * self.depth) * second])

    def polyline_points(self, mouth, lengths) -> np.ndarray:
        """Points at path lengths ``lengths`` [m] from ``mouth`` (n, 2) (unchecked)."""
        return np.array([self.polyline(mouth, s)[-1] for s in np.asarray(lengths, float)])

    def _check_tooth(self, ring: RingGear):
        if self.tooth >= ring.teeth:
            raise GearGeometryError(
                f"crack.tooth = {self.tooth}, but the ring has {ring.teeth} teeth: allowed "
                f"0..{ring.teeth - 1}")


FRONT_SHAPES = tuple(FRONTS)
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
        an ellipse, its mouth ``2 half_length`` long on the surface it starts from
        (``crack_kinds``: each shape owns its depth profile and checks).
    centre : float
        z_c, the deepest point, as a fraction of the face width, (0, 1).
    half_length : float
        Half the mouth length along the width [m] (semi-elliptic only).
    """

    shape: str = "through"
    centre: float = 0.5
    half_length: float = 5e-3

    def __post_init__(self):
        front_shape(self.shape)
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

    @property
    def kind(self) -> FrontShape:
        """The front shape (``crack_kinds.FRONTS[shape]``)."""
        return FRONTS[self.shape]

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

    def check(self, crack: Crack, ring: RingGear) -> None:
        """Refuse a crack this front cannot carry (GearGeometryError)."""
        self.kind.check(self, crack, ring)

    def depth_at(self, crack: Crack, z, face_width: float) -> np.ndarray:
        """Crack depth at height z [m] (0 outside the mouth)."""
        return self.kind.depth_at(self, crack, z, face_width)
