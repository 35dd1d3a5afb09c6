"""Sparse symmetric positive definite solvers for ``K u = f``, chosen by problem size.

On 3D elasticity SuperLU runs out of time and memory, smoothed-aggregation AMG with the
rigid-body near-null space as CG preconditioner and PARDISO in SPD mode both finish, and on
node blocks PARDISO is also faster than SuperLU on the plane ring (the figures:
``docs/fe_accuracy.md#measured-behind-the-codes-choices``).  ``"auto"`` therefore picks

- ``"pardiso"`` when pypardiso (our MKL loader) is installed,
- else ``"superlu"`` for plane problems and anything below ``DIRECT_LIMIT`` DOFs,
- else ``"amg"`` (pyamg; each column is one preconditioned CG solve to
  ``AMG_TOLERANCE``).

A factorisation (``factorise``) serves any number of load columns, now or
later.  PARDISO takes a model's node blocks as they are (``factorise_blocks``),
factorised in single precision and refined in double to 1e-12 (``fem/pardiso.py``;
faster than pypardiso's CSR path on the solid ring), or, for
``DOUBLE_COLUMNS`` load columns and more, in double precision.  SuperLU runs
with one BLAS thread (``hubvib.foundation.blas``).  Every solver refuses a singular
(unsupported) system with ``SingularSystemError``.

Tried on the solid ring and not taken (the figures: the same page): pyamg smoothed
aggregation with the six rigid-body modes is several times slower than PARDISO for the
same c_ru; PARDISO's parallel nested dissection (``iparm[1] = 3``) and improved two-level
factorisation (``iparm[23] = 10``) gave the same times as METIS and the two-level default.
"""
from __future__ import annotations

import importlib.util

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from hubvib.fem.mkl_sparse import SymmetricBlockProduct
from hubvib.fem.pardiso import Pardiso, PardisoError
from hubvib.foundation.blas import blas_threads

SOLVERS = ("auto", "superlu", "pardiso", "amg")
DIRECT_LIMIT = 60_000  # [DOF] 3D systems below this factorise fast enough with SuperLU
AMG_TOLERANCE = 1e-10  # relative residual of the CG iteration
PIVOT_RATIO = 1e-13    # a pivot this small relative to the largest: singular
#: estimated relative error (max norm, per column) of a refined single-precision solve:
#: below what a double-precision factorisation leaves on the solid ring (~1e-13..1e-12)
REFINE_TOLERANCE = 1e-12
REFINE_STEPS = 8
#: unknowns times load columns per refined single-precision solve: the refinement's
#: temporaries and PARDISO's solve workspace grow with the columns solved at once; the
#: solid ring's 24 carrier columns go at once (each refinement step is one PARDISO solve
#: of all of them: chunks save little memory and cost time), more in chunks
SOLVE_ENTRIES = 24 * 560_000
#: from this many load columns on, a 3D system is factorised in double precision (no
#: refinement): each refined column costs about four single-precision solves and three
#: products with K; the two agree to 7e-13.  Break-even ~13 columns on the half-width
#: solid ring, ~18 estimated on the whole-width ring (factorisation ~n^2, solve ~n^1.3;
#: the figures: docs/fe_accuracy.md)
DOUBLE_COLUMNS = 24


class SingularSystemError(ValueError):
    """The stiffness matrix is singular with the given supports (rigid-body motion left)."""


def pick(method: str, ndofs: int, dim: int) -> str:
    """The solver ``method`` stands for on a system of ``ndofs`` unknowns in ``dim`` D."""
    if method not in SOLVERS:
        raise ValueError(f"solver = {method!r}; allowed: {', '.join(SOLVERS)}")
    if method != "auto":
        return method
    if importlib.util.find_spec("pypardiso"):
        return "pardiso"
    return "superlu" if dim == 2 or ndofs < DIRECT_LIMIT else "amg"


