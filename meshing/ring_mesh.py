"""Plane (2D) gmsh mesh of the ring gear, intact or with a zero-width crack (SI units).

Named groups handed to the FE stage (``FEMesh.boundaries``):

``support_j`` / ``supports``
    Held arcs of the outer surface (all of it when ``Supports.count == 0``).
``outer_free``
    The rest of the outer surface.
``tooth{k}_flank_pos`` / ``tooth{k}_flank_neg``
    Flank and fillet of tooth k on its counter-clockwise (+psi) and clockwise side.
``tooth{k}_root``
    The two root-land arcs beside tooth k (on the root circle).
``tooth{k}_load``
    Patch of ``tooth{k}_flank_pos`` around the working pitch radius where a
    planet's mesh force is applied.
``crack_a`` / ``crack_b``
    The two faces of the crack (same geometry, separate nodes except at the tip).

Node sets (``FEMesh.points_of``): ``crack_tip`` (one node), ``crack_mouth``.
"""
from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, replace

import numpy as np

from .crack import Crack
from .ring_outline import FILLET_POINTS, INVOLUTE_POINTS
from .fe_mesh import FEMesh
from .gear import GearGeometryError, rotation
from .ring_gear import RingGear, ToothedBody
from .extract import extract_plane
from .session import MeshingError, gmsh_model, split_crack


@dataclass(frozen=True)
class MeshOptions:
    """Element sizes [m] and order.

    Parameters
    ----------
    size : float
        Element size in the rim, away from teeth, loads and crack.
    tooth_size : float
        Element size along the toothed boundary.
    tip_size : float
        Element size at the crack tip.
    load_size : float
        Element size on the load patches.
    grading : float
        Growth of the element size per unit distance from a refined spot, (0, 1].
    load_patch : float
        Radial extent of each load patch on the flank [m].
    order : int
        1 (straight triangles) or 2 (curved, on the exact boundary).
    """

    size: float = 2.0e-3
    tooth_size: float = 0.5e-3
    tip_size: float = 0.05e-3
    load_size: float = 0.1e-3
    grading: float = 0.3
    load_patch: float = 0.4e-3
    order: int = 2

    def __post_init__(self):
        for name in ("size", "tooth_size", "tip_size", "load_size", "load_patch"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                    math.isfinite(value) and 1e-7 <= value <= 0.1):
                raise GearGeometryError(f"mesh.{name} = {value!r} m, allowed 1e-7..0.1 m")
        if not 0 < self.grading <= 1:
            raise GearGeometryError(f"mesh.grading = {self.grading!r}, allowed (0, 1]")
        if self.order not in (1, 2):
            raise GearGeometryError(f"mesh.order = {self.order!r}, allowed 1 or 2")




def ring_mesh(ring: ToothedBody, crack: Crack | None = None,
              options: MeshOptions = MeshOptions(), refinements: int = 0) -> FEMesh:
    """Mesh the cross-section of a ring (or of an external ``GearBody``) with gmsh.

    Plane, triangles.  A crack of zero depth (or ``None``) gives the intact mesh;
    cracks are modelled in ring gears only.  ``refinements`` (intact meshes, 0..4):
    split every triangle of the mesh of ``options`` into four that many times (new
    boundary nodes on the exact curves), so that successive levels are nested and the
    element size halves everywhere: the uniform refinement convergence theory assumes.
    """
    if isinstance(refinements, bool) or not isinstance(refinements, int) or not (
            0 <= refinements <= 4):
        raise GearGeometryError(f"refinements = {refinements!r}, allowed integers 0..4")
    if crack is not None and crack.depth == 0:
        crack = None
    if crack is not None and refinements:
        raise GearGeometryError("refinements: intact meshes only (crack given)")
    if crack is not None and not isinstance(ring, RingGear):
        raise GearGeometryError("crack: only ring gears (RingGear) take a crack")
    crack_path = crack.path(ring) if crack is not None else None
    check_load_patch(ring, options)
    started = time.perf_counter()
    with gmsh_model("ring") as gmsh:
        builder = RingBuilder(gmsh, ring, crack, crack_path, options)
        builder.refinements = refinements
        mesh = run_builder(builder, f"the ring section (options={options}, crack={crack})")
    extra = {"refinements": refinements} if refinements else {}
    return with_info(mesh, started, ring, options, crack, crack_path, exact_area=ring.area(),
                     **extra)


