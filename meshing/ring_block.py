"""Plane gmsh mesh of a run of consecutive tooth pitches of the ring, intact or with the
crack inside, whose two radial cuts carry a fixed node distribution (SI units).

A block of ``count`` pitches starting at tooth ``first`` lies between the radial cuts
through the middles of the tooth spaces before tooth ``first`` and after its last tooth,
and the held circle.  Each cut is a chain of straight segments, one element each,
through the nodes ``cut_radii`` gives (the same for every cut of a ring and mesh
options): blocks meshed apart share their cut nodes exactly, so any set of blocks that
covers the ring glues into one conforming ring mesh (``meshing.ring_pieces``).  The outer
arc carries a node at every support end inside the block (the crack's outer end too), each
refined like the whole ring's (``ring_mesh``); the teeth, load patches and the crack are
meshed by the whole ring's builder (``RingBuilder``), with its size fields.

Groups (``FEMesh.boundaries``): as ``ring_mesh`` for the block's teeth (``tooth{k}_load``,
``tooth{k}_root``, ``tooth{k}_flank_pos``, ``tooth{k}_flank_neg``, ``crack_a``,
``crack_b``), ``cut_minus`` and ``cut_plus`` (the cuts at the lower and upper polar
angle), ``outer`` (the held circle's arcs).  Node sets (``FEMesh.points_of``):
``crack_tip``, ``crack_mouth`` with a crack.
"""
from __future__ import annotations

import math
import time

import numpy as np

from .crack import Crack
from .fe_mesh import FEMesh
from .gear import GearGeometryError
from .ring_gear import RingGear
from .ring_mesh import MeshOptions, RingBuilder, check_load_patch, run_builder, with_info
from .ring_outline import FILLET_POINTS, INVOLUTE_POINTS
from .session import gmsh_model

#: samples of the element-size integral along a cut
CUT_SAMPLES = 4001


def cut_radii(ring: RingGear, options: MeshOptions, refined_outer: bool = False) -> np.ndarray:
    """Radii [m] of the vertex nodes of a radial cut, root circle to held circle.

    The element size follows the whole ring's size fields along the cut: ``tooth_size``
    at the root circle growing by ``grading`` per unit distance up to ``size``, and
    ``tip_size`` at the held circle with ``refined_outer`` (a support end on the cut).
    The nodes are equally spaced in the integral of 1 / size."""
    r0, r1 = ring.profile.root_radius, ring.held_radius
    r = np.linspace(r0, r1, CUT_SAMPLES)
    size = np.minimum(options.size, options.tooth_size + options.grading * (r - r0))
    if refined_outer:
        size = np.minimum(size, options.tip_size + options.grading * (r1 - r))
    density = 1.0 / size
    s = np.concatenate([[0.0], np.cumsum((density[1:] + density[:-1]) / 2 * np.diff(r))])
    n = max(1, int(round(s[-1])))
    radii = np.interp(np.linspace(0.0, s[-1], n + 1), s, r)
    radii[0], radii[-1] = r0, r1
    return radii


def support_ends(ring: RingGear) -> np.ndarray:
    """Polar angles [rad] of every support end in [0, 2 pi) (none when the whole outer
    surface is held)."""
    if ring.supports.count == 0:
        return np.zeros(0)
    return np.array(sorted({a % (2 * math.pi) for arc in ring.supports.arcs() for a in arc}))


def block_span(ring: RingGear, first: int, count: int) -> tuple[float, float]:
    """Polar angles [rad] of the block's lower and upper cut (upper > lower)."""
    half = math.pi / ring.teeth
    low = 2 * math.pi * first / ring.teeth - half
    return low, low + 2 * math.pi * count / ring.teeth


def ends_in(ring: RingGear, first: int, count: int) -> np.ndarray:
    """The support ends in the block's span, cuts included, as angles in its span [rad]."""
    low, high = block_span(ring, first, count)
    angles = low + (support_ends(ring) - low) % (2 * math.pi)
    tol = 1e-12
    angles = np.where(np.abs(angles - low - 2 * math.pi) < tol, low, angles)
    return np.sort(angles[angles <= high + tol])


def block_mesh(ring: RingGear, first: int, count: int, options: MeshOptions = MeshOptions(),
               crack=None, ends=None) -> FEMesh:
    """Mesh the ``count`` pitches from tooth ``first`` (curved P2 if ``options.order``).

    ``crack`` (a ``Crack`` or ``crack_path.PathCrack`` of a tooth in the block; None or
    depth 0: intact) is meshed as ``ring_mesh`` meshes it.  ``ends``: the outer nodes'
    angles [rad] (default: the ring's support ends in the block, ``ends_in``)."""
    if not isinstance(ring, RingGear):
        raise GearGeometryError("block_mesh: ring gears only (RingGear)")
    z = ring.teeth
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count < z:
        raise GearGeometryError(f"count = {count!r}, allowed integers 1..{z - 1}")
    teeth = [(first + j) % z for j in range(count)]
    if crack is not None and crack.depth == 0:
        crack = None
    if crack is not None and crack.tooth not in teeth:
        raise GearGeometryError(f"crack.tooth = {crack.tooth} lies outside the block's teeth "
                                f"{teeth}")
    path = None
    if crack is not None:
        path = crack.path(ring) if isinstance(crack, Crack) else crack.path(ring,
                                                                            options.tip_size)
    check_load_patch(ring, options)
    ends = ends_in(ring, first, count) if ends is None else np.asarray(ends, dtype=float)
    started = time.perf_counter()
    with gmsh_model("ring-block") as gmsh:
        builder = BlockBuilder(gmsh, ring, crack, path, options, first, count, ends)
        mesh = run_builder(builder, f"the ring block of teeth {teeth} (options={options}, "
                                    f"crack={crack})")
    return with_info(mesh, started, ring, options, crack if isinstance(crack, Crack) else None,
                     path, block=[int(first) % z, int(count)])