class Factor:
    """A factorised (or preconditioned) SPD system: ``solve`` any number of times, then
    ``free``.  ``method`` names the solver."""

    method = ""

    def solve(self, f: np.ndarray) -> np.ndarray:
        """``u`` with ``K u = f``; f (n,) or (n, k)."""
        f = np.asarray(f, dtype=float)
        return self._solve(f.reshape(f.shape[0], -1)).reshape(f.shape)

    def free(self) -> None:
        """Release the factorisation's memory."""

    def _solve(self, columns: np.ndarray) -> np.ndarray:
        raise NotImplementedError


def factorise(K, method: str, near_null: np.ndarray | None = None) -> Factor:
    """Factorise the SPD matrix ``K`` (whole, sparse) with the named solver (not ``"auto"``).

    ``near_null`` (n, m): rigid-body modes of the free DOFs, AMG's near-null space.
    """
    if method == "superlu":
        return _SuperLU(K)
    if method == "pardiso":
        return _PardisoFactor.from_csr(K)
    if method == "amg":
        return _AMG(K, near_null)
    raise ValueError(f"solver = {method!r}; allowed: {', '.join(SOLVERS[1:])}")


def factorise_blocks(indptr, indices, values, single: bool = True) -> Factor:
    """PARDISO on an SPD matrix given as its upper block triangle (``BlockMatrix.upper``).

    ``single``: factorise in single precision and refine each solution in double
    precision until its estimated relative error is ``REFINE_TOLERANCE`` (what a double
    factorisation leaves); if that fails, factorise again in double precision.
    """
    def matrix(dtype):
        return indptr, indices, values.astype(dtype, copy=False)

    return _PardisoFactor(matrix, values.shape[1], single,
                          lambda: _symmetric_block_matvec(indptr, indices, values))


def factorise_free_blocks(blocks, keep: np.ndarray, single: bool = True) -> Factor:
    """PARDISO on the free unknowns of a symmetric ``BlockMatrix`` ``blocks``
    (``fem.fast_assembly``): ``factorise_blocks`` of the kept nodes' upper block triangle,
    without a second double-precision copy of the matrix.

    ``keep`` (nodes,) is true at the nodes whose every component is free; (nodes, dim)
    marks each free component, and a node with some components held stays a block:
    those rows and columns are zero, the diagonal entry kept (``_hold_components``), so
    the held unknowns decouple and come out exactly zero (a symmetry plane's u_z = 0).
    The factor then solves for the free unknowns only, in ``keep``'s order.

    PARDISO gets the upper block triangle in the factorisation's precision only
    (single: float32, half the bytes); the refinement multiplies by ``blocks`` itself,
    the unknowns set in a whole vector with zeros at the other nodes.  This saves a
    double copy of the matrix during the factorisation's peak.
    """
    dim = blocks.pattern.dim
    keep = np.asarray(keep, dtype=bool)
    free = keep.reshape(-1, dim) if keep.ndim == 2 else np.repeat(keep[:, None], dim, axis=1)
    nodes = free.any(axis=1)
    held = ~free[nodes]  # (kept nodes, dim)

    def matrix(dtype):
        upper = blocks.upper(nodes, dtype)
        return upper if not held.any() else _hold_components(*upper, held)

    def matvec():
        p = blocks.pattern
        whole = _FreeMatvec(_symmetric_block_matvec(p.indptr, p.indices, blocks.values),
                            np.repeat(nodes, dim))
        if not held.any():
            return whole
        diagonal = blocks.values[p.indptr[:-1]][nodes].diagonal(axis1=1, axis2=2)
        return _HeldMatvec(whole, held.ravel(), diagonal[held])

    factor = _PardisoFactor(matrix, dim, single, matvec)
    return factor if not held.any() else _FreeOfHeld(factor, np.flatnonzero(~held.ravel()),
                                                     held.size)


