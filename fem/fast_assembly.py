"""Isotropic linear-elasticity stiffness assembled in whole-array operations (SI units).

scikit-fem's generic form assembly evaluates the weak form once per pair of
local basis functions (900 calls for P2 tetrahedra); here all element
matrices of a chunk of elements come from three ``einsum`` calls on the
scalar shape-function gradients.  Same quadrature, same matrix (to rounding:
``tests/test_solid.py``), ~3x less time in 3D.
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

CHUNK = 20_000  # elements per block: bounds the (chunk, n, d, n, d) temporaries


def elasticity_matrix(basis, lam: float, mu: float):
    """K [N/m] of a scikit-fem ``ElementVector`` basis for Lame constants ``lam``, ``mu`` [Pa]."""
    import skfem

    scalar = skfem.CellBasis(basis.mesh, basis.elem.elem, quadrature=basis.quadrature)
    dim = basis.mesh.dim()
    n = scalar.Nbfun
    # gradients (elements, points, functions, dim) and weights (elements, points)
    grads = np.stack([scalar.basis[a][0].grad for a in range(n)]).transpose(2, 3, 0, 1)
    weights = scalar.dx
    # ElementVector numbers local DOFs function-major: local dof 3 a + i is component i
    # of scalar function a
    dofs = basis.element_dofs.T.reshape(-1, n, dim).astype(np.int32)
    eye = np.eye(dim)
    size = (n * dim) ** 2
    rows = np.empty(basis.mesh.nelements * size, dtype=np.int32)
    cols = np.empty_like(rows)
    data = np.empty(len(rows))
    for start in range(0, basis.mesh.nelements, CHUNK):
        block = slice(start, start + CHUNK)
        g, w = grads[block], weights[block]
        outer = np.einsum("eqai,eqbj->eaibj", g * w[:, :, None, None], g)  # sum_q w G_ai G_bj
        dot = np.einsum("eaibi->eab", outer)
        k = lam * outer + mu * outer.transpose(0, 1, 4, 3, 2)
        k += mu * dot[:, :, None, :, None] * eye[None, None, :, None, :]
        d = dofs[block]
        out = slice(start * size, start * size + k.size)
        rows[out] = np.broadcast_to(d[:, :, :, None, None], k.shape).ravel()
        cols[out] = np.broadcast_to(d[:, None, None, :, :], k.shape).ravel()
        data[out] = k.ravel()
    return sp.coo_matrix((data, (rows, cols)), shape=(basis.N, basis.N)).tocsr()
