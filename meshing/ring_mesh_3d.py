"""Solid (3D) gmsh mesh of the ring gear: the cross-section extruded over the face width.

The crack is a zero-width surface (duplicated nodes), either through the whole
width (the plane crack extruded) or a part-width semi-elliptic surface crack
whose front is half an ellipse (``CrackFront``).  The front's nodes are shared
by both faces, also where it meets the free surface.

Named groups (``FEMesh.boundaries``, triangles): every group of the plane mesh
(``support_j``, ``supports``, ``outer_free``, ``tooth{k}_flank_pos/neg``,
``tooth{k}_root``, ``tooth{k}_load``) as the surfaces swept by its curves, plus
``face_0`` (z = 0) and ``face_1`` (z = face width), and ``crack_a`` / ``crack_b``.
Node sets: ``crack_front``, ``crack_mouth``.  z runs along the axis, from 0 to
the face width [m].

``half_width``: only z from 0 to half the face width, the mid-plane z = b/2 the group
``mid_plane`` (no ``face_1``), and a crack centred on the width cut there (a quarter
ellipse, or the through crack's half).  A body, supports and loads that are all
mirror-symmetric about the mid-plane have the mirror-symmetric solution, so this half
with u_z = 0 on ``mid_plane`` solves the whole (``fem.solid``, docs/crack_growth_3d.md).
``FEMesh.info["mirror_z"]`` is then the mid-plane's z [m] (None for the whole width).
"""
from __future__ import annotations

import ctypes
import ctypes.util
import functools
import time
from dataclasses import asdict

import numpy as np

from .crack import Crack, CrackFront
from .fe_mesh import TETRA10_EDGES, FEMesh
from .extract import extract
from .ring_gear import RingGear
from .ring_mesh import MeshOptions, check_load_patch, RingBuilder, run_builder, with_info
from .session import MeshingError, gmsh_model, split_crack

#: Default sizes for solid meshes (the plane defaults would need ~50x the elements in 3D).
SOLID_OPTIONS = MeshOptions(size=6e-3, tooth_size=2e-3, tip_size=0.5e-3, load_size=1e-3,
                            load_patch=2e-3, grading=0.3, order=2)
_EPS = 1e-6  # [m] bounding-box tolerance for finding entities (OCC pads boxes by 1e-7)


def ring_mesh_3d(ring: RingGear, crack: Crack | None = None, front: CrackFront = CrackFront(),
                 options: MeshOptions = SOLID_OPTIONS, half_width: bool = False) -> FEMesh:
    """Mesh the ring as a solid (tetrahedra), intact or with a crack.

    A crack of zero depth (or ``None``) gives the intact mesh.  A part-width
    crack may not cut through the rim and must be straight.  ``half_width``: the half
    z <= b/2 only (see the module's doc); a part-width crack must then be centred.
    """
    if crack is not None and crack.depth == 0:
        crack = None
    path = crack.path(ring) if crack is not None else None
    width = ring.gear.face_width
    if crack is not None:
        front.check(crack, ring)
        if half_width and front.kind.part_width and front.centre != 0.5:
            raise ValueError(f"half_width: the crack front's centre is {front.centre!r}; a "
                             "half-width mesh needs the crack centred on the width (0.5)")
    check_load_patch(ring, options)
    started = time.perf_counter()
    try:
        with gmsh_model("ring3d") as gmsh:
            mesh = run_builder(_SolidBuilder(gmsh, ring, crack, path, options, front,
                                             half_width),
                               f"the solid ring (options={options}, crack={crack}, "
                               f"front={front}, half_width={half_width})")
    finally:
        release_freed_heap()
    height = width / 2 if half_width else width
    return with_info(mesh, started, ring, options, crack, path,
                     front=None if crack is None else asdict(front),
                     exact_volume=ring.area() * height, mirror_z=height if half_width else None)


def release_freed_heap() -> None:
    """Hand the heap memory gmsh freed back to the operating system (glibc's
    ``malloc_trim``; elsewhere nothing).  gmsh frees its model in many small pieces that
    glibc keeps resident (a large part of a GB after the default solid mesh), which the
    factorisation that follows then stacked its own peak on (``hubvib stiffness --solid``)."""
    trim = _malloc_trim()
    if trim is not None:
        trim(0)


@functools.cache
def _malloc_trim():
    """glibc's ``malloc_trim``, or None where the C library has none."""
    try:
        return ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6").malloc_trim
    except (OSError, AttributeError):
        return None


