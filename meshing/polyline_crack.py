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

import time
from dataclasses import dataclass

import numpy as np

from hubvib.meshing.crack import Crack
from hubvib.meshing.crack_kinds import START_KINDS
from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.gear import GearGeometryError
from hubvib.meshing.ring_gear import RingGear
from hubvib.meshing.ring_mesh import MeshOptions, RingBuilder, check_load_patch, run_builder, with_info
from hubvib.meshing.ring_outline import (Exit, boundary_segments, distance_to_segments,  # noqa: F401
                           ray_exit, surface_gap, tooth_outline)  # (re-exported)
from hubvib.meshing.session import gmsh_model

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

    @property
    def kind(self):
        """The start kind (a root crack)."""
        return START_KINDS[self.start]

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

    def path(self, ring: RingGear, clearance: float = 0.0) -> np.ndarray:
        """The polyline [m] (n, 2), checked against ``ring`` (as ``Crack.path``): the mouth
        is the tooth's critical fillet point and every other point lies inside the body,
        more than ``clearance`` [m] from its surface (GearGeometryError otherwise)."""
        if not isinstance(ring, RingGear):
            raise GearGeometryError("crack: only ring gears (RingGear) take a crack")
        mouth = Crack(self.tooth, 0.0).mouth(ring)
        path = self.array
        if np.hypot(*(path[0] - mouth)) > 1e-9 * ring.outer_radius:
            raise GearGeometryError(f"crack path starts at {path[0].tolist()} m, not at the "
                                    f"critical fillet point {mouth.tolist()} m of tooth "
                                    f"{self.tooth}")
        segments = boundary_segments(ring, self.tooth)
        for point in path[1:]:
            gap = min(distance_to_segments(point, segments),
                      ring.outer_radius - float(np.hypot(*point)))
            if gap <= clearance:
                raise GearGeometryError(
                    f"crack path point {point.tolist()} m is {gap:.3g} m from the ring's "
                    f"surface (allowed > {clearance:g} m, inside the body)")
        return path

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
    path = crack.path(ring, options.tip_size)
    check_load_patch(ring, options)
    started = time.perf_counter()
    with gmsh_model("ring-path") as gmsh:
        mesh = run_builder(RingBuilder(gmsh, ring, crack, path, options),
                           f"the ring with a {len(path) - 1}-segment crack at tooth "
                           f"{crack.tooth}")
    return with_info(mesh, started, ring, options, None, path, crack_tooth=crack.tooth)


def tooth_height(ring: RingGear) -> float:
    """Whole depth of the ring's teeth, root radius minus tip radius [m]."""
    return ring.profile.root_radius - ring.profile.tip_radius


def backup_ratio(ring: RingGear) -> float:
    """Rim thickness below the root circle over the tooth height [-] (Lewicki & Ballarini
    1997, m_B)."""
    return ring.rim_thickness / tooth_height(ring)
