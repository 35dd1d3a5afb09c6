"""The reduced ring for many carrier positions at once: one Ritz basis per position, each
the ring's modes plus the contact responses of the teeth engaged there (and, optionally,
of further functionals such as crack-face pairs), from one set of static responses (SI).

``fem.ring_basis`` builds one basis for a few positions.  Over a planet pitch every tooth
is engaged somewhere, and one basis holding all of them would be several times larger
than any position needs.  Here every static response is made M-orthogonal to the modes
once (``S' = S - phi phi^T M S``) and kept as Gram matrices ``S'^T M S'`` and
``S'^T K S'``; a position's basis ``[phi, S'_sel T]`` (``T`` orthonormalising the selected
columns) then costs only small dense algebra.  Because ``K phi = M phi Lambda``, the modes
and ``S'`` are K-orthogonal as well, so the reduced stiffness is block diagonal.  A
position's basis spans exactly what ``ring_basis`` builds for the same teeth.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubvib.foundation.blas import blas_threads

from .ring_basis import RingBasis
from .ring_body import RingBody

#: a selected static direction is kept when its Gram eigenvalue exceeds this share of the
#: largest (as in ``ring_basis``)
USEFUL = 1e-12


@dataclass(frozen=True, eq=False)
class RingPositions:
    """What every position's basis is assembled from (coordinates: the modes, then the
    deflated statics ``S'``, each of unit M-norm).

    Attributes
    ----------
    phi_K : ndarray (n, n)
        The reduced stiffness on the modes (diagonal, omega^2, to round-off) [N/m].
    phi_contact, static_contact : ndarray (n, z), (s, z)
        Each tooth's contact functional on the modes and on the statics [m per unit].
    phi_probe, static_probe : ndarray (2 P, n), (2 P, s)
        The mid-rim probe [m per unit].
    phi_rows, static_rows : ndarray (q, n), (q, s)
        The extra functionals (``functionals.T``) [m per unit].
    gram_M, gram_K : ndarray (s, s)
        ``S'^T M S'`` [kg], ``S'^T K S'`` [N/m].
    first, second : dict tooth -> column of S'
    functional_columns : ndarray of int
        Columns of S' holding the functionals' responses.
    """

    phi_K: np.ndarray
    phi_contact: np.ndarray
    static_contact: np.ndarray
    phi_probe: np.ndarray
    static_probe: np.ndarray
    phi_rows: np.ndarray
    static_rows: np.ndarray
    gram_M: np.ndarray
    gram_K: np.ndarray
    first: dict
    second: dict
    functional_columns: np.ndarray

    @property
    def teeth(self) -> tuple:
        return tuple(sorted(self.first))


@dataclass(frozen=True, eq=False)
class PositionBasis:
    """One position's reduced ring (M = I): stiffness ``K`` [N/m], ``contact`` (m, z),
    ``probe`` (2 P, m), ``rows`` (q, m): the extra functionals on its coordinates."""

    K: np.ndarray
    contact: np.ndarray
    probe: np.ndarray
    rows: np.ndarray


def ring_positions(body: RingBody, basis: RingBasis, functionals=None) -> RingPositions:
    """From a basis built with ``more_teeth`` and ``functionals`` (its ``responses``);
    ``functionals``: the same sparse (dofs, q) matrix, for the rows."""
    raw = basis.responses
    if raw is None:
        raise ValueError("ring_positions: the basis holds no responses; build it with "
                         "more_teeth or functionals")
    phi = basis.V[:, :basis.modes]
    z = len(raw.teeth)
    with blas_threads(1):
        S = np.hstack([raw.first, raw.second, raw.functional])
        MS, Mphi = body.M @ S, body.M @ phi
        step = np.empty_like(S)  # (dofs, many): updated in place, not allocated anew
        for _ in range(2):  # twice: Gram-Schmidt to round-off (M S updated, not remade)
            C = phi.T @ MS
            S -= np.matmul(phi, C, out=step)
            MS -= np.matmul(Mphi, C, out=step)
        del step
        # the sparse products and the column sums read S row by row: one row-major copy
        # serves them all (each would copy a column-major S; the sums are the same)
        S_rows = np.ascontiguousarray(S)  # S itself when row-major already
        norm = 1 / np.sqrt(np.einsum("ij,ij->j", S_rows, MS))
        S *= norm
        if not np.shares_memory(S_rows, S):
            S_rows *= norm
        MS *= norm
        gram_M = S.T @ MS
        del MS
        gram_K = S.T @ (body.K @ S_rows)
        rows = np.zeros((0, body.ndofs)) if functionals is None else functionals.T
        phi_rows, static_rows = np.asarray(rows @ phi), np.asarray(rows @ S_rows)
        contact_T = body.contact.T
        probe = body.probe
        out = RingPositions(
            basis.K[:basis.modes, :basis.modes], np.asarray(contact_T @ phi).T,
            np.asarray(contact_T @ S_rows).T, np.asarray(probe @ phi),
            np.asarray(probe @ S_rows),
            phi_rows, static_rows, 0.5 * (gram_M + gram_M.T), 0.5 * (gram_K + gram_K.T),
            {int(k): i for i, k in enumerate(raw.teeth)},
            {int(k): z + i for i, k in enumerate(raw.teeth)},
            np.arange(2 * z, S.shape[1]))
    return out


def position_basis(rp: RingPositions, teeth, functionals: bool = True) -> PositionBasis:
    """The reduced ring for contacts on ``teeth`` (and the functionals' responses when
    ``functionals``): the modes and the M-orthonormalised selected statics."""
    missing = sorted(set(int(k) for k in teeth) - set(rp.first))
    if missing:
        raise ValueError(f"teeth {missing}: no contact response in the ring's positions")
    cols = [rp.first[int(k)] for k in teeth] + [rp.second[int(k)] for k in teeth]
    if functionals:
        cols += list(rp.functional_columns)
    cols = np.asarray(cols, dtype=int)
    w, U = np.linalg.eigh(rp.gram_M[np.ix_(cols, cols)])
    useful = w > USEFUL * w.max()
    T = U[:, useful] / np.sqrt(w[useful])
    k_static = T.T @ rp.gram_K[np.ix_(cols, cols)] @ T
    n, m = rp.phi_K.shape[0], T.shape[1]
    K = np.zeros((n + m, n + m))
    K[:n, :n] = rp.phi_K
    K[n:, n:] = 0.5 * (k_static + k_static.T)
    return PositionBasis(
        K, np.vstack([rp.phi_contact, T.T @ rp.static_contact[cols]]),
        np.hstack([rp.phi_probe, rp.static_probe[:, cols] @ T]),
        np.hstack([rp.phi_rows, rp.static_rows[:, cols] @ T]))