class _SolidBuilder(RingBuilder):
    def __init__(self, gmsh, ring, crack, path, options, front, half_width=False):
        super().__init__(gmsh, ring, crack, path, options)
        self.half_width = half_width
        # z of the top face [m]: the face width, or the mid-plane of a half-width mesh
        self.height = ring.gear.face_width / (2 if half_width else 1)
        self.geo = gmsh.model.occ  # its extrusion is topological: much faster than geo's
        self.front = front
        self.part_width = crack is not None and front.kind.part_width
        self.crack_surfaces: list[int] = []
        self.straightened = 0
        self.open_curves: list[int] = []
        self.front_corners: list[np.ndarray] = []   # where the front meets a free surface
        self.front_curves: list[int] = []

    # geometry ----------------------------------------------------------
    def find(self, dim, low, high) -> list[int]:
        box = [c - _EPS for c in low] + [c + _EPS for c in high]
        return [t for _, t in self.gmsh.model.getEntitiesInBoundingBox(*box, dim=dim)]

    def geometry(self):
        width = self.height
        self.section(crack_lines=self.crack is not None and not self.part_width)
        if self.crack is not None and not self.crack.kind.splits_fillet:
            self.crack_points["mouth"] = self.crack_points["outer_end"]
        self.geo.synchronize()
        model = self.gmsh.model
        section_curves = [abs(t) for _, t in model.getBoundary([(2, self.surface)],
                                                               oriented=False)]
        centroids = np.array([self.geo.getCenterOfMass(1, c)[:2] for c in section_curves])
        out = self.geo.extrude([(2, self.surface)], 0, 0, width)
        self.volume = out[1][1]
        if self.crack is not None and self.part_width:
            self.part_width_crack()  # synchronised at its end
        else:  # each synchronisation of the whole ring is costly
            self.geo.synchronize()
        swept = {c: [] for c in section_curves}
        faces = {}
        for _, surface in model.getEntities(2):
            z0, z1 = model.getBoundingBox(2, surface)[2::3]
            if surface in self.crack_surfaces:
                continue
            if z1 < 1e-5 or z0 > width - 1e-5:
                faces[int(z0 > width / 2)] = surface
                continue
            centre = self.geo.getCenterOfMass(2, surface)
            distance = np.hypot(*(centroids - centre[:2]).T)
            nearest = int(np.argmin(distance))
            if distance[nearest] > 1e-9 or abs(centre[2] - width / 2) > 1e-9:
                raise MeshingError(f"side surface {surface} matches no curve of the section")
            swept[section_curves[nearest]].append(surface)
        self.groups = {name: [s for c in curves for s in swept[c]]
                       for name, curves in self.groups.items()}
        self.surface, self.top = faces[0], faces[1]
        self.groups["face_0"] = [self.surface]
        self.groups["mid_plane" if self.half_width else "face_1"] = [self.top]
        if self.crack is not None and not self.part_width:
            self.through_crack(width)
            self.geo.synchronize()
            model.mesh.embed(2, self.crack_surfaces, 3, self.volume)

    def vertical_line(self, xy, z0, z1) -> int:
        found = self.find(1, (xy[0], xy[1], z0), (xy[0], xy[1], z1))
        if len(found) != 1:
            raise MeshingError(f"expected one vertical edge at {xy}, found {found}")
        return found[0]

    def point_at(self, xy, z) -> int:
        found = self.find(0, (xy[0], xy[1], z), (xy[0], xy[1], z))
        if len(found) != 1:
            raise MeshingError(f"expected one point at {xy}, z = {z}, found {found}")
        return found[0]

    def through_crack(self, width):
        """The plane crack swept over the whole width: a ruled surface per path segment."""
        geo, model = self.geo, self.gmsh.model
        path = self.path
        on_surface = {0} | ({len(path) - 1} if self.crack.is_through(self.ring) else set())
        tops, verticals = [], []
        for i, p in enumerate(path):
            if i in on_surface:  # swept already as an edge of the side surfaces
                tops.append(self.point_at(p, width))
                verticals.append(self.vertical_line(p, 0.0, width))
            else:
                size = self.opt.tip_size if i == len(path) - 1 else self.opt.tooth_size
                tops.append(geo.addPoint(p[0], p[1], width, size))
                verticals.append(geo.addLine(self.crack_tags[i], tops[-1]))
        top_lines = [geo.addLine(a, b) for a, b in zip(tops[:-1], tops[1:])]
        for i, (bottom_line, top_line) in enumerate(zip(self.crack_lines, top_lines)):
            loop = geo.addCurveLoop([bottom_line, verticals[i + 1], -top_line, -verticals[i]])
            self.crack_surfaces.append(geo.addPlaneSurface([loop]))
        geo.synchronize()
        model.mesh.embed(1, self.crack_lines, 2, self.surface)
        model.mesh.embed(1, top_lines, 2, self.top)
        self.open_curves = self.crack_lines + top_lines + [verticals[i] for i in on_surface]
        if not self.crack.is_through(self.ring):
            self.front_curves = [verticals[-1]]
            self.front_corners = [np.array([*path[-1], z]) for z in (0.0, width)]

    def part_width_crack(self):
        """Semi-elliptic surface crack: mouth edge plus two quarter ellipses, imprinted by OCC.

        ``fragment`` splits the swept mouth edge at the crack's ends and embeds the
        crack face in the volume (it may renumber the side surfaces).  In a half-width
        mesh the crack ends on the mid-plane: mouth edge, one quarter ellipse and the
        crack's line on the mid-plane, which opens like the mouth.
        """
        geo, model = self.geo, self.gmsh.model
        z_low, z_high = self.front.span(self.ring.gear.face_width)
        z_c = 0.5 * (z_low + z_high)
        mouth, tip = self.path[0], self.path[-1]
        low = geo.addPoint(mouth[0], mouth[1], z_low, self.opt.tip_size)
        centre = geo.addPoint(mouth[0], mouth[1], z_c, self.opt.tip_size)
        deepest = geo.addPoint(tip[0], tip[1], z_c, self.opt.tip_size)
        major = low if self.front.half_length >= self.crack.depth else deepest
        first = geo.addEllipseArc(low, centre, major, deepest)
        if self.half_width:
            loop = [geo.addLine(low, centre), geo.addLine(centre, deepest), -first]
        else:
            high = geo.addPoint(mouth[0], mouth[1], z_high, self.opt.tip_size)
            second = geo.addEllipseArc(deepest, centre, major, high)
            loop = [geo.addLine(low, high), -second, -first]
        face = geo.addPlaneSurface([geo.addCurveLoop(loop)])
        _, pieces = geo.fragment([(3, self.volume)], [(2, face)])
        if not self.half_width:
            geo.remove([(0, centre)])
        geo.synchronize()
        self.volume = pieces[0][0][1]
        self.crack_surfaces = [t for d, t in pieces[1] if d == 2]
        z_top = z_c if self.half_width else z_high
        self.open_curves = [self.vertical_line(mouth, z_low, z_top)]
        edges = {abs(t) for _, t in model.getBoundary([(2, s) for s in self.crack_surfaces],
                                                      oriented=False)}
        if self.half_width:  # the crack's line on the mid-plane: flat at z = z_c
            self.open_curves += [c for c in edges
                                 if np.ptp(model.getBoundingBox(1, c)[2::3]) < _EPS]
        self.front_curves = sorted(edges - set(self.open_curves))
        self.front_corners = [np.array([*mouth, z_low])] + (
            [np.array([*tip, z_c])] if self.half_width else [np.array([*mouth, z_high])])

    # mesh --------------------------------------------------------------
    def mesh(self):
        gmsh, opt = self.gmsh, self.opt
        field = gmsh.model.mesh.field
        toothed = self.groups_of("_flank_pos") + self.groups_of("_flank_neg") + self.groups_of(
            "_root")
        fields = [self.graded(self.distance("SurfacesList", toothed, 8), opt.tooth_size),
                  self.graded(self.distance("SurfacesList", self.groups_of("_load"), 12),
                              opt.load_size)]
        if self.crack_surfaces:
            fields.append(self.graded(self.distance("CurvesList", self.front_curves or
                                                    self.open_curves, 200), opt.tip_size))
            fields.append(self.graded(self.distance("SurfacesList", self.crack_surfaces, 40),
                                      opt.tooth_size))
        smallest = field.add("Min")
        field.setNumbers(smallest, "FieldsList", fields)
        field.setAsBackgroundMesh(smallest)
        for name, value in (("Mesh.MeshSizeExtendFromBoundary", 0),
                            ("Mesh.MeshSizeFromPoints", 0), ("Mesh.MeshSizeFromCurvature", 0),
                            ("Mesh.LcIntegrationPrecision", 1e-3),
                            ("Mesh.Algorithm", 6), ("Mesh.Algorithm3D", 1),
                            ("Mesh.ElementOrder", 1)):
            gmsh.option.setNumber(name, value)
        gmsh.model.mesh.generate(3)
        if opt.order == 2:
            gmsh.model.mesh.setOrder(2)
            self.straightened = _straighten_inverted(gmsh, self.front_curves)
        if self.crack_surfaces:
            self.crack_b = split_crack(gmsh, 2, self.crack_surfaces, self.open_curves)

    def groups_of(self, suffix) -> list[int]:
        return [s for name, surfaces in self.groups.items() if name.endswith(suffix)
                for s in surfaces]

    def distance(self, kind, entities, sampling) -> int:
        field = self.gmsh.model.mesh.field
        distance = field.add("Distance")
        field.setNumbers(distance, kind, list(entities))
        field.setNumber(distance, "Sampling", sampling)
        return distance

    def graded(self, distance, size, start=0.0) -> int:
        """Size ``size`` up to ``start`` [m] of ``distance``, then growing by ``grading``."""
        field, opt = self.gmsh.model.mesh.field, self.opt
        threshold = field.add("Threshold")
        field.setNumber(threshold, "InField", distance)
        field.setNumber(threshold, "SizeMin", size)
        field.setNumber(threshold, "SizeMax", opt.size)
        field.setNumber(threshold, "DistMin", start)
        field.setNumber(threshold, "DistMax", start + max((opt.size - size) / opt.grading, 1e-12))
        return threshold

    # extraction --------------------------------------------------------
    def extract(self) -> FEMesh:
        model = self.gmsh.model
        groups = dict(self.groups)
        if self.crack_surfaces:
            groups["crack_a"] = self.crack_surfaces
            groups["crack_b"] = self.crack_b
        mesh, index = extract(self.gmsh, groups, 3)
        points, cells, boundaries = mesh.points, mesh.cells, mesh.boundaries
        points_of = {}
        if self.crack_surfaces:
            front = np.concatenate([model.mesh.getNodes(1, c, includeBoundary=True)[0]
                                    for c in self.front_curves]).astype(int) \
                if self.front_curves else np.zeros(0, int)
            points, cells, boundaries, front = _weld(points, cells, boundaries,
                                                     self.front_corners, index[front])
            points_of["crack_front"] = np.unique(front)
            faces = np.unique(np.concatenate([boundaries["crack_a"].ravel(),
                                              boundaries["crack_b"].ravel()]))
            points_of["crack_mouth"] = faces[
                np.hypot(*(points[faces, :2] - self.path[0]).T) < 1e-9]
        info = dict(mesh.info, straightened=self.straightened)
        return FEMesh(points, cells, mesh.cell_type, boundaries, points_of, info,
                      mesh.cell_quality)


