"""Where a crack starts and how its front runs across the face width: small classes, one
per kind, registered by the name scene files and JSON use (SI units).

A start kind (``RootStart``, ``RimStart``) owns the crack's mouth and direction (its
profile in the cross-section), the checks of its angle and depth against the ring, and
the hook the ring mesh builder calls (does the crack split the tooth's fillet, where does
it meet the outer surface).  A front shape (``ThroughFront``, ``SemiEllipticFront``)
owns the depth over the face width and its check against the 3D crack.  Strings map to
them only at the edge: ``start_kind("root")``, ``front_shape("semi_elliptic")``.  A new
kind is one class and one ``register_start`` / ``register_front`` call.
"""
from __future__ import annotations

import math

import numpy as np

from .gear import GearGeometryError, rotation
from .profile import ISO_TANGENT_INTERNAL
from .ring_gear import RingGear
from .ring_outline import tooth_outline

TIP_CLEARANCE = 1e-6  # [m] a crack tip this close to a boundary counts as touching it
#: [m] a root crack must keep this far from the toothed surface it does not start on
TOOTH_GAP = 0.5e-3
#: [m] spacing of the points at which a root crack's gap to the toothed surface is checked
GAP_SAMPLING = 0.05e-3


def _ray_to_circle(origin, direction, radius) -> float:
    """Distance along a unit ray from a point inside a circle to the circle."""
    b = float(origin @ direction)
    c = float(origin @ origin) - radius ** 2
    return -b + math.sqrt(b * b - c)


class CrackStart:
    """A surface a crack starts from (one instance per kind, see ``START_KINDS``).

    Attributes
    ----------
    name : str
        The scene/JSON value (``[crack] start``).
    inward : float
        +1 if the crack runs outwards (from the teeth into the rim), -1 inwards.
    angle_range : tuple of float
        Allowed direction of every segment from the radial [rad], (low, high).
    splits_fillet : bool
        Meshing hook: the ring builder splits the cracked tooth's +psi fillet at the
        mouth (the crack starts there) instead of starting it on the outer surface.
    """

    name = ""
    inward = 1.0
    angle_range = (-math.radians(60.0), math.radians(60.0))
    splits_fillet = False

    def mouth(self, ring: RingGear, tooth: int) -> np.ndarray:
        raise NotImplementedError

    def check_angle(self, name: str, value: float) -> None:
        """Refuse a direction [rad] outside ``angle_range``; ``name`` is the crack's key."""
        low, high = self.angle_range
        if not low - 1e-12 <= value <= high + 1e-12:
            raise GearGeometryError(
                f"crack.{name} = {math.degrees(value):.4g} deg, allowed "
                f"{math.degrees(low):.4g}..{math.degrees(high):.4g} deg for a {self.name} "
                f"crack{self.angle_reason}")

    angle_reason = ""

    def through_depth(self, crack, ring: RingGear) -> float:
        """Path length to the outer surface [m] (inf: this kind never goes through)."""
        return math.inf

    def is_through(self, crack, ring: RingGear) -> bool:
        return False

    def checked_path(self, crack, ring: RingGear) -> np.ndarray:
        raise NotImplementedError

    def outer_end(self, crack, ring: RingGear, path: np.ndarray):
        """Meshing hook: the crack's point on the outer surface [m], or None."""
        return None


