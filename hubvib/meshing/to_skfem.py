"""Hand a plane ``FEMesh`` to scikit-fem with its named boundaries."""
from __future__ import annotations

import numpy as np

from .fe_mesh import GMSH_TO_VTK_TETRA10, FEMesh


def to_skfem(mesh: FEMesh):
    """scikit-fem mesh (MeshTri1/MeshTet1 or curved MeshTri2/MeshTet2) with ``boundaries``.

    Curved second-order meshes keep their mid-edge nodes on the exact
    boundary.  Boundary names map to facet indices of the returned mesh.
    Crack faces stay separate: never call ``remove_duplicate_nodes`` on it.

    Returns the mesh and ``vertex_of``: for every node of ``mesh`` the
    index of the corresponding vertex in the skfem mesh (-1 for mid-edge nodes).
    """
    import skfem

    vertices = mesh.vertices()
    vertex_of = np.full(len(mesh.points), -1, dtype=np.int64)
    vertex_of[vertices] = np.arange(len(vertices))
    linear, curved = (skfem.MeshTri1, skfem.MeshTri2) if mesh.dim == 2 else (skfem.MeshTet1,
                                                                           skfem.MeshTet2)
    if mesh.order == 1:
        fe = linear(np.ascontiguousarray(mesh.points[vertices].T),
                    np.ascontiguousarray(vertex_of[mesh.cells].T))
    else:
        # gmsh triangle6 order (vertices, then edges 01, 12, 20) is skfem's; skfem
        # renumbers the vertices in sorted node order, as vertex_of does
        cells = mesh.cells if mesh.dim == 2 else mesh.cells[:, GMSH_TO_VTK_TETRA10]
        fe = curved(np.ascontiguousarray(mesh.points.T), np.ascontiguousarray(cells.T))
    lookup = {tuple(row): i for i, row in enumerate(np.sort(fe.facets, axis=0).T)}
    boundaries = {}
    for name, elements in mesh.boundaries.items():
        keys = np.sort(vertex_of[elements[:, :mesh.dim]], axis=1)
        try:
            boundaries[name] = np.array([lookup[tuple(k)] for k in keys], dtype=np.int64)
        except KeyError:
            raise ValueError(f"boundary group {name!r} has facets that are not mesh facets") \
                from None
    return fe.with_boundaries(boundaries), vertex_of
