"""A root crack of any shape: a polyline from the root fillet into the ring, meshed with gmsh
(SI units).

The crack of ``meshing.crack.Crack`` runs straight (or with one kink); a crack grown step
by step (``fem.crack_growth``) is a polyline of any number of points.  ``PathCrack`` holds
it; ``path_ring_mesh`` meshes the ring with it through the same builder as
``ring_mesh`` (same groups, crack faces ``crack_a``/``crack_b``, node set ``crack_tip``),
so every FE quantity of the ring works on it.  The tip stays inside the body: a crack
that reaches a surface has severed the tooth or the rim and is not meshed.

``ray_exit`` finds where a ray from inside the ring leaves it, through the toothed inner
boundary (the crack cuts the tooth off) or through the outer surface (it cuts the rim).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .crack import Crack
from .fe_mesh import FEMesh
from .gear import GearGeometryError, rotation
from .ring_gear import RingGear
from .ring_mesh import (FILLET_POINTS, INVOLUTE_POINTS, MeshOptions, RingBuilder,
                        check_load_patch, run_builder, with_info)
from .session import gmsh_model

#: the two ways a root crack can sever the ring
FRACTURES = ("tooth", "rim")


@dataclass(frozen=True)
class PathCrack:
    """A root crack at tooth ``tooth`` along the polyline ``points`` [m] (mouth first).

    The mouth must be the tooth's critical fillet point (``Crack(tooth).mouth(ring)``),
    where the ring mesh splits the fillet.  Duck-types the parts of ``Crack`` the ring
    mesh builder reads (``tooth``, ``start``, ``depth``, ``is_through``).
    """

    tooth: int
    points: tuple

    start = "root"

    def __post_init__(self):
        pts = np.asarray(self.points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2 or not np.all(np.isfinite(pts)):
            raise GearGeometryError(f"crack path: {len(pts)} points of shape {pts.shape[1:]}; "
                                    "need >= 2 finite (x, y) points [m]")
        if np.any(np.hypot(*np.diff(pts, axis=0).T) <= 0):
            raise GearGeometryError("crack path: two consecutive points coincide")
        object.__setattr__(self, "points", tuple(map(tuple, pts.tolist())))

    @property
    def array(self) -> np.ndarray:
        return np.asarray(self.points)

    @property
    def depth(self) -> float:
        """Length along the path [m]."""
        return float(np.hypot(*np.diff(self.array, axis=0).T).sum())

    @property
    def tip(self) -> np.ndarray:
        return self.array[-1]

    @property
    def direction(self) -> np.ndarray:
        """Unit direction of the last segment (the crack's extension at the tip)."""
        d = self.array[-1] - self.array[-2]
        return d / np.hypot(*d)

    @property
    def last_segment(self) -> float:
        """Length of the last segment [m]."""
        return float(np.hypot(*(self.array[-1] - self.array[-2])))

    @property
    def is_kinked(self) -> bool:
        return len(self.points) > 2

    def is_through(self, ring) -> bool:
        """Never: a path crack's tip is inside the body."""
        return False

    def extended(self, point) -> "PathCrack":
        """This crack with one more point (the new tip) [m]."""
        return PathCrack(self.tooth, self.points + (tuple(float(v) for v in point),))


def initial_crack(ring: RingGear, tooth: int, depth: float) -> PathCrack:
    """The straight radial root crack of ``depth`` [m] at ``tooth`` (as ``meshing.crack``)."""
    return PathCrack(tooth, tuple(map(tuple, Crack(tooth, depth).path(ring).tolist())))


def path_ring_mesh(ring: RingGear, crack: PathCrack,
                   options: MeshOptions = MeshOptions()) -> FEMesh:
    """Mesh of the ring's cross-section with the crack ``crack`` (groups as ``ring_mesh``).

    Raises GearGeometryError if the mouth is not the critical fillet point of the tooth or
    a point of the path lies outside the ring (or within a tip size of its surface).
    """
    if not isinstance(ring, RingGear):
        raise GearGeometryError("crack: only ring gears (RingGear) take a crack")
    mouth = Crack(crack.tooth, 0.0).mouth(ring)
    path = crack.array
    if np.hypot(*(path[0] - mouth)) > 1e-9 * ring.outer_radius:
        raise GearGeometryError(f"crack path starts at {path[0].tolist()} m, not at the "
                                f"critical fillet point {mouth.tolist()} m of tooth {crack.tooth}")
    segments = boundary_segments(ring, crack.tooth)
    for point in path[1:]:
        gap = min(_distance_to_segments(point, segments),
                  ring.outer_radius - float(np.hypot(*point)))
        if gap <= options.tip_size:
            raise GearGeometryError(
                f"crack path point {point.tolist()} m is {gap:.3g} m from the ring's surface "
                f"(allowed > the tip size {options.tip_size:g} m, inside the body)")
    check_load_patch(ring, options)
    started = time.perf_counter()
    with gmsh_model("ring-path") as gmsh:
        mesh = run_builder(RingBuilder(gmsh, ring, crack, path, options),
                           f"the ring with a {len(path) - 1}-segment crack at tooth "
                           f"{crack.tooth}")
    return with_info(mesh, started, ring, options, None, path, crack_tooth=crack.tooth)


def tooth_outline(ring: RingGear, tooth: int) -> np.ndarray:
    """The toothed inner boundary of one tooth pitch [m], (n, 2): from the middle of the
    space before tooth ``tooth`` over its -psi root land, fillet and flank, tip, +psi
    flank, fillet and root land to the middle of the next space."""
    prof, gear = ring.profile, ring.gear
    flank = gear.flank(np.linspace(prof.tip_radius, prof.form_radius, 4 * INVOLUTE_POINTS))
    fillet = prof.fillet_points(np.linspace(1.0, 0.0, 2 * FILLET_POINTS))
    land_from = math.atan2(fillet[-1, 1], fillet[-1, 0])
    land = prof.root_radius * np.column_stack(
        [np.cos(a := np.linspace(land_from, prof.space_angle, 24)), np.sin(a)])
    positive = np.vstack([flank, fillet[1:], land[1:]])  # tip -> middle of the space
    negative = (positive * np.array([1.0, -1.0]))[::-1]
    tip_from = math.atan2(flank[0, 1], flank[0, 0])
    tip = prof.tip_radius * np.column_stack(
        [np.cos(b := np.linspace(-tip_from, tip_from, 16)), np.sin(b)])
    outline = np.vstack([negative, tip[1:-1], positive])
    return outline @ rotation(ring.tooth_angle(tooth)).T


def boundary_segments(ring: RingGear, tooth: int, reach: int = 1) -> np.ndarray:
    """Segments (m, 2, 2) [m] of the toothed boundary of teeth ``tooth - reach`` ..
    ``tooth + reach``."""
    parts = [tooth_outline(ring, (tooth + k) % ring.teeth) for k in range(-reach, reach + 1)]
    return np.concatenate([np.stack([p[:-1], p[1:]], axis=1) for p in parts])


def _distance_to_segments(point, segments) -> float:
    a, b = segments[:, 0], segments[:, 1]
    d = b - a
    t = np.clip(np.einsum("ij,ij->i", point - a, d) / np.einsum("ij,ij->i", d, d), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * d - point).T)))