def run_builder(builder, what: str) -> FEMesh:
    """Geometry, mesh and extraction; gmsh's failures become a ``MeshingError``."""
    builder.geometry()
    try:
        builder.mesh()
    except Exception as error:  # gmsh raises bare Exceptions with its log text
        first = str(error).splitlines()[0] if str(error) else type(error).__name__
        raise MeshingError(f"gmsh failed to mesh {what}: {first}") from None
    return builder.extract()


def with_info(mesh: FEMesh, started: float, ring, options, crack, crack_path, **extra) -> FEMesh:
    """The mesh with its parameters, exact measures and time in ``info`` (JSON-ready)."""
    info = dict(mesh.info)
    info.update(seconds=time.perf_counter() - started, ring=_describe(ring), options=asdict(options),
                crack=None if crack is None else asdict(crack),
                crack_path=None if crack_path is None else crack_path.tolist(),
                density=ring.density, **extra)
    return replace(mesh, info=info)


def check_load_patch(body: ToothedBody, options: MeshOptions) -> None:
    prof = body.profile
    low, high = sorted((prof.tip_radius, prof.form_radius))
    if not (low < body.load_radius - options.load_patch / 2
            and body.load_radius + options.load_patch / 2 < high):
        raise GearGeometryError(
            f"mesh.load_patch = {options.load_patch} m does not fit on the involute between "
            f"r = {low:.6g} and {high:.6g} m around the load radius {body.load_radius:.6g} m")


def _describe(body: ToothedBody) -> dict:
    g = body.gear
    return dict(teeth=g.teeth, module=g.module, pressure_angle=g.pressure_angle,
                profile_shift=g.profile_shift, face_width=g.face_width, internal=g.internal,
                held_diameter=2 * body.held_radius, fillet=body.fillet,
                supports=asdict(body.supports), load_radius=body.load_radius)


def size_threshold(gmsh, opt: MeshOptions, size: float, *, points=(), curves=(),
                   sampling: int = 20) -> int:
    """A gmsh Threshold field: ``size`` [m] at the given points/curves, growing by
    ``opt.grading`` to ``opt.size``; returns the field's tag."""
    field = gmsh.model.mesh.field
    distance = field.add("Distance")
    if points:
        field.setNumbers(distance, "PointsList", list(points))
    if curves:
        field.setNumbers(distance, "CurvesList", list(curves))
        field.setNumber(distance, "Sampling", sampling)
    threshold = field.add("Threshold")
    field.setNumber(threshold, "InField", distance)
    field.setNumber(threshold, "SizeMin", size)
    field.setNumber(threshold, "SizeMax", opt.size)
    field.setNumber(threshold, "DistMin", 0.0)
    field.setNumber(threshold, "DistMax", max((opt.size - size) / opt.grading, 1e-12))
    return threshold


