"""Edge-cracked strip: the crack model's exact benchmark (SI units).

The strip ``-L <= x <= L``, ``0 <= y <= W`` has a zero-width crack from the
middle of the lower edge, ``x = 0``, ``0 <= y <= a``, made by gmsh's Crack
plugin as on the ring, with the same tip refinement.  Groups: ``left``,
``right`` (ends), ``crack_a``/``crack_b`` (faces); node sets ``pin`` (top
middle) and ``roller`` (top right corner), ``crack_tip``.
"""
from __future__ import annotations

from dataclasses import replace

from .extract import extract_plane
from .fe_mesh import FEMesh
from .gear import GearGeometryError
from .session import gmsh_model, grade_towards, split_crack


def edge_crack_strip(width: float, half_length: float, depth: float, size: float,
                     tip_size: float, order: int = 2) -> FEMesh:
    """Mesh of the strip; ``depth = 0`` gives it uncracked (same sizes)."""
    if not 0 < width <= half_length:
        raise GearGeometryError(f"width = {width!r} m, allowed (0, half_length]")
    if not 0 <= depth < width:
        raise GearGeometryError(f"depth = {depth!r} m, allowed 0 <= depth < width = {width} m")
    if not 0 < tip_size <= size <= width:
        raise GearGeometryError(f"tip_size = {tip_size!r}, size = {size!r}: need "
                                f"0 < tip_size <= size <= width")
    if order not in (1, 2):
        raise GearGeometryError(f"order = {order!r}, allowed 1 or 2")
    W, L = width, half_length
    with gmsh_model("strip") as gmsh:
        geo = gmsh.model.geo
        corners = [geo.addPoint(x, y, 0) for x, y in ((-L, 0), (0, 0), (L, 0), (L, W), (0, W),
                                                       (-L, W))]
        lines = [geo.addLine(corners[i], corners[(i + 1) % 6]) for i in range(6)]
        surface = geo.addPlaneSurface([geo.addCurveLoop(lines)])
        groups = {"left": [lines[5]], "right": [lines[2]]}
        tip = crack = None
        if depth > 0:
            tip = geo.addPoint(0, depth, 0)
            crack = geo.addLine(corners[1], tip)
        geo.synchronize()
        model = gmsh.model
        grade_towards(gmsh, [tip if tip else corners[1]], tip_size, size)
        if crack is not None:
            model.mesh.embed(1, [crack], 2, surface)
            model.mesh.embed(0, [tip], 2, surface)
        model.mesh.generate(2)
        if order == 2:
            model.mesh.setOrder(2)
        if crack is not None:
            groups["crack_a"] = [crack]
            groups["crack_b"] = split_crack(gmsh, 1, [crack], [corners[1]])
        mesh, index = extract_plane(gmsh, groups)
        points_of = {name: index[model.mesh.getNodes(0, corners[i])[0]]
                     for name, i in (("pin", 4), ("roller", 3))}
        if tip is not None:
            points_of["crack_tip"] = index[model.mesh.getNodes(0, tip)[0]]
    info = dict(mesh.info, width=W, half_length=L, depth=depth, size=size, tip_size=tip_size)
    return replace(mesh, points_of=points_of, info=info)
