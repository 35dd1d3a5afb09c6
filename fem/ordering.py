"""Fill-reducing order of a quadratic tetrahedral mesh from its corner-vertex graph.

PARDISO orders a block matrix on its node graph with METIS nested dissection.  On P2
tetrahedra six of every seven nodes sit mid-edge, so the same dissection is found on
the graph of the corner vertices alone (6 times fewer vertices, 9 times fewer edges)
and carried over: each mid-edge node is eliminated just before the earlier of its two
corners.  That keeps it a nested dissection of the node graph: a mid-edge node joins
the part of its earlier corner, and two corners on either side of a separator never
share an element, so neither do the nodes assigned to those sides.  Measured on the
solid ring (1.85e5 free nodes, same run, ``fem/pardiso.py``): PARDISO's analysis
0.9 s plus 0.3 s for this order against 2.5-3.7 s, and 2 % fewer factorisation flops.
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .pardiso import metis_order

#: corner pairs of the mid-edge nodes 4..9 of scikit-fem's ElementTetP2 (and of VTK's
#: tetra10): checked against the node coordinates in tests/test_solid.py
TET10_EDGES = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))


def tet10_order(elements: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """Elimination order of the nodes where ``keep`` is true, numbered 0.. among them.

    ``elements`` (elements, 10): nodes of each P2 tetrahedron, corners first, then the
    mid-edge nodes of ``TET10_EDGES``; ``keep`` (nodes,) bool.  ``order[i]`` is the
    (renumbered) kept node eliminated i-th."""
    if elements.ndim != 2 or elements.shape[1] != 10:
        raise ValueError(f"tet10_order needs (elements, 10) nodes, got {elements.shape}")
    corners = elements[:, :4]
    vertices, local = np.unique(corners, return_inverse=True)
    local = local.reshape(corners.shape).astype(np.int32)
    rows = np.repeat(local, 4, axis=1).ravel()
    cols = np.tile(local, (1, 4)).ravel()
    upper = rows <= cols
    graph = sp.csr_matrix((np.ones(int(upper.sum()), dtype=np.float32),
                           (rows[upper], cols[upper])), shape=(len(vertices),) * 2)
    graph.sum_duplicates()  # sorted unique columns, each row starting at its diagonal
    position = np.empty(len(vertices), dtype=np.int64)
    position[metis_order(graph.indptr, graph.indices)] = np.arange(len(vertices))
    # a corner eliminates at 2 p + 1, a mid-edge node at 2 p of its earlier corner p
    key = np.full(len(keep), -1, dtype=np.int64)
    key[vertices] = 2 * position + 1
    at = position[local]
    for k, (a, b) in enumerate(TET10_EDGES):
        key[elements[:, 4 + k]] = 2 * np.minimum(at[:, a], at[:, b])
    if (key < 0).any():
        raise ValueError(f"{int((key < 0).sum())} nodes belong to no tetrahedron")
    return np.argsort(key[keep], kind="stable")