class RingBuilder:
    def __init__(self, gmsh, ring, crack, crack_path, options):
        self.gmsh, self.ring, self.crack, self.path, self.opt = gmsh, ring, crack, crack_path, options
        self.geo = gmsh.model.geo
        self.groups: dict[str, list[int]] = {}
        self.support_ends: list[int] = []  # where a clamped arc ends: a stress singularity
        self.load_curves: list[int] = []
        self.inner_curves: list[int] = []
        self.crack_lines: list[int] = []
        self.crack_points: dict[str, int] = {}
        self.refinements = 0  # uniform splits after meshing (``ring_mesh``)

    # geometry ----------------------------------------------------------
    def point(self, xy, size: float = 0.0) -> int:
        return self.geo.addPoint(float(xy[0]), float(xy[1]), 0.0, size)

    def spline(self, start: int, points, end: int) -> int:
        inner = [self.point(p) for p in points[1:-1]]
        return self.geo.addSpline([start, *inner, end])

    def arc(self, start: int, end: int) -> int:
        return self.geo.addCircleArc(start, self.centre, end)

    def geometry(self):
        self.section(crack_lines=True)
        self.geo.synchronize()
        if self.crack_lines:
            self.gmsh.model.mesh.embed(1, self.crack_lines, 2, self.surface)
        model = self.gmsh.model
        # the tags gmsh would number itself (one past the largest), given explicitly: its
        # own numbering scans every entity per group (slow for the ~200 groups)
        first = max((tag for _, tag in model.getPhysicalGroups()), default=0) + 1
        model.addPhysicalGroup(2, [self.surface], tag=first, name="ring")
        for tag, (name, curves) in enumerate(self.groups.items(), start=first + 1):
            model.addPhysicalGroup(1, curves, tag=tag, name=name)

    def section(self, crack_lines: bool):
        """The cross-section at z = 0: curves, named curve lists and the plane surface."""
        ring, prof, opt = self.ring, self.ring.profile, self.opt
        self.centre = self.geo.addPoint(0, 0, 0)
        z = ring.teeth
        root_crack_tooth = self.crack.tooth if self.crack and self.crack.kind.splits_fillet else None
        t_crit = prof.critical_parameter() if root_crack_tooth is not None else None

        # half profile (+psi side), pieces from the tip towards the space centre
        half = math.copysign(opt.load_patch / 2, prof.form_radius - prof.tip_radius)
        radii = [prof.tip_radius, ring.load_radius - half, ring.load_radius + half,
                 prof.form_radius]
        involute_pieces = [ring.gear.flank(np.linspace(a, b, INVOLUTE_POINTS))
                           for a, b in zip(radii[:-1], radii[1:])]
        load_piece = 1

        def fillet_pieces(split):
            cuts = [1.0, split, 0.0] if split is not None else [1.0, 0.0]
            return [prof.fillet_points(np.linspace(a, b, FILLET_POINTS))
                    for a, b in zip(cuts[:-1], cuts[1:])]

        space_points = [self.point(prof.root_radius * np.array(
            [math.cos((2 * k + 1) * math.pi / z), math.sin((2 * k + 1) * math.pi / z)]),
            opt.tooth_size) for k in range(z)]
        self.teeth_curves(range(z), {k: space_points[k % z] for k in range(-1, z)},
                          involute_pieces, fillet_pieces, load_piece, root_crack_tooth, t_crit)
        toothed = self.geo.addCurveLoop(self.inner_curves)
        held = self.geo.addCurveLoop(self.outer_boundary())
        loops = [held, toothed] if ring.gear.internal else [toothed, held]
        self.surface = self.geo.addPlaneSurface(loops)
        if self.path is not None:
            self.crack_geometry(lines=crack_lines)

    def teeth_curves(self, teeth, space_points: dict, involute_pieces, fillet_pieces,
                     load_piece: int, root_crack_tooth, t_crit) -> None:
        """The toothed boundary of ``teeth`` (ascending), tooth k from the space centre
        ``space_points[k - 1]`` to ``space_points[k]`` (gmsh point tags), with its groups."""
        ring, opt = self.ring, self.opt
        patch_ends = {load_piece, load_piece + 1}  # pieces whose first point ends a patch
        mirror = np.array([1.0, -1.0])
        for k in teeth:
            rot = rotation(ring.tooth_angle(k))
            fillets = fillet_pieces(t_crit if k == root_crack_tooth else None)
            pos_pieces = involute_pieces + fillets
            neg_pieces = [(p * mirror)[::-1] for p in involute_pieces + fillet_pieces(None)][::-1]
            # clockwise side: space centre -> land end -> fillet -> involute -> tip
            start = space_points[k - 1]
            land_end = self.point(rot @ neg_pieces[0][0], opt.tooth_size)
            neg = [self.arc(start, land_end)]
            current = land_end
            for index, piece in enumerate(neg_pieces):
                nxt = self.point(rot @ piece[-1], opt.tooth_size)
                neg.append(self.spline(current, [rot @ p for p in piece], nxt))
                current = nxt
            tip_pos = self.point(rot @ pos_pieces[0][0], opt.tooth_size)
            tip = self.arc(current, tip_pos)
            current, pos = tip_pos, []
            for index, piece in enumerate(pos_pieces):
                end_size = opt.load_size if index + 1 in patch_ends else opt.tooth_size
                nxt = self.point(rot @ piece[-1], end_size)
                pos.append(self.spline(current, [rot @ p for p in piece], nxt))
                if k == root_crack_tooth and index == len(involute_pieces):
                    self.crack_points["mouth"] = nxt
                current = nxt
            pos.append(self.arc(current, space_points[k]))
            self.inner_curves += neg + [tip] + pos
            self.groups[f"tooth{k}_flank_neg"] = neg[1:]
            self.groups[f"tooth{k}_flank_pos"] = pos[:-1]
            self.groups[f"tooth{k}_load"] = [pos[load_piece]]
            self.groups[f"tooth{k}_root"] = [neg[0], pos[-1]]
            self.load_curves.append(pos[load_piece])

    def outer_boundary(self) -> list[int]:
        ring = self.ring
        supports = ring.supports.arcs()
        breaks = [a for arc in supports for a in arc] or [0.0]
        special = {}
        end = None if self.path is None else self.crack.kind.outer_end(self.crack, ring, self.path)
        if end is not None:
            angle = math.atan2(end[1], end[0])
            special[angle % (2 * math.pi)] = "crack_end"
            breaks.append(angle)
        angles = sorted({round(a % (2 * math.pi), 15) for a in breaks})
        while True:  # arcs must be shorter than pi
            gaps = np.diff(angles + [angles[0] + 2 * math.pi])
            widest = int(np.argmax(gaps))
            if gaps[widest] < 0.6 * math.pi:
                break
            angles.insert(widest + 1, angles[widest] + gaps[widest] / 2)
        r = ring.held_radius
        points = []
        support_ends = {round(a % (2 * math.pi), 15) for arc in supports for a in arc}
        for a in angles:
            points.append(self.point(r * np.array([math.cos(a), math.sin(a)]), self.opt.size))
            if any(abs(a - s) < 1e-14 for s in special):
                self.crack_points["outer_end"] = points[-1]
            if a in support_ends:
                self.support_ends.append(points[-1])
        curves, free = [], []
        support_groups = {f"support_{j}": [] for j in range(len(supports))}
        for i, a in enumerate(angles):
            curve = self.arc(points[i], points[(i + 1) % len(points)])
            curves.append(curve)
            mid = a + (((angles[(i + 1) % len(angles)] - a) % (2 * math.pi)) / 2)
            held = [j for j, (lo, hi) in enumerate(supports)
                    if (mid - lo) % (2 * math.pi) < (hi - lo)]
            if ring.supports.count == 0:
                support_groups.setdefault("support_0", []).append(curve)
            elif held:
                support_groups[f"support_{held[0]}"].append(curve)
            else:
                free.append(curve)
        self.groups.update(support_groups)
        self.groups["supports"] = [c for v in support_groups.values() for c in v]
        if free:
            self.groups["outer_free"] = free
        return curves

    def crack_geometry(self, lines: bool = True):
        """Crack points (``mouth``, ``tip``, ``outer_end``) and, if ``lines``, its lines."""
        path, crack = self.path, self.crack
        if crack.kind.splits_fillet:
            first = self.crack_points["mouth"]
        else:
            first = self.crack_points["outer_end"]
            self.crack_points["mouth"] = first
        tags = [first]
        for i, p in enumerate(path[1:], start=1):
            last = i == len(path) - 1
            if last and crack.is_through(self.ring):
                tags.append(self.crack_points["outer_end"])
            else:
                tags.append(self.point(p, self.opt.tip_size if last else self.opt.tooth_size))
        self.crack_points["tip"] = tags[-1]
        self.crack_tags = tags
        if lines:
            self.crack_lines = [self.geo.addLine(a, b) for a, b in zip(tags[:-1], tags[1:])]

    # mesh --------------------------------------------------------------
    def threshold(self, size, *, points=(), curves=(), sampling=20):
        return size_threshold(self.gmsh, self.opt, size, points=points, curves=curves,
                              sampling=sampling)

    def mesh(self):
        gmsh, opt = self.gmsh, self.opt
        fields = [self.threshold(opt.tooth_size, curves=self.inner_curves, sampling=8),
                  self.threshold(opt.load_size, curves=self.load_curves, sampling=4)]
        if self.support_ends:
            fields.append(self.threshold(opt.tip_size, points=self.support_ends))
        if self.crack_lines:
            fields.append(self.threshold(opt.tooth_size, curves=self.crack_lines))
            fields.append(self.threshold(opt.tip_size, points=[self.crack_points["tip"]]))
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
        for _ in range(self.refinements):
            gmsh.model.mesh.refine()
        if opt.order == 2:
            gmsh.model.mesh.setOrder(2)
        if self.crack_lines:
            open_points = [self.crack_points["mouth"]]
            if self.crack.is_through(self.ring):
                open_points.append(self.crack_points["tip"])
            self.crack_b = split_crack(gmsh, 1, self.crack_lines, open_points)

    # extraction --------------------------------------------------------
    def extract(self) -> FEMesh:
        model = self.gmsh.model
        groups = dict(self.groups)
        if self.crack_lines:
            groups["crack_a"] = self.crack_lines
            groups["crack_b"] = self.crack_b
        mesh, index = extract_plane(self.gmsh, groups)
        points_of = {}
        if self.crack_lines:
            tip_nodes = model.mesh.getNodes(0, self.crack_points["tip"])[0]
            points_of["crack_tip"] = index[tip_nodes]
            points_of["crack_mouth"] = np.nonzero(
                np.hypot(*(mesh.points - self.path[0]).T) < 1e-12 * self.ring.outer_radius)[0]
            twins = [points_of["crack_mouth"]]
            if self.crack.is_through(self.ring):
                twins.append(np.nonzero(np.hypot(*(mesh.points - self.path[-1]).T)
                                        < 1e-12 * self.ring.outer_radius)[0])
            mesh = replace(mesh, boundaries=facets_on_cells(mesh, twins))
        return replace(mesh, points_of=points_of)