class RootStart(CrackStart):
    """A crack from the critical fillet point of the tooth's +psi flank (ISO 6336-3, where
    the fillet tangent makes 60 deg with the tooth axis of an internal gear), running
    into the rim.  Clockwise it may turn down to -90 deg (along the root circle, under
    its own tooth); counter-clockwise only up to the fillet tangent, +60 deg: beyond it
    points into the tooth space.  It must keep ``TOOTH_GAP`` from the toothed surface
    (a crack that reaches it has cut the tooth off); one as deep as ``through_depth``
    splits the rim."""

    name = "root"
    inward = 1.0
    angle_range = (-math.radians(90.0), ISO_TANGENT_INTERNAL)
    angle_reason = " (beyond +60 deg it points out of the fillet into the tooth space)"
    splits_fillet = True

    def mouth(self, ring, tooth):
        return rotation(ring.tooth_angle(tooth)) @ ring.profile.critical_point()

    def through_depth(self, crack, ring):
        mouth = crack.mouth(ring)
        first, second = crack.directions(mouth)
        reach = _ray_to_circle(mouth, first, ring.outer_radius)
        kink_at = crack.kink_fraction * crack.depth if crack.is_kinked else math.inf
        if reach <= kink_at:
            return reach
        kink = mouth + kink_at * first
        return kink_at + _ray_to_circle(kink, second, ring.outer_radius)

    def is_through(self, crack, ring):
        return crack.depth >= self.through_depth(crack, ring) - TIP_CLEARANCE

    def tooth_reach(self, crack, ring) -> float:
        """Path length [m] at which the crack comes within ``TOOTH_GAP`` of the toothed
        surface (other than the +psi side of its own tooth, where it starts), inf if it
        reaches the outer surface first."""
        through = self.through_depth(crack, ring)
        s = np.arange(GAP_SAMPLING, through + GAP_SAMPLING, GAP_SAMPLING)
        s = np.minimum(s, through)
        points = crack.polyline_points(crack.mouth(ring), s)
        gaps = _gaps(points, _far_segments(ring, crack.tooth))
        close = np.nonzero(gaps < TOOTH_GAP)[0]
        return math.inf if len(close) == 0 else float(s[close[0]] - GAP_SAMPLING)

    def checked_path(self, crack, ring):
        through = self.through_depth(crack, ring)
        if crack.depth > through + TIP_CLEARANCE:
            raise GearGeometryError(
                f"crack.depth = {crack.depth:.6g} m is deeper than the rim it cuts: allowed "
                f"0..{through:.6g} m (through-rim) for this direction")
        if crack.angle < -math.radians(60.0) - 1e-12 or (
                crack.angle + crack.kink_angle) < -math.radians(60.0) - 1e-12:
            reach = self.tooth_reach(crack, ring)
            if crack.depth > reach:
                raise GearGeometryError(
                    f"crack.depth = {crack.depth:.6g} m at crack.angle = "
                    f"{math.degrees(crack.angle):.4g} deg comes within {1e3 * TOOTH_GAP:g} mm "
                    f"of the tooth surface (the tooth would break off): allowed "
                    f"0..{reach:.6g} m for this direction")
        points = crack.polyline(crack.mouth(ring), min(crack.depth, through))
        if crack.depth >= through - TIP_CLEARANCE:
            tip = points[-1]
            points[-1] = tip / np.hypot(*tip) * ring.outer_radius
        return points

    def outer_end(self, crack, ring, path):
        return path[-1] if crack.is_through(ring) else None


class RimStart(CrackStart):
    """A crack from the rim's outer surface at the polar angle of the tooth's critical
    fillet point, running inwards; its tip stays ``TIP_CLEARANCE`` outside the root
    circle."""

    name = "rim"
    inward = -1.0
    angle_range = (-math.radians(60.0), math.radians(60.0))
    splits_fillet = False

    def mouth(self, ring, tooth):
        point = ring.profile.critical_point()
        angle = math.atan2(point[1], point[0]) + ring.tooth_angle(tooth)
        return ring.outer_radius * np.array([math.cos(angle), math.sin(angle)])

    def rim_limit(self, crack, ring) -> float:
        """Deepest rim crack that keeps its tip TIP_CLEARANCE outside the root circle [m]."""
        r_min = ring.profile.root_radius + TIP_CLEARANCE
        low, high = 0.0, ring.rim_thickness / math.cos(self.angle_range[1]) * 2
        mouth = crack.mouth(ring)
        for _ in range(200):
            mid = 0.5 * (low + high)
            if np.hypot(*crack.polyline(mouth, mid)[-1]) > r_min:
                low = mid
            else:
                high = mid
        return low

    def checked_path(self, crack, ring):
        points = crack.polyline(crack.mouth(ring), crack.depth)
        r_tip = float(np.hypot(*points[-1]))
        limit = self.rim_limit(crack, ring)
        if crack.depth > limit:
            raise GearGeometryError(
                f"crack.depth = {crack.depth:.6g} m runs out of the rim: a rim crack with "
                f"this direction is allowed 0..{limit:.6g} m (tip radius {r_tip:.6g} m, "
                f"root circle {ring.profile.root_radius:.6g} m)")
        return points

    def outer_end(self, crack, ring, path):
        return path[0]


