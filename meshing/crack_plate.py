"""Rectangular plate with an inclined centre crack: the mixed-mode benchmark (SI units).

The plate ``-W <= x <= W``, ``-H <= y <= H`` holds a zero-width straight crack of
length ``2 a`` through its centre, at ``angle`` from the x axis, made by gmsh's Crack
plugin as on the ring (both tips closed), with the same graded tip refinement.
Groups: ``left``, ``right``, ``bottom``, ``top`` (edges), ``crack_a``/``crack_b``
(faces); node sets ``corner_bl``, ``corner_br`` (bottom corners), ``crack_tip``
(the tip at ``+a (cos angle, sin angle)``) and ``crack_tip_2`` (the other one).
"""
from __future__ import annotations

import math
from dataclasses import replace

from .extract import extract_plane
from .fe_mesh import FEMesh
from .gear import GearGeometryError
from .session import gmsh_model, grade_towards


def centre_crack_plate(half_width: float, half_height: float, half_length: float,
                       angle: float, size: float, tip_size: float, order: int = 2) -> FEMesh:
    """Mesh of the plate [m]; ``angle`` [rad] from the x axis, |angle| < 90 deg."""
    W, H, a = half_width, half_height, half_length
    if not (0 < W and 0 < H):
        raise GearGeometryError(f"half_width = {W!r}, half_height = {H!r} m: allowed > 0")
    if not abs(angle) < math.pi / 2:
        raise GearGeometryError(f"angle = {math.degrees(angle):.4g} deg, allowed -90..90 deg")
    if not 0 < a * math.cos(angle) < W or not a * abs(math.sin(angle)) < H:
        raise GearGeometryError(f"half_length = {a!r} m: the crack must stay inside the plate")
    if not 0 < tip_size <= size <= min(W, H):
        raise GearGeometryError(f"tip_size = {tip_size!r}, size = {size!r}: need "
                                "0 < tip_size <= size <= min(half_width, half_height)")
    if order not in (1, 2):
        raise GearGeometryError(f"order = {order!r}, allowed 1 or 2")
    c, s = math.cos(angle), math.sin(angle)
    with gmsh_model("plate") as gmsh:
        geo = gmsh.model.geo
        corners = [geo.addPoint(x, y, 0) for x, y in ((-W, -H), (W, -H), (W, H), (-W, H))]
        lines = [geo.addLine(corners[i], corners[(i + 1) % 4]) for i in range(4)]
        surface = geo.addPlaneSurface([geo.addCurveLoop(lines)])
        groups = {"bottom": [lines[0]], "right": [lines[1]], "top": [lines[2]],
                  "left": [lines[3]]}
        tips = [geo.addPoint(a * c, a * s, 0), geo.addPoint(-a * c, -a * s, 0)]
        crack = geo.addLine(tips[1], tips[0])
        geo.synchronize()
        model = gmsh.model
        grade_towards(gmsh, tips, tip_size, size)
        model.mesh.embed(1, [crack], 2, surface)
        model.mesh.generate(2)
        if order == 2:
            model.mesh.setOrder(2)
        groups["crack_a"] = [crack]
        groups["crack_b"] = _split_closed(gmsh, crack)
        mesh, index = extract_plane(gmsh, groups)
        points_of = {name: index[model.mesh.getNodes(0, tag)[0]] for name, tag in (
            ("corner_bl", corners[0]), ("corner_br", corners[1]), ("crack_tip", tips[0]),
            ("crack_tip_2", tips[1]))}
    info = dict(mesh.info, half_width=W, half_height=H, half_length=a, angle=angle, size=size,
                tip_size=tip_size)
    return replace(mesh, points_of=points_of, info=info)


def _split_closed(gmsh, line: int) -> list[int]:
    """Duplicate the nodes of ``line`` except its two end points (gmsh's Crack plugin with
    no open boundary): the second face's new curve tags."""
    model = gmsh.model
    group = model.addPhysicalGroup(1, [line], name="crack")
    before = {tag for _, tag in model.getEntities(1)}
    gmsh.plugin.setNumber("Crack", "Dimension", 1)
    gmsh.plugin.setNumber("Crack", "PhysicalGroup", group)
    gmsh.plugin.setNumber("Crack", "OpenBoundaryPhysicalGroup", 0)
    gmsh.plugin.run("Crack")
    return sorted({tag for _, tag in model.getEntities(1)} - before)
