"""Annulus mesh: the exact-solution benchmark of the FE chain (SI units)."""
from __future__ import annotations

from .extract import extract_plane
from .fe_mesh import FEMesh
from .gear import GearGeometryError
from .session import gmsh_model


def annulus_mesh(inner_radius: float, outer_radius: float, size: float, order: int = 2) -> FEMesh:
    """Triangles between two circles; boundary groups ``inner`` and ``outer``.

    With ``order=2`` the mid-edge nodes lie on the circles (curved elements).
    """
    if not 0 < inner_radius < outer_radius:
        raise GearGeometryError(
            f"inner_radius = {inner_radius!r} m, outer_radius = {outer_radius!r} m: need "
            "0 < inner < outer")
    if not 0 < size <= outer_radius:
        raise GearGeometryError(f"size = {size!r} m, allowed (0, outer_radius]")
    if order not in (1, 2):
        raise GearGeometryError(f"order = {order!r}, allowed 1 or 2")
    with gmsh_model("annulus") as gmsh:
        geo = gmsh.model.geo
        centre = geo.addPoint(0, 0, 0)
        loops, groups = [], {}
        for name, r in (("outer", outer_radius), ("inner", inner_radius)):
            pts = [geo.addPoint(x * r, y * r, 0) for x, y in ((1, 0), (0, 1), (-1, 0), (0, -1))]
            arcs = [geo.addCircleArc(pts[i], centre, pts[(i + 1) % 4]) for i in range(4)]
            loops.append(geo.addCurveLoop(arcs))
            groups[name] = arcs
        geo.addPlaneSurface(loops)
        geo.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.option.setNumber("Mesh.MeshSizeMin", size)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.model.mesh.generate(2)
        if order == 2:
            gmsh.model.mesh.setOrder(2)
        mesh, _ = extract_plane(gmsh, groups)
    mesh.info.update(inner_radius=inner_radius, outer_radius=outer_radius, size=size)
    return mesh