class BlockBuilder(RingBuilder):
    """``RingBuilder`` for a run of pitches: the teeth as the whole ring's, the cuts as
    chains of fixed nodes, the outer arc between them."""

    def __init__(self, gmsh, ring, crack, path, options, first, count, ends):
        super().__init__(gmsh, ring, crack, path, options)
        self.first, self.count, self.ends = int(first), int(count), ends
        self.cut_lines: list[int] = []

    def section(self, crack_lines: bool):
        ring, prof, opt = self.ring, self.ring.profile, self.opt
        z = ring.teeth
        self.centre = self.geo.addPoint(0, 0, 0)
        root_crack_tooth = self.crack.tooth if self.crack and self.crack.kind.splits_fillet else None
        t_crit = prof.critical_parameter() if root_crack_tooth is not None else None
        half = math.copysign(opt.load_patch / 2, prof.form_radius - prof.tip_radius)
        radii = [prof.tip_radius, ring.load_radius - half, ring.load_radius + half,
                 prof.form_radius]
        involute_pieces = [ring.gear.flank(np.linspace(a, b, INVOLUTE_POINTS))
                           for a, b in zip(radii[:-1], radii[1:])]

        def fillet_pieces(split):
            cuts = [1.0, split, 0.0] if split is not None else [1.0, 0.0]
            return [prof.fillet_points(np.linspace(a, b, FILLET_POINTS))
                    for a, b in zip(cuts[:-1], cuts[1:])]

        low, high = block_span(ring, self.first, self.count)
        teeth = [(self.first + j) % z for j in range(self.count)]
        space_list = []
        for j in range(self.count + 1):
            a = low + 2 * math.pi * j / z
            space_list.append(self.point(prof.root_radius * np.array([math.cos(a), math.sin(a)]),
                                         opt.tooth_size))
        space = {}
        for j, k in enumerate(teeth):  # tooth k runs from space k - 1 to space k
            space[k - 1], space[k] = space_list[j], space_list[j + 1]
        self.teeth_curves(teeth, space, involute_pieces, fillet_pieces, 1, root_crack_tooth,
                          t_crit)
        # outer arc, from the upper cut down to the lower one
        r = ring.held_radius
        special = {}
        end = None if self.path is None else self.crack.kind.outer_end(self.crack, ring, self.path)
        if end is not None:
            angle = low + (math.atan2(end[1], end[0]) - low) % (2 * math.pi)
            special[angle] = "crack_end"
        tol = 1e-12
        inside = sorted({float(a) for a in self.ends if low + tol < a < high - tol}
                        | {a for a in special}, reverse=True)
        angles = [high] + inside + [low]
        outer_points = [self.point(r * np.array([math.cos(a), math.sin(a)]), opt.size)
                        for a in angles]
        for a, p in zip(angles, outer_points):
            if any(abs(a - s) < tol for s in special):
                self.crack_points["outer_end"] = p
            if np.any(np.abs(self.ends - a) < tol):
                self.support_ends.append(p)
        outer = [self.arc(a, b) for a, b in zip(outer_points[:-1], outer_points[1:])]
        refined = [bool(np.any(np.abs(self.ends - a) < tol)) for a in (low, high)]
        cut_minus = self.cut_chain(space_list[0], outer_points[-1], low, refined[0])
        cut_plus = self.cut_chain(space_list[-1], outer_points[0], high, refined[1])
        loop = self.geo.addCurveLoop(self.inner_curves + cut_plus + outer
                                     + [-c for c in reversed(cut_minus)])
        self.surface = self.geo.addPlaneSurface([loop])
        self.groups.update(cut_minus=cut_minus, cut_plus=cut_plus, outer=outer)
        if self.path is not None:
            self.crack_geometry(lines=crack_lines)

    def cut_chain(self, root_point: int, outer_point: int, angle: float,
                  refined_outer: bool) -> list[int]:
        """Lines from the root circle to the held circle at ``angle`` through the nodes of
        ``cut_radii``, one element each."""
        radii = cut_radii(self.ring, self.opt, refined_outer)
        direction = np.array([math.cos(angle), math.sin(angle)])
        tags = [root_point] + [self.point(r * direction) for r in radii[1:-1]] + [outer_point]
        lines = [self.geo.addLine(a, b) for a, b in zip(tags[:-1], tags[1:])]
        self.cut_lines += lines
        return lines

    def geometry(self):
        super().geometry()
        for line in self.cut_lines:
            self.gmsh.model.mesh.setTransfiniteCurve(line, 2)