def _weld(points, cells, boundaries, corners, front):
    """Join the node copies the Crack plugin made where the front meets a free surface.

    Returns the mesh without the copies (nodes renumbered) and ``front`` renumbered.
    """
    remap = np.arange(len(points))
    for corner in corners:
        same = np.nonzero(np.abs(points - corner).max(axis=1) < 1e-12)[0]
        remap[same] = same.min()
    kept = np.unique(remap)
    new = np.full(len(points), -1, dtype=np.int64)
    new[kept] = np.arange(len(kept))
    remap = new[remap]
    return (points[kept], remap[cells], {name: remap[f] for name, f in boundaries.items()},
            remap[front[front >= 0]])


def _straighten_inverted(gmsh, keep_curves=(), rounds: int = 5) -> int:
    """Make the surface edges of curved tetrahedra whose Jacobian changes sign straight again.

    Where a face spans more of a concave fillet than the element is thick, the
    mid-node pulled onto the true surface inverts the element.  Putting those
    mid-nodes back at their edge midpoints (a geometric error of the order
    h^2 / (8 R), the same order as the mesh's own) keeps every element valid.
    Edges on ``keep_curves`` (the crack front) stay exact unless that is not enough: a
    shallow, long front (its ends curved with radius depth^2 / half-length) may need its
    own edges straight too.  Returns the number of elements straightened.
    """
    model = gmsh.model
    front = {(1, c) for c in keep_curves}
    types, element_tags, nodes = model.mesh.getElements(3)
    tags, cells = element_tags[0], nodes[0].reshape(-1, 10)
    fixed = 0
    for attempt in range(2 * rounds):
        keep = front if attempt < rounds else set()
        bad = np.nonzero(model.mesh.getElementQualities(tags, "minSICN") <= 0)[0]
        if not len(bad):
            return fixed
        fixed += len(bad)
        for cell in cells[bad]:
            for (a, b), mid in zip(TETRA10_EDGES, cell[4:]):
                if model.mesh.getNode(mid)[2:] in keep:
                    continue
                xa, xb = model.mesh.getNode(cell[a])[0], model.mesh.getNode(cell[b])[0]
                model.mesh.setNode(mid, list(0.5 * (xa + xb)), [])
    if np.any(model.mesh.getElementQualities(tags, "minSICN") <= 0):
        raise MeshingError("curved tetrahedra stay inverted after straightening their edges")
    return fixed