def _far_segments(ring: RingGear, tooth: int) -> np.ndarray:
    """The toothed boundary around ``tooth`` without the +psi side (flank, fillet, land)
    of ``tooth`` itself, where a root crack starts: (m, 2, 2) [m]."""
    own = tooth_outline(ring, tooth)
    half = len(own) // 2
    kept = own[:half + 1]
    parts = [kept] + [tooth_outline(ring, (tooth + k) % ring.teeth) for k in (-1, 1)]
    return np.concatenate([np.stack([p[:-1], p[1:]], axis=1) for p in parts])


def _gaps(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """Distance [m] from each of ``points`` (n, 2) to the nearest of ``segments``."""
    a, d = segments[:, 0], segments[:, 1] - segments[:, 0]
    dd = np.einsum("ij,ij->i", d, d)
    out = np.empty(len(points))
    for start in range(0, len(points), 256):
        p = points[start:start + 256, None, :]
        t = np.clip(np.einsum("nij,ij->ni", p - a, d) / dd, 0, 1)
        out[start:start + 256] = np.min(np.hypot(*(a + t[..., None] * d - p).transpose(2, 0, 1)),
                                        axis=1)
    return out


#: the start kinds by their scene/JSON name
START_KINDS: dict[str, CrackStart] = {}


def register_start(kind: CrackStart) -> CrackStart:
    START_KINDS[kind.name] = kind
    return kind


def start_kind(name: str) -> CrackStart:
    """The start kind called ``name``; GearGeometryError lists the allowed names."""
    try:
        return START_KINDS[name]
    except (KeyError, TypeError):
        raise GearGeometryError(f"crack.start = {name!r}, allowed: {', '.join(START_KINDS)}"
                                ) from None


register_start(RootStart())
register_start(RimStart())


class FrontShape:
    """How a crack runs across the face width (3D meshes only).

    Attributes
    ----------
    name : str
        The scene/JSON value.
    part_width : bool
        Meshing hook: the solid builder imprints a part-width crack surface instead of
        sweeping the plane crack over the width.
    """

    name = ""
    part_width = False

    def depth_at(self, front, crack, z, face_width: float) -> np.ndarray:
        raise NotImplementedError

    def check(self, front, crack, ring: RingGear) -> None:
        """Refuse a crack this front cannot carry (GearGeometryError)."""


class ThroughFront(FrontShape):
    """``Crack.depth`` over the whole face width, the front a straight line."""

    name = "through"

    def depth_at(self, front, crack, z, face_width):
        return np.full(np.shape(z), crack.depth)


class SemiEllipticFront(FrontShape):
    """A part-width crack of depth ``Crack.depth * sqrt(1 - ((z - z_c) / half_length)^2)``,
    its front half an ellipse, its mouth ``2 half_length`` long; the crack must be
    straight and stay inside the rim."""

    name = "semi_elliptic"
    part_width = True

    def depth_at(self, front, crack, z, face_width):
        s = (np.asarray(z, dtype=float) - front.centre * face_width) / front.half_length
        return crack.depth * np.sqrt(np.clip(1 - s * s, 0.0, None))

    def check(self, front, crack, ring):
        front.span(ring.gear.face_width)
        if crack.is_through(ring) or crack.is_kinked:
            raise GearGeometryError(
                "crack.front = 'semi_elliptic' needs a straight crack that stays inside the rim: "
                f"allowed crack.depth 0..{crack.through_depth(ring):.6g} m and kink_fraction = 1")


#: the front shapes by their scene/JSON name
FRONTS: dict[str, FrontShape] = {}


def register_front(shape: FrontShape) -> FrontShape:
    FRONTS[shape.name] = shape
    return shape


def front_shape(name: str) -> FrontShape:
    """The front shape called ``name``; GearGeometryError lists the allowed names."""
    try:
        return FRONTS[name]
    except (KeyError, TypeError):
        raise GearGeometryError(f"crack.front = {name!r}, allowed: {', '.join(FRONTS)}"
                                ) from None


register_front(ThroughFront())
register_front(SemiEllipticFront())