def facets_on_cells(mesh: FEMesh, twins: list) -> dict:
    """The boundary groups with each facet that ends at a split crack end (mouth, or the
    outer end of a through crack) on the copy of that node its cell uses.

    gmsh's Crack plugin gives one side's cells a copy of the crack-end node and decides
    which line elements of the surface there follow by a side test; for a crack at a
    shallow angle to the surface (e.g. +60 deg from the radial) it can put the flank
    element on the wrong copy, so the facet is no edge of any cell."""
    cells = mesh.cells[:, :3]
    groups = {}
    for name, facets in mesh.boundaries.items():
        if name.startswith("crack_") or len(facets) == 0:
            groups[name] = facets
            continue
        facets = facets.copy()
        for pair in twins:
            if len(pair) != 2:
                continue
            for row in np.nonzero(np.isin(facets[:, :2], pair).any(axis=1))[0]:
                ends = facets[row, :2]
                if _is_cell_edge(cells, *ends):
                    continue
                swapped = np.where(ends == pair[0], pair[1],
                                   np.where(ends == pair[1], pair[0], ends))
                if _is_cell_edge(cells, *swapped):
                    facets[row, :2] = swapped
        groups[name] = facets
    return groups


def _is_cell_edge(cells: np.ndarray, a: int, b: int) -> bool:
    return bool(np.any((cells == a).any(axis=1) & (cells == b).any(axis=1)))
