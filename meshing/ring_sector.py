"""Plane gmsh mesh of ONE tooth pitch of an intact ring (a cyclic sector), and the whole
ring's mesh as rotated copies of it (SI units).

The sector of tooth 0 lies between the radial cuts at polar angles -pi/z and +pi/z
(through the middles of the tooth spaces) and the held circle.  The two cuts are meshed
periodically (gmsh ``setPeriodic``: the +pi/z cut is the -pi/z cut rotated by 2 pi / z),
so copies rotated by whole tooth pitches share their cut nodes.  The outer arc has a node
at every angle where a support of the ring ends, in every pitch (the union over the
supports of their end angles modulo the pitch), so the copies carry the supports exactly.
Meshing one pitch instead of z costs about 1/z of the whole ring's gmsh time.

Groups of the sector (``FEMesh.boundaries``): ``tooth0_load``, ``tooth0_root`` (as in
``ring_mesh``), ``cut_minus``, ``cut_plus`` (the radial cuts), ``outer`` (the held
circle).  Node set ``support_ends`` (``FEMesh.points_of``): the outer-arc nodes at the
support-end angles.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from .fe_mesh import FEMesh
from .extract import extract_plane
from .gear import GearGeometryError, rotation
from .ring_gear import RingGear
from .ring_mesh import MeshOptions, check_load_patch, size_threshold, with_info
from .ring_outline import FILLET_POINTS, INVOLUTE_POINTS
from .session import MeshingError, gmsh_model


def support_end_phases(ring: RingGear) -> np.ndarray:
    """Angles in [0, 2 pi / z) [rad] of every support end, modulo the tooth pitch."""
    pitch = 2 * math.pi / ring.teeth
    ends = np.array([a for arc in ring.supports.arcs() for a in arc])
    phases = (ends + math.pi / ring.teeth) % pitch
    phases[np.abs(phases - pitch) < 1e-9 * pitch] = 0.0  # on a cut: the -pi/z one
    phases = np.sort(phases)
    keep = np.r_[True, np.diff(phases) > 1e-9 * pitch]
    return phases[keep] - math.pi / ring.teeth  # in [-pi/z, pi/z)


def sector_mesh(ring: RingGear, options: MeshOptions = MeshOptions(),
                refinements: int = 0) -> FEMesh:
    """Mesh the tooth pitch of tooth 0 (curved P2 if ``options.order == 2``).

    ``refinements`` (0..5): split every triangle into four that many times (gmsh
    ``refine``, new boundary nodes on the curves) before raising the order, so that
    successive levels are nested and the element size halves everywhere."""
    if not isinstance(ring, RingGear):
        raise GearGeometryError("sector_mesh: ring gears only (RingGear)")
    if isinstance(refinements, bool) or not isinstance(refinements, int) or not (
            0 <= refinements <= 5):
        raise GearGeometryError(f"refinements = {refinements!r}, allowed integers 0..5")
    if ring.supports.count == 0:
        raise GearGeometryError("sector_mesh: needs supports that end (Supports.count > 0)")
    check_load_patch(ring, options)
    started = time.perf_counter()
    with gmsh_model("ring-sector") as gmsh:
        builder = _SectorBuilder(gmsh, ring, options)
        builder.geometry()
        try:
            builder.mesh(refinements)
        except Exception as error:  # gmsh raises bare Exceptions with its log text
            first = str(error).splitlines()[0] if str(error) else type(error).__name__
            raise MeshingError(f"gmsh failed to mesh the ring sector (options={options}): "
                               f"{first}") from None
        mesh, index = extract_plane(gmsh, builder.groups)
        ends = np.concatenate([gmsh.model.mesh.getNodes(0, p)[0] for p in builder.end_points])
        mesh = replace(mesh, points_of={"support_ends": index[ends.astype(np.int64)]})
    return with_info(mesh, started, ring, options, None, None, refinements=refinements,
                     sector=True)


class _SectorBuilder:
    def __init__(self, gmsh, ring, options):
        self.gmsh, self.ring, self.opt = gmsh, ring, options
        self.geo = gmsh.model.geo
        self.groups: dict[str, list[int]] = {}

    def point(self, xy, size: float = 0.0) -> int:
        return self.geo.addPoint(float(xy[0]), float(xy[1]), 0.0, size)

    def spline(self, start: int, points, end: int) -> int:
        return self.geo.addSpline([start, *[self.point(p) for p in points[1:-1]], end])

    def arc(self, start: int, end: int) -> int:
        return self.geo.addCircleArc(start, self.centre, end)

    def geometry(self):
        ring, prof, opt, geo = self.ring, self.ring.profile, self.opt, self.geo
        z = ring.teeth
        self.centre = geo.addPoint(0, 0, 0)
        half = math.copysign(opt.load_patch / 2, prof.form_radius - prof.tip_radius)
        radii = [prof.tip_radius, ring.load_radius - half, ring.load_radius + half,
                 prof.form_radius]
        involute = [ring.gear.flank(np.linspace(a, b, INVOLUTE_POINTS))
                    for a, b in zip(radii[:-1], radii[1:])]
        fillet = [prof.fillet_points(np.linspace(1.0, 0.0, FILLET_POINTS))]
        pos_pieces = involute + fillet
        mirror = np.array([1.0, -1.0])
        neg_pieces = [(p * mirror)[::-1] for p in pos_pieces][::-1]
        load_piece, patch_ends = 1, {1, 2}

        def polar(r, a):
            return r * np.array([math.cos(a), math.sin(a)])

        space_minus = self.point(polar(prof.root_radius, -math.pi / z), opt.tooth_size)
        space_plus = self.point(polar(prof.root_radius, math.pi / z), opt.tooth_size)
        land_end = self.point(neg_pieces[0][0], opt.tooth_size)
        neg = [self.arc(space_minus, land_end)]
        current = land_end
        for piece in neg_pieces:
            nxt = self.point(piece[-1], opt.tooth_size)
            neg.append(self.spline(current, piece, nxt))
            current = nxt
        tip_pos = self.point(pos_pieces[0][0], opt.tooth_size)
        tip = self.arc(current, tip_pos)
        current, pos = tip_pos, []
        for index, piece in enumerate(pos_pieces):
            nxt = self.point(piece[-1], opt.load_size if index + 1 in patch_ends
                             else opt.tooth_size)
            pos.append(self.spline(current, piece, nxt))
            current = nxt
        pos.append(self.arc(current, space_plus))
        self.inner = neg + [tip] + pos
        self.load_curves = [pos[load_piece]]
        # outer arc: from +pi/z down to -pi/z through every support-end phase
        r = ring.held_radius
        phases = [a for a in support_end_phases(ring) if abs(a + math.pi / z) > 1e-12]
        angles = [math.pi / z] + sorted(phases, reverse=True) + [-math.pi / z]
        outer_points = [self.point(polar(r, a), opt.size) for a in angles]
        ends = support_end_phases(ring)
        on_cut = abs(ends[0] + math.pi / z) < 1e-12
        self.end_points = [p for p, a in zip(outer_points, angles)
                           if np.min(np.abs(ends - a)) < 1e-12
                           or (on_cut and abs(a) > 0.99 * math.pi / z)]
        outer = [self.arc(a, b) for a, b in zip(outer_points[:-1], outer_points[1:])]
        cut_plus = geo.addLine(space_plus, outer_points[0])
        cut_minus = geo.addLine(space_minus, outer_points[-1])
        loop = geo.addCurveLoop(self.inner + [cut_plus] + outer + [-cut_minus])
        self.surface = geo.addPlaneSurface([loop])
        geo.synchronize()
        model = self.gmsh.model
        c, s = math.cos(2 * math.pi / z), math.sin(2 * math.pi / z)
        model.mesh.setPeriodic(1, [cut_plus], [cut_minus],
                               [c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
        self.groups = {"tooth0_load": [pos[load_piece]], "tooth0_root": [neg[0], pos[-1]],
                       "cut_minus": [cut_minus], "cut_plus": [cut_plus], "outer": outer}
        model.addPhysicalGroup(2, [self.surface], name="ring")

    def threshold(self, size, *, points=(), curves=(), sampling=20):
        return size_threshold(self.gmsh, self.opt, size, points=points, curves=curves,
                              sampling=sampling)

    def mesh(self, refinements: int):
        gmsh, opt = self.gmsh, self.opt
        fields = [self.threshold(opt.tooth_size, curves=self.inner, sampling=20),
                  self.threshold(opt.load_size, curves=self.load_curves, sampling=10),
                  self.threshold(opt.tip_size, points=self.end_points)]
        field = gmsh.model.mesh.field
        smallest = field.add("Min")
        field.setNumbers(smallest, "FieldsList", fields)
        field.setAsBackgroundMesh(smallest)
        for name, value in (("Mesh.MeshSizeExtendFromBoundary", 0),
                            ("Mesh.MeshSizeFromPoints", 0), ("Mesh.MeshSizeFromCurvature", 0),
                            ("Mesh.Algorithm", 6), ("Mesh.ElementOrder", 1),
                            ("Mesh.LcIntegrationPrecision", 1e-3)):
            gmsh.option.setNumber(name, value)
        gmsh.model.mesh.generate(2)
        for _ in range(refinements):
            gmsh.model.mesh.refine()
        if opt.order == 2:
            gmsh.model.mesh.setOrder(2)


def cut_pairs(sector: FEMesh, ring: RingGear) -> tuple[np.ndarray, np.ndarray]:
    """Nodes of the -pi/z cut and, in the same order, the nodes of the +pi/z cut they
    become when rotated by one tooth pitch; raises MeshingError when they do not match."""
    minus = np.unique(sector.boundaries["cut_minus"])
    plus = np.unique(sector.boundaries["cut_plus"])
    turned = sector.points[minus] @ rotation(2 * math.pi / ring.teeth).T
    distance = np.linalg.norm(turned[:, None, :] - sector.points[plus][None, :, :], axis=2)
    match = np.argmin(distance, axis=1) if len(plus) else np.zeros(0, dtype=np.int64)
    gap = np.hypot(*(turned - sector.points[plus][match]).T).max() if len(minus) else 0.0
    if len(minus) != len(plus) or len(set(match.tolist())) != len(plus) or (
            gap > 1e-9 * ring.held_radius):
        raise MeshingError(f"the sector's cuts are not periodic ({len(minus)} and "
                           f"{len(plus)} nodes, largest gap {gap:.3e} m)")
    return minus, plus[match]


def in_support(ring: RingGear, angles: np.ndarray) -> np.ndarray:
    """Whether each polar angle [rad] lies inside a support arc."""
    angles = np.asarray(angles, dtype=float)
    inside = np.zeros(angles.shape, dtype=bool)
    for lo, hi in ring.supports.arcs():
        inside |= (angles - lo) % (2 * math.pi) < (hi - lo)
    return inside


def ring_from_sector(sector: FEMesh, ring: RingGear) -> FEMesh:
    """The whole ring as z copies of ``sector`` rotated by whole tooth pitches, the cut
    nodes shared: groups ``tooth{k}_load``, ``tooth{k}_root``, ``supports`` (the outer
    facets inside a support arc) and ``outer_free``.  The same discretisation as the
    sector model of ``fem.ring_sector``, assembled whole (its independent check)."""
    z = ring.teeth
    minus, plus = cut_pairs(sector, ring)
    n = len(sector.points)
    own = np.ones(n, dtype=bool)
    own[plus] = False
    local = np.full(n, -1, dtype=np.int64)
    local[own] = np.arange(own.sum())
    per = int(own.sum())
    points, cells, groups = [], [], {}
    for k in range(z):
        index = local + k * per
        index[plus] = local[minus] + ((k + 1) % z) * per
        points.append(sector.points[own] @ rotation(ring.tooth_angle(k)).T)
        cells.append(index[sector.cells])
        groups[f"tooth{k}_load"] = index[sector.boundaries["tooth0_load"]]
        groups[f"tooth{k}_root"] = index[sector.boundaries["tooth0_root"]]
        outer = sector.boundaries["outer"]
        middle = (sector.points[outer[:, 2]] if outer.shape[1] == 3
                  else sector.points[outer[:, :2]].mean(axis=1))
        held = in_support(ring, np.arctan2(middle[:, 1], middle[:, 0]) + ring.tooth_angle(k))
        groups.setdefault("supports", []).append(index[outer[held]])
        groups.setdefault("outer_free", []).append(index[outer[~held]])
    groups["supports"] = np.vstack(groups["supports"])
    groups["outer_free"] = np.vstack(groups["outer_free"])
    info = dict(sector.info, nodes=per * z, elements=len(sector.cells) * z,
                from_sector=True)
    return FEMesh(np.vstack(points), np.vstack(cells), sector.cell_type, groups, {}, info,
                  np.tile(sector.cell_quality, z) if sector.cell_quality is not None
                  else None)
