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
    from . import skfem_meshes as skfem  # scikit-fem's meshes, faster entity numbering

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
    # a facet is its sorted vertices as one int64 (digits in base ``len(vertices)``)
    if len(vertices) ** mesh.dim >= 2 ** 63:
        raise ValueError(f"mesh: {len(vertices)} vertices are too many for int64 facet keys "
                         f"(allowed: fewer than {int(2 ** (63 / mesh.dim))})")

    def keys(facets):
        key = np.zeros(len(facets), dtype=np.int64)
        for column in np.sort(facets, axis=1).T:
            key = key * len(vertices) + column
        return key

    known = keys(fe.facets.T)
    order = np.argsort(known)
    boundaries = {}
    for name, elements in mesh.boundaries.items():
        wanted = keys(vertex_of[elements[:, :mesh.dim]])
        at = np.minimum(np.searchsorted(known, wanted, sorter=order), len(known) - 1)
        if not np.array_equal(known[order[at]], wanted):
            raise ValueError(f"boundary group {name!r} has facets that are not mesh facets")
        boundaries[name] = order[at].astype(np.int64)
    return fe.with_boundaries(boundaries), vertex_of
