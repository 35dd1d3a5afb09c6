"""Sparse symmetric positive definite solvers for ``K u = f``, chosen by problem size.

Measured on 2 cores (``validation/benchmark.py`` and fe_facts.md, 3D elasticity
~3e5 DOF): SuperLU does not finish in 330 s (13 GB), smoothed-aggregation AMG
with the rigid-body near-null space as CG preconditioner takes 7-15 s (1 GB),
PARDISO in SPD mode ~10 s (2.5 GB).  Plane problems up to ~3e5 DOF solve in
seconds with SuperLU.  ``"auto"`` therefore picks

- ``"superlu"`` for plane problems and for anything below ``DIRECT_LIMIT`` DOFs,
- else ``"pardiso"`` when pypardiso is installed (one factorisation serves every
  load column),
- else ``"amg"`` (pyamg; each column is one preconditioned CG solve to
  ``AMG_TOLERANCE``).

Every solver refuses a singular (unsupported) system with ``SingularSystemError``.
"""
from __future__ import annotations

import importlib.util

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

SOLVERS = ("auto", "superlu", "pardiso", "amg")
DIRECT_LIMIT = 60_000  # [DOF] 3D systems below this factorise fast enough with SuperLU
AMG_TOLERANCE = 1e-10  # relative residual of the CG iteration
PIVOT_RATIO = 1e-13    # a pivot this small relative to the largest: singular


class SingularSystemError(ValueError):
    """The stiffness matrix is singular with the given supports (rigid-body motion left)."""


def pick(method: str, ndofs: int, dim: int) -> str:
    """The solver ``method`` stands for on a system of ``ndofs`` unknowns in ``dim`` D."""
    if method not in SOLVERS:
        raise ValueError(f"solver = {method!r}; allowed: {', '.join(SOLVERS)}")
    if method != "auto":
        return method
    if dim == 2 or ndofs < DIRECT_LIMIT:
        return "superlu"
    return "pardiso" if importlib.util.find_spec("pypardiso") else "amg"


def solve_spd(K, f: np.ndarray, method: str, near_null: np.ndarray | None = None
              ) -> np.ndarray:
    """Solve ``K u = f`` (f: (n,) or (n, k)) with the named solver (not ``"auto"``).

    ``near_null`` (n, m): rigid-body modes of the free DOFs, AMG's near-null space.
    """
    f = np.asarray(f, dtype=float)
    columns = f.reshape(K.shape[0], -1)
    if method == "superlu":
        u = _superlu(K, columns)
    elif method == "pardiso":
        u = _pardiso(K, columns)
    elif method == "amg":
        u = _amg(K, columns, near_null)
    else:
        raise ValueError(f"solver = {method!r}; allowed: {', '.join(SOLVERS[1:])}")
    return u.reshape(f.shape)


def _superlu(K, f):
    try:
        lu = spla.splu(sp.csc_matrix(K), permc_spec="COLAMD")
    except RuntimeError as error:
        raise SingularSystemError(f"the supported stiffness matrix is singular: {error}") from None
    diag = np.abs(lu.U.diagonal())
    if diag.min() <= PIVOT_RATIO * diag.max():
        raise SingularSystemError(
            f"the supported stiffness matrix is singular to working precision (pivot ratio "
            f"{diag.min() / diag.max():.1e}): check the supports")
    return lu.solve(f)


def _pardiso(K, f):
    import pypardiso
    from pypardiso.pardiso_wrapper import PyPardisoError

    solver = pypardiso.PyPardisoSolver(mtype=2)  # real SPD: Cholesky on the upper triangle
    upper = sp.triu(K, format="csr")
    try:
        solver.factorize(upper)
        u = solver.solve(upper, f)
    except PyPardisoError as error:
        raise SingularSystemError(f"PARDISO: the supported stiffness matrix is not positive "
                                  f"definite ({error}): check the supports") from None
    finally:
        solver.free_memory(everything=True)
    return u.reshape(f.shape)


def _amg(K, f, near_null):
    import pyamg

    K = sp.csr_matrix(K)
    hierarchy = pyamg.smoothed_aggregation_solver(K, B=near_null, symmetry="symmetric")
    u = np.empty_like(f)
    for j in range(f.shape[1]):
        residuals = []
        u[:, j] = hierarchy.solve(f[:, j], tol=AMG_TOLERANCE, accel="cg", maxiter=500,
                                  residuals=residuals)
        reached = residuals[-1] / max(residuals[0], np.finfo(float).tiny)
        if not np.isfinite(reached) or reached > 10 * AMG_TOLERANCE:
            raise SingularSystemError(
                f"AMG-CG stalled at relative residual {reached:.1e} after {len(residuals) - 1} "
                "iterations: the system is singular or badly conditioned; check the supports")
    return u
