"""Free vibration of a plane FE model: the lowest modes by shift-invert Lanczos (SI units).

``K phi = omega^2 M phi`` with the consistent mass matrix (density x
thickness).  ARPACK (``scipy.sparse.linalg.eigsh``) in shift-invert mode
about ``sigma``: a fixed start vector makes runs repeatable.  An unsupported
body has rigid-body modes at omega = 0; the shift must then be negative so
that ``K - sigma M`` stays positive definite (fe_facts: sigma = -1e4 rad^2/s^2
returns them converged).  Each mode is checked: its Rayleigh quotient equals
its eigenvalue, and a clearly negative eigenvalue (an indefinite K) raises.
Each shape is mass-normalised with its largest entry positive.

``(K - sigma M)^-1`` comes from the project's solvers (``fem.solvers.pick``): with
PARDISO a double-precision Cholesky factor of the free DOFs' CSR matrix where that
matrix is positive definite (sigma < 0, or 0 with supports), else ARPACK's own SuperLU.
ARPACK's iteration and the solves run on one BLAS (and MKL) thread: on two cores the
second only spin-waits.  PARDISO on one thread is the fastest of SuperLU and PARDISO,
on the default or one thread, on the CSR matrix or the node blocks (the figures:
``docs/fe_accuracy.md``, Speed and memory).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spla

from hubvib.foundation.blas import blas_threads

from .elasticity import PlaneModel, SingularSystemError, submatrix
from .pardiso import mkl_library
from .solvers import factorise, pick

RAYLEIGH_TOLERANCE = 1e-8
#: the factorisations ``lowest_modes`` can take (AMG gives no shift-invert operator)
MODAL_SOLVERS = ("auto", "pardiso", "superlu")


@dataclass(frozen=True)
class Modes:
    """Angular frequencies [rad/s] (ascending), mass-normalised shapes (ndofs, k), and the
    factorisation of the shift-invert operator (``"pardiso"`` or ``"superlu"``)."""

    omega: np.ndarray
    shapes: np.ndarray
    rayleigh_error: float
    seconds: float
    solver: str

    @property
    def hertz(self) -> np.ndarray:
        return self.omega / (2 * np.pi)


def mass_matrix(model: PlaneModel):
    """Consistent mass matrix [kg] (density x thickness x int u.v)."""
    import skfem

    @skfem.BilinearForm
    def mass(u, v, w):
        return u[0] * v[0] + u[1] * v[1]

    return (model.material.density * model.thickness * mass.assemble(model.basis)).tocsr()


def lowest_modes(model: PlaneModel, count: int = 6, fixed_groups: list[str] | None = None,
                 sigma: float | None = None, solver: str = "auto") -> Modes:
    """The ``count`` lowest modes; ``fixed_groups`` are clamped (None: free-free).

    ``solver``: ``"auto"`` (as ``fem.solvers.pick``), ``"pardiso"`` or ``"superlu"``, for
    the factorisation of ``K - sigma M``: PARDISO where picked, its library loads and that
    matrix is positive definite (sigma < 0, or 0 with supports), else ARPACK's own SuperLU.
    ``Modes.solver`` names the one used.
    """
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= 200:
        raise ValueError(f"count = {count!r}, allowed integers 1..200")
    if solver not in MODAL_SOLVERS:
        raise ValueError(f"solver = {solver!r}; allowed: {', '.join(MODAL_SOLVERS)}")
    started = time.perf_counter()
    K, M = model.K, mass_matrix(model)
    fe = model.basis.mesh
    keep = np.ones(model.ndofs, dtype=bool)
    if fixed_groups:
        missing = [g for g in fixed_groups if g not in fe.boundaries]
        if missing:
            raise KeyError(f"the mesh has no boundary group {', '.join(map(repr, missing))}")
        keep[np.concatenate([model.basis.get_dofs(g).flatten() for g in fixed_groups])] = False
    free = np.flatnonzero(keep)
    Kf, Mf = submatrix(K, keep), submatrix(M, keep)
    if sigma is None:
        sigma = 0.0 if fixed_groups else -1e4
    v0 = np.ones(len(free)) / np.sqrt(len(free))
    method = pick(solver, len(free), fe.dim())
    # PARDISO's Cholesky needs K - sigma M positive definite: a negative shift, or supports
    use_pardiso = method == "pardiso" and (sigma < 0 or (sigma == 0 and bool(fixed_groups)))
    if use_pardiso:
        try:  # loaded before blas_threads looks for it, so that MKL is limited too
            mkl_library()
        except (OSError, AttributeError):  # pypardiso found, its MKL not loadable
            use_pardiso = False
    factor = None
    try:
        # ARPACK's and the solves' small BLAS kernels only spin-wait on a second thread;
        # the factorisation too is fastest there on one
        with blas_threads(1):
            if use_pardiso:
                try:
                    factor = factorise(Kf - sigma * Mf if sigma else Kf, "pardiso")
                except SingularSystemError:
                    raise SingularSystemError(
                        f"K - sigma M is not positive definite (sigma = {sigma:g} rad^2/s^2): "
                        f"check the supports {fixed_groups}, or K is indefinite") from None
                inverse = spla.LinearOperator(Kf.shape, matvec=factor.solve, dtype=float)
            else:
                inverse = None  # ARPACK factorises K - sigma M with SuperLU
            values, vectors = spla.eigsh(Kf, k=count, M=Mf, sigma=sigma, which="LM", v0=v0,
                                         OPinv=inverse)
    except RuntimeError as error:  # a singular K - sigma M
        raise SingularSystemError(f"shift-invert failed ({error}); with no supports use a "
                                  "negative sigma") from None
    finally:
        if factor is not None:
            factor.free()
    order = np.argsort(values)
    values, vectors = values[order], vectors[:, order]
    scale = np.sqrt(np.abs(np.diag(vectors.T @ (Mf @ vectors))))
    largest = vectors[np.argmax(np.abs(vectors), axis=0), np.arange(count)]
    vectors = vectors / (scale * np.sign(largest))  # sign fixed: largest entry positive
    rayleigh = np.array([(v @ (Kf @ v)) / (v @ (Mf @ v)) for v in vectors.T])
    reference = max(abs(values).max(), 1.0)
    error = float(np.max(np.abs(rayleigh - values)) / reference)
    if error > RAYLEIGH_TOLERANCE:
        raise ArithmeticError(f"eigsh returned modes whose Rayleigh quotient differs from the "
                              f"eigenvalue by {error:.1e} (relative)")
    floor = 1e-8 * reference
    if values.min() < -floor:
        raise SingularSystemError(f"negative eigenvalue {values.min():.3e}: K is indefinite")
    shapes = np.zeros((model.ndofs, count))
    shapes[free] = vectors
    omega = np.sqrt(np.clip(values, 0.0, None))
    return Modes(omega, shapes, error, time.perf_counter() - started,
                 "pardiso" if use_pardiso else "superlu")