@dataclass(frozen=True)
class Exit:
    """Where a ray from inside the ring leaves it.

    Attributes
    ----------
    distance : float
        Along the ray [m].
    point : ndarray
        [m]
    surface : str
        ``"tooth"`` (the toothed inner boundary: the crack would cut the tooth off) or
        ``"rim"`` (the outer surface: it would cut the rim).
    """

    distance: float
    point: np.ndarray
    surface: str


def ray_exit(ring: RingGear, tooth: int, origin, direction) -> Exit:
    """First crossing of the ring's surface by the ray ``origin + s direction``, s > 0."""
    origin = np.asarray(origin, dtype=float)
    d = np.asarray(direction, dtype=float)
    d = d / np.hypot(*d)
    b = float(origin @ d)
    c = float(origin @ origin) - ring.outer_radius ** 2
    outer = -b + math.sqrt(max(b * b - c, 0.0))
    segments = boundary_segments(ring, tooth)
    a, e = segments[:, 0], segments[:, 1] - segments[:, 0]
    cross = d[0] * e[:, 1] - d[1] * e[:, 0]
    ok = np.abs(cross) > 1e-30
    w = a - origin
    s = np.where(ok, (w[:, 0] * e[:, 1] - w[:, 1] * e[:, 0]) / np.where(ok, cross, 1), np.inf)
    t = np.where(ok, (w[:, 0] * d[1] - w[:, 1] * d[0]) / np.where(ok, cross, 1), -1)
    hits = ok & (s > 1e-12) & (t >= 0) & (t <= 1)
    inner = float(s[hits].min()) if np.any(hits) else math.inf
    if inner < outer:
        return Exit(inner, origin + inner * d, "tooth")
    return Exit(outer, origin + outer * d, "rim")


def surface_gap(ring: RingGear, tooth: int, point) -> float:
    """Distance [m] from ``point`` to the nearest surface of the ring (toothed boundary of
    the teeth around ``tooth`` or outer surface)."""
    point = np.asarray(point, dtype=float)
    return min(_distance_to_segments(point, boundary_segments(ring, tooth)),
               ring.outer_radius - float(np.hypot(*point)))


def tooth_height(ring: RingGear) -> float:
    """Whole depth of the ring's teeth, root radius minus tip radius [m]."""
    return ring.profile.root_radius - ring.profile.tip_radius


def backup_ratio(ring: RingGear) -> float:
    """Rim thickness below the root circle over the tooth height [-] (Lewicki & Ballarini
    1997, m_B)."""
    return ring.rim_thickness / tooth_height(ring)
