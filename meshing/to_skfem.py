"""Hand an ``FEMesh`` to scikit-fem with its named boundaries."""
from __future__ import annotations

import numpy as np

from .fe_mesh import FEMesh


def to_skfem(mesh: FEMesh):
    """scikit-fem mesh (MeshTri1/MeshTri2/MeshTet1/MeshTet2) with ``boundaries``.

    Curved second-order meshes keep their mid-edge nodes on the exact
    boundary.  Boundary names map to facet indices of the returned mesh.
    Crack faces stay separate: never call ``remove_duplicate_nodes`` on it.

    Returns the mesh and ``vertex_of``: for every node of ``mesh`` the
    index of the corresponding vertex in the skfem mesh (-1 for mid-edge nodes).
    """
    import skfem

    kinds = {"triangle": skfem.MeshTri1, "triangle6": skfem.MeshTri2,
             "tetra": skfem.MeshTet1, "tetra10": skfem.MeshTet2}
    kind = kinds[mesh.cell_type]
    nv = mesh.vertex_count
    vertices = np.unique(mesh.cells[:, :nv])
    vertex_of = np.full(len(mesh.points), -1, dtype=np.int64)
    vertex_of[vertices] = np.arange(len(vertices))
    if mesh.order == 1:
        fe = kind(np.ascontiguousarray(mesh.points[vertices].T),
                  np.ascontiguousarray(vertex_of[mesh.cells].T))
    else:
        cells = mesh.cells
        if mesh.cell_type == "tetra10":  # gmsh edge order 01 12 20 30 32 31 -> skfem 01 12 02 03 13 23
            cells = cells[:, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]]
        # skfem renumbers vertices in sorted order of their node index, as vertex_of does
        fe = kind(np.ascontiguousarray(mesh.points.T), np.ascontiguousarray(cells.T))
    facets = fe.facets.T  # sorted vertex indices, one row per facet
    lookup = {tuple(row): i for i, row in enumerate(facets)}
    boundaries = {}
    for name, elements in mesh.boundaries.items():
        keys = np.sort(vertex_of[elements[:, :nv - 1 + (mesh.dim == 3)]], axis=1) \
            if mesh.dim == 3 else np.sort(vertex_of[elements[:, :2]], axis=1)
        try:
            boundaries[name] = np.array([lookup[tuple(k)] for k in keys], dtype=np.int64)
        except KeyError:
            raise ValueError(f"boundary group {name!r} has facets that are not mesh facets") \
                from None
    return fe.with_boundaries(boundaries), vertex_of
