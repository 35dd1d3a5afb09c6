"""``fem.ring_positions`` gives the same Gram matrices and functionals whatever the memory
order of the static responses it is handed (row- or column-major), each static of unit
M-norm: on a small synthetic body (no mesh)."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from hubvib.fem.ring_positions import ring_positions


def _body_and_basis(order: str, functionals: int):
    rng = np.random.default_rng(1)
    n, modes, teeth = 60, 4, 3
    A = sp.random(n, n, density=0.1, random_state=2)
    K = (A @ A.T + n * sp.identity(n)).tocsr()
    M = (sp.identity(n) + 0.1 * sp.diags(rng.random(n))).tocsr()
    w, phi = sla.eigh(K.toarray(), M.toarray())
    basis_K = np.diag(w[:modes])
    blocks = [rng.standard_normal((n, k)) for k in (teeth, teeth, functionals)]
    first, second, functional = (np.asarray(b, order=order) for b in blocks)
    responses = SimpleNamespace(teeth=tuple(range(teeth)), first=first, second=second,
                                functional=functional)
    basis = SimpleNamespace(V=phi[:, :modes], modes=modes, K=basis_K, responses=responses)
    body = SimpleNamespace(M=M, K=K, ndofs=n, contact=sp.csc_matrix(rng.random((n, teeth))),
                           probe=sp.csr_matrix(rng.random((8, n))))
    rows = sp.csc_matrix(rng.random((n, functionals))) if functionals else None
    return body, basis, rows


def test_the_same_positions_from_either_memory_order():
    for functionals in (0, 2):
        out = {order: ring_positions(*_body_and_basis(order, functionals))
               for order in ("C", "F")}
        for name in ("gram_M", "gram_K", "static_contact", "static_probe", "static_rows"):
            a, b = getattr(out["C"], name), getattr(out["F"], name)
            assert np.allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(b).max(initial=1.0)), name
        for positions in out.values():
            assert np.allclose(np.diag(positions.gram_M), 1.0, rtol=1e-12)
