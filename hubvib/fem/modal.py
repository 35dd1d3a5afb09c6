"""Free vibration of a plane FE model: the lowest modes by shift-invert Lanczos (SI units).

``K phi = omega^2 M phi`` with the consistent mass matrix (density x
thickness).  ARPACK (``scipy.sparse.linalg.eigsh``) in shift-invert mode
about ``sigma``: a fixed start vector makes runs repeatable.  An unsupported
body has rigid-body modes at omega = 0; the shift must then be negative so
that ``K - sigma M`` stays positive definite (fe_facts: sigma = -1e4 rad^2/s^2
returns them converged).  Each mode is checked: its Rayleigh quotient equals
its eigenvalue, and a clearly negative eigenvalue (an indefinite K) raises.
Each shape is mass-normalised with its largest entry positive.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spla

from .elasticity import PlaneModel, SingularSystemError

RAYLEIGH_TOLERANCE = 1e-8


@dataclass(frozen=True)
class Modes:
    """Angular frequencies [rad/s] (ascending), mass-normalised shapes (ndofs, k)."""

    omega: np.ndarray
    shapes: np.ndarray
    rayleigh_error: float
    seconds: float

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
                 sigma: float | None = None) -> Modes:
    """The ``count`` lowest modes; ``fixed_groups`` are clamped (None: free-free)."""
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= 200:
        raise ValueError(f"count = {count!r}, allowed integers 1..200")
    started = time.perf_counter()
    K, M = model.K, mass_matrix(model)
    fe = model.basis.mesh
    free = np.arange(model.ndofs)
    if fixed_groups:
        missing = [g for g in fixed_groups if g not in fe.boundaries]
        if missing:
            raise KeyError(f"the mesh has no boundary group {', '.join(map(repr, missing))}")
        fixed = np.concatenate([model.basis.get_dofs(g).flatten() for g in fixed_groups])
        free = np.setdiff1d(free, fixed)
    Kf, Mf = K[free][:, free].tocsc(), M[free][:, free].tocsc()
    if sigma is None:
        sigma = 0.0 if fixed_groups else -1e4
    v0 = np.ones(len(free)) / np.sqrt(len(free))
    try:
        values, vectors = spla.eigsh(Kf, k=count, M=Mf, sigma=sigma, which="LM", v0=v0)
    except RuntimeError as error:  # a singular K - sigma M
        raise SingularSystemError(f"shift-invert failed ({error}); with no supports use a "
                                  "negative sigma") from None
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
    return Modes(omega, shapes, error, time.perf_counter() - started)
