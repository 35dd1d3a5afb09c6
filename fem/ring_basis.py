"""A reduced ring for coupled vibration: its own modes below a cut-off and the residual
flexibility of the planets' contacts (SI units).

Free-interface component mode synthesis (MacNeal / Rubin): the Ritz basis holds the
mounted ring's modes up to ``cutoff`` [Hz] and, for each contact tooth the coupled model
will load, the static response ``(K - sigma M)^-1 b_k`` of its contact load, made
M-orthogonal to the modes.  Free interfaces suit this coupling: the interface of a planet
is one functional (the patch's mean displacement along the line of action), so each
costs one vector, where Craig-Bampton would keep every node of every load patch and every
support node as a DOF.  The mounting is in the ring's own matrices, so it needs no
interface of its own.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse.linalg as spla

from hubvib.foundation.blas import blas_threads

from .ring_body import RingBody
from .solvers import SingularSystemError, factorise, pick

#: shift for a ring with rigid-body modes (free-free) [rad^2/s^2]: K - sigma M is then
#: positive definite
FREE_SHIFT = -1e4
#: modes asked of ARPACK per round while the highest found is below the cut-off
MODES_PER_ROUND = 24
MAX_MODES = 400
RAYLEIGH_TOLERANCE = 1e-8


@dataclass(frozen=True, eq=False)
class RingBasis:
    """The reduced ring: ``u = V q`` with V M-orthonormal.

    Attributes
    ----------
    V : ndarray (dofs, m)
        Ritz basis [m per unit q]: the ring's modes, then the contacts' static responses.
    K : ndarray (m, m)
        Reduced stiffness ``V^T K V`` [N/m]; ``V^T M V`` is the identity [kg] to round-off.
    mode_hz : ndarray
        The mounted ring's own frequencies in the basis [Hz], ascending.
    cutoff_hz : float
    teeth : tuple of int
        Teeth whose contact responses are in the basis.
    solver : str
    responses : Responses or None
        The raw static responses asked for beside the basis (not M-orthogonalised).
    """

    V: np.ndarray
    K: np.ndarray
    mode_hz: np.ndarray
    cutoff_hz: float
    teeth: tuple
    solver: str
    responses: "Responses | None" = None

    @property
    def size(self) -> int:
        return self.V.shape[1]

    @property
    def modes(self) -> int:
        """Number of the ring's own modes (the first columns of V)."""
        return self.mode_hz.size


@dataclass(frozen=True, eq=False)
class Responses:
    """Raw static responses ``(K - sigma M)^-1 load`` from the basis's factorisation.

    ``teeth``: the teeth; ``first`` (dofs, teeth): to each tooth's contact load [m/N];
    ``second`` (dofs, teeth): to the inertia of ``first``; ``functional`` (dofs, p): to
    the functionals' loads.
    """

    teeth: tuple
    first: np.ndarray
    second: np.ndarray
    functional: np.ndarray


def ring_modes(body: RingBody, cutoff_hz: float, solver: str = "auto"):
    """The mounted ring's modes up to ``cutoff_hz`` [Hz]: (omega [rad/s], shapes (dofs, k)
    M-normalised), and the factor of ``K - sigma M`` (caller frees it) with its shift."""
    if not (np.isfinite(cutoff_hz) and cutoff_hz > 0):
        raise ValueError(f"cutoff_hz = {cutoff_hz!r}, allowed > 0 Hz")
    sigma = FREE_SHIFT if body.mounting == "free" else 0.0
    A = (body.K - sigma * body.M).tocsr() if sigma else body.K
    method = pick(solver, body.ndofs, 2)
    method = "superlu" if method == "amg" else method
    try:
        factor = factorise(A, method)
    except SingularSystemError:
        raise SingularSystemError(f"the ring's K - sigma M (sigma = {sigma:g} rad^2/s^2, "
                                  f"mounting {body.mounting!r}) is singular") from None
    inverse = spla.LinearOperator(A.shape, matvec=factor.solve, dtype=float)
    target = (2 * np.pi * cutoff_hz) ** 2
    count = MODES_PER_ROUND
    v0 = np.ones(body.ndofs) / np.sqrt(body.ndofs)
    with blas_threads(1):
        while True:
            count = min(count, MAX_MODES, body.ndofs - 2)
            values, vectors = spla.eigsh(body.K, k=count, M=body.M, sigma=sigma, which="LM",
                                         v0=v0, OPinv=inverse)
            order = np.argsort(values)
            values, vectors = values[order], vectors[:, order]
            if values[-1] > target or count >= min(MAX_MODES, body.ndofs - 2):
                break
            count *= 2
    keep = values <= target
    values, vectors = values[keep], vectors[:, keep]
    vectors = vectors / np.sqrt(np.einsum("ij,ij->j", vectors, body.M @ vectors))
    rayleigh = np.einsum("ij,ij->j", vectors, body.K @ vectors)
    scale = max(float(np.abs(values).max(initial=0.0)), target)
    error = float(np.max(np.abs(rayleigh - values), initial=0.0)) / scale
    if error > RAYLEIGH_TOLERANCE:
        factor.free()
        raise ArithmeticError(f"the ring's modes fail their Rayleigh check: relative error "
                              f"{error:.2e} > {RAYLEIGH_TOLERANCE:g}")
    omega = np.sqrt(np.clip(values, 0.0, None))
    return omega, vectors, factor, sigma