def _hold_components(indptr, indices, values, held: np.ndarray):
    """The block-CSR upper triangle ``(indptr, indices, values)`` with the rows and columns
    of the ``held`` components (nodes, dim) zero and their diagonal entries kept: a held
    unknown's equation is ``K_ii u_i = f_i``, coupled to nothing (values changed in place)."""
    rows = np.repeat(np.arange(len(indptr) - 1), np.diff(indptr))
    diagonal = values[indptr[:-1]].diagonal(axis1=1, axis2=2).copy()
    values *= ~held[rows][:, :, None]
    values *= ~held[indices][:, None, :]
    node, component = np.nonzero(held)
    values[indptr[:-1][node], component, component] = diagonal[node, component]
    return indptr, indices, values


class _HeldMatvec:
    """``x -> K' x`` for ``_hold_components``' matrix K' from the kept nodes' ``matvec``:
    the held unknowns out of the product, ``K_ii x_i`` in their rows."""

    def __init__(self, matvec, held: np.ndarray, diagonal: np.ndarray):
        self._matvec, self._held, self._diagonal = matvec, held, diagonal

    def __call__(self, x):
        x = np.array(x, dtype=float)
        on_held = x[self._held]
        x[self._held] = 0.0
        y = self._matvec(x)
        y[self._held] = self._diagonal.reshape((-1,) + (1,) * (x.ndim - 1)) * on_held
        return y


class _FreeOfHeld(Factor):
    """A factor over the kept nodes' ``size`` unknowns (held ones included, zero) solving
    for the free unknowns only, at positions ``free`` of the kept nodes' unknowns."""

    method = "pardiso"

    def __init__(self, factor: Factor, free: np.ndarray, size: int):
        self._factor, self._free, self._size = factor, free, size

    def _solve(self, columns):
        whole = np.zeros((self._size, columns.shape[1]))
        whole[self._free] = columns
        return self._factor.solve(whole)[self._free]

    def free(self):
        self._factor.free()


def _csc_of_symmetric(K):
    """CSC of a symmetric matrix: its CSR arrays read column-wise (no conversion)."""
    if sp.issparse(K) and K.format == "csr":
        return sp.csc_matrix((K.data, K.indices, K.indptr), shape=K.shape)
    return sp.csc_matrix(K)


class _SuperLU(Factor):
    method = "superlu"

    def __init__(self, K):
        try:
            with blas_threads(1):
                self._lu = spla.splu(_csc_of_symmetric(K), permc_spec="COLAMD")
        except RuntimeError as error:
            raise SingularSystemError(
                f"the supported stiffness matrix is singular: {error}") from None
        diag = np.abs(self._lu.U.diagonal())
        if diag.min() <= PIVOT_RATIO * diag.max():
            raise SingularSystemError(
                f"the supported stiffness matrix is singular to working precision (pivot ratio "
                f"{diag.min() / diag.max():.1e}): check the supports")

    def _solve(self, columns):
        with blas_threads(1):  # small BLAS kernels: more threads only wait (foundation/blas.py)
            return self._lu.solve(columns)

    def free(self):
        self._lu = None


