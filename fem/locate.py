"""Reference coordinates of points inside curved (isoparametric) elements.

scikit-fem's ``invF`` starts Newton's method at the element centre and stops
at an absolute step of 1e-12 in reference coordinates, which round-off alone
exceeds on small elements far from the origin (about eps |x| / h; see
``fem.facets``).  Here Newton starts from the straight-sided element through
the corners and stops when the residual is within a few ulps of the point's
coordinates; it raises only when a point is not in its element.
"""
from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix, csr_matrix

ITERATIONS = 30
#: a residual this far (relative to the element size) after Newton: not in the element
OUTSIDE = 1e-6


def reference_coordinates(mesh, points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """(dim, n) reference coordinates of ``points`` (dim, n) [m] in ``cells`` (n,)."""
    from skfem.mapping import MappingIsoparametric

    points = np.asarray(points, dtype=float)
    corners = mesh.p[:, mesh.t[:, cells]]  # (dim, dim + 1, n)
    edges = corners[:, 1:] - corners[:, :1]  # (dim, dim, n): columns are the edge vectors
    X = np.linalg.solve(edges.transpose(2, 0, 1), (points - corners[:, 0]).T[:, :, None])
    X = X[:, :, 0].T
    if mesh.affine:
        return X
    mapping = MappingIsoparametric(mesh, mesh.elem(), mesh.bndelem)
    size = np.linalg.norm(edges, axis=0).max(axis=0)  # (n,)
    floor = 8 * np.finfo(float).eps * np.abs(points).max(axis=0)
    for _ in range(ITERATIONS):
        residual = points - mapping.F(X[:, :, None], tind=cells)[:, :, 0]
        distance = np.linalg.norm(residual, axis=0)
        if np.all(distance <= np.maximum(floor, 1e-14 * size)):
            return X
        step = np.einsum("ijn,jn->in", mapping.invDF(X[:, :, None], tind=cells)[:, :, :, 0],
                         residual)
        X = X + step
    if np.any(distance > OUTSIDE * size):
        worst = int(np.argmax(distance / size))
        raise ValueError(f"point {points[:, worst].tolist()} m is not inside element "
                         f"{int(cells[worst])} (residual {distance[worst]:.1e} m)")
    return X


def interpolation_matrix(basis, points: np.ndarray, cells: np.ndarray) -> csr_matrix:
    """The sparse matrix that maps the DOFs of the vector ``basis`` to its displacement
    components at ``points`` (dim x n [m], each inside its element of ``cells``), rows
    component by component (all x, then all y, ...)."""
    dim, n = points.shape
    local = reference_coordinates(basis.mesh, points, cells)[:, :, None]
    values = np.array([basis.elem.gbasis(basis.mapping, local, k, tind=cells)[0]
                       for k in range(basis.Nbfun)]).flatten()
    rows = np.tile(np.arange(dim * n), basis.Nbfun)
    cols = basis.element_dofs[:, np.tile(cells, dim)].flatten()
    return coo_matrix((values, (rows, cols)), shape=(dim * n, basis.N)).tocsr()