def ring_basis(body: RingBody, teeth, cutoff_hz: float, solver: str = "auto",
               more_teeth=(), functionals=None) -> RingBasis:
    """The Ritz basis of ``body`` for contacts on ``teeth``: modes up to ``cutoff_hz``
    [Hz] and, per tooth, the static response to its contact load and the response to
    that response's inertia (two Krylov vectors of ``(K - sigma M)^-1 M``).

    ``more_teeth`` and ``functionals`` (sparse (dofs, p), e.g. crack-face pair loads): their
    responses from the same factorisation, kept apart (``RingBasis.responses``, for
    ``fem.ring_positions``); the basis itself is as without them."""
    teeth = tuple(sorted({int(k) for k in teeth}))
    more = tuple(sorted({int(k) for k in more_teeth} - set(teeth)))
    omega, phi, factor, sigma = ring_modes(body, cutoff_hz, solver)
    responses = None
    with blas_threads(1):  # tall-skinny dense products: one thread is fastest on a busy host
        try:
            static = _krylov(body, factor, teeth)
            if more or functionals is not None:
                extra = _krylov(body, factor, more)
                loads = np.zeros((body.ndofs, 0)) if functionals is None else (
                    functionals.toarray() if hasattr(functionals, "toarray")
                    else np.asarray(functionals))
                response = np.asarray(factor.solve(loads)).reshape(body.ndofs, loads.shape[1]) \
                    if loads.shape[1] else loads
                n = len(teeth)
                responses = Responses(
                    teeth + more,
                    np.hstack([static[:, :n], extra[:, :len(more)]]),
                    np.hstack([static[:, n:], extra[:, len(more):]]), response)
        finally:
            factor.free()
        static = static - phi @ (phi.T @ (body.M @ static))
        static = static - phi @ (phi.T @ (body.M @ static))  # twice: Gram-Schmidt to round-off
        if static.shape[1]:
            static = static / np.sqrt(np.einsum("ij,ij->j", static, body.M @ static))
            gram = static.T @ (body.M @ static)
            w, U = np.linalg.eigh(0.5 * (gram + gram.T))
            useful = w > 1e-12 * w.max()
            static = static @ (U[:, useful] / np.sqrt(w[useful]))
        V = np.hstack([phi, static])
        K = V.T @ (body.K @ V)
        M = V.T @ (body.M @ V)
        # V is M-orthonormal to round-off; one Cholesky step makes it so to the last digits
        L = sla.cholesky(0.5 * (M + M.T), lower=True)
        V = sla.solve_triangular(L, V.T, lower=True).T
        K = V.T @ (body.K @ V)
    return RingBasis(V, 0.5 * (K + K.T), omega / (2 * np.pi), float(cutoff_hz), teeth,
                     factor.method, responses)


def _krylov(body: RingBody, factor, teeth) -> np.ndarray:
    """Static responses to the teeth's contact loads, then the responses to their inertia
    (dofs, 2 teeth)."""
    if not teeth:
        return np.zeros((body.ndofs, 0))
    loads = body.contact[:, list(teeth)].toarray()
    first = np.asarray(factor.solve(loads)).reshape(body.ndofs, len(teeth))
    # the second Krylov vector of each contact (its inertia-loaded response): the
    # truncated modes' inertia, to fourth order in omega / omega_cut
    second = np.asarray(factor.solve(body.M @ first)).reshape(body.ndofs, len(teeth))
    return np.hstack([first, second])