class _PardisoFactor(Factor):
    method = "pardiso"

    def __init__(self, matrix, block: int = 1, single: bool = False, matvec=None):
        self._matrix = matrix  # dtype -> the upper (block) triangle (indptr, indices, values)
        self._block = block
        self._single = single
        self._make_matvec = matvec  # built when first needed: after the factorisation's peak
        self._matvec = None
        self._pardiso = self._factorise(single)

    def _factorise(self, single: bool):
        try:
            factor = Pardiso(*self._matrix(np.float32 if single else np.float64),
                             self._block, single=single)
        except PardisoError as error:
            if single:  # too ill-conditioned for float32: try again in double
                return self._factorise(False)
            raise SingularSystemError(f"PARDISO: the supported stiffness matrix is not positive "
                                      f"definite ({error}): check the supports") from None
        self._single = single
        if not single:  # no refinement: the matrix is not needed again
            self._matrix = self._make_matvec = None
        return factor

    @classmethod
    def from_csr(cls, K) -> "_PardisoFactor":
        upper = sp.triu(K, format="csr")
        upper.sort_indices()
        return cls(lambda dtype: (upper.indptr, upper.indices, upper.data.astype(dtype)))

    def _solve(self, columns):
        if not self._single:
            return self._pardiso.solve(columns)
        if self._matvec is None:
            self._matvec = self._make_matvec()
        chunk = max(1, SOLVE_ENTRIES // len(columns))
        if columns.shape[1] <= chunk:
            return self._refined(columns)
        u = np.empty_like(columns)
        for first in range(0, columns.shape[1], chunk):
            part = slice(first, first + chunk)
            u[:, part] = self._refined(columns[:, part]) if self._single \
                else self._pardiso.solve(columns[:, part])
        return u

    def _refined(self, columns):
        """The single-precision solve refined in double (or, where refinement stalls, the
        solve of a double-precision factorisation made then)."""
        u = self._pardiso.solve(columns).astype(float)
        previous = None
        for _ in range(REFINE_STEPS):
            step = self._pardiso.solve(columns - self._matvec(u)).astype(float)
            u += step
            tiny = np.finfo(float).tiny
            size = np.abs(step).max(axis=0) / np.maximum(np.abs(u).max(axis=0), tiny)
            if not size.any():
                return u
            if previous is not None:
                # each step shrinks the error by ``rate``: what is left after this one
                rate = size / np.maximum(previous, tiny)
                if np.all((rate < 0.5) & (size * rate / (1 - rate) <= REFINE_TOLERANCE)):
                    return u
            previous = size
        self._pardiso.free()  # refinement stalls: the float32 factor is not good enough
        self._pardiso = self._factorise(False)
        return self._pardiso.solve(columns)

    def free(self):
        self._pardiso.free()
        self._matvec = self._make_matvec = None  # releases MKL's sparse handle too


def _symmetric_block_matvec(indptr, indices, values) -> SymmetricBlockProduct:
    """``x -> K x`` for the symmetric K whose upper block triangle is given (block CSR):
    MKL's symmetric block product, sharing the arrays (no copy of the matrix: a CSR copy
    was the peak of the solid ring's solve)."""
    return SymmetricBlockProduct(indptr, indices, values)


class _FreeMatvec:
    """``x -> K_ff x`` on the free unknowns (``free`` mask over all of K's rows) from the
    whole matrix's ``matvec``: x goes into a whole vector with zeros elsewhere."""

    def __init__(self, matvec, free: np.ndarray):
        self._matvec = matvec
        self._free = free

    def __call__(self, x):
        x = np.asarray(x)
        whole = np.zeros((len(self._free),) + x.shape[1:])
        whole[self._free] = x
        return self._matvec(whole)[self._free]


class _AMG(Factor):
    method = "amg"

    def __init__(self, K, near_null):
        import pyamg

        self._hierarchy = pyamg.smoothed_aggregation_solver(sp.csr_matrix(K), B=near_null,
                                                            symmetry="symmetric")

    def _solve(self, columns):
        u = np.empty_like(columns)
        for j in range(columns.shape[1]):
            residuals = []
            u[:, j] = self._hierarchy.solve(columns[:, j], tol=AMG_TOLERANCE, accel="cg",
                                            maxiter=500, residuals=residuals)
            reached = residuals[-1] / max(residuals[0], np.finfo(float).tiny)
            if not np.isfinite(reached) or reached > 10 * AMG_TOLERANCE:
                raise SingularSystemError(
                    f"AMG-CG stalled at relative residual {reached:.1e} after "
                    f"{len(residuals) - 1} iterations: the system is singular or badly "
                    "conditioned; check the supports")
        return u

    def free(self):
        self._hierarchy = None
