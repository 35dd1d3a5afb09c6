"""Frictionless unilateral contact condensed onto a few pairs: the linear complementarity
problem of Signorini's conditions with a symmetric positive definite compliance (SI).

With pair forces ``lam`` [N] (positive: pressing the faces apart) the openings are
``g = g0 + C lam`` [m], ``C`` the contact compliance (SPD) [m/N].  With a closure gap
``c >= 0`` [m] the faces are apart only where ``w = g - c > 0``; Signorini's conditions are

    w = q + C lam >= 0,   lam >= 0,   lam . w = 0,     q = g0 - c,

an LCP whose solution is unique because C is positive definite (it is the minimum of the
strictly convex ``1/2 lam^T C lam + q^T lam`` over ``lam >= 0``).

Method: the primal-dual active set method, i.e. the semismooth Newton method on the
min-function ``min(lam, w / d) = 0`` (Hintermueller, Ito & Kunisch, SIAM J. Optim. 13,
2002), with ``d = diag(C)`` so that both arguments are forces.  Each step guesses the
pressed set from the sign of ``lam - w / d``, solves the pressed block exactly and stops
when the set repeats; it needs a handful of dense Cholesky solves of at most pairs x pairs
and is exact at convergence.  The min-function rather than Alart-Curnier's augmented
Lagrangian: without friction the two coincide up to the scaling, and the min-function
needs no penalty parameter.  Its superlinear (finite) convergence is proven for M-matrices,
not for every SPD C, so a set seen before (a cycle) or too many steps hands over to the
Lawson-Hanson active-set method on the equivalent least-squares form
``min || L^T lam + L^-1 q ||, lam >= 0`` (``C = L L^T``), which terminates finitely.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla


@dataclass(frozen=True, eq=False)
class ContactSolution:
    """Signorini's conditions solved.

    Attributes
    ----------
    force : ndarray (pairs,)
        Contact force of each pair [N], >= 0.
    gap : ndarray (pairs,)
        ``w = g - c`` [m], >= 0 (zero where pressed).
    pressed : ndarray of bool (pairs,)
        Pairs in contact (force > 0).
    iterations : int
        Active-set steps taken.
    method : str
        ``"active set"`` or ``"nnls"`` (the fallback).
    """

    force: np.ndarray
    gap: np.ndarray
    pressed: np.ndarray
    iterations: int
    method: str


def signorini(C: np.ndarray, q: np.ndarray, max_steps: int | None = None) -> ContactSolution:
    """Solve ``w = q + C lam >= 0, lam >= 0, lam . w = 0`` for SPD ``C`` [m/N] and ``q`` [m]."""
    C = np.asarray(C, dtype=float)
    q = np.asarray(q, dtype=float).ravel()
    n = q.size
    if C.shape != (n, n):
        raise ValueError(f"C is {C.shape}, q has {n} entries: C must be {n} x {n}")
    if n == 0:
        return ContactSolution(np.zeros(0), np.zeros(0), np.zeros(0, bool), 0, "active set")
    d = np.diag(C).copy()
    if np.any(d <= 0):
        raise ValueError("C has a diagonal entry <= 0: the contact compliance must be SPD")
    max_steps = 4 * n + 20 if max_steps is None else max_steps
    lam = np.zeros(n)
    w = q.copy()
    seen = set()
    step = 0
    for step in range(1, max_steps + 1):
        pressed = lam - w / d > 0
        key = pressed.tobytes()
        if key in seen:
            break
        seen.add(key)
        lam = np.zeros(n)
        if pressed.any():
            A = np.flatnonzero(pressed)
            lam[A] = sla.solve(C[np.ix_(A, A)], -q[A], assume_a="pos")
        w = q + C @ lam
        if np.array_equal(lam - w / d > 0, pressed) and _feasible(lam, w, q, C):
            w[pressed] = 0.0
            return ContactSolution(lam, w, pressed, step, "active set")
    return _nnls(C, q, step)


def _feasible(lam, w, q, C) -> bool:
    """Complementarity to round-off: no negative force or gap beyond it."""
    scale_w = np.abs(q).max() + 1e-300
    scale_f = scale_w / np.abs(np.diag(C)).max()
    return bool(lam.min() >= -1e-10 * scale_f and w.min() >= -1e-10 * scale_w)


def _nnls(C, q, steps) -> ContactSolution:
    from scipy.optimize import nnls

    L = sla.cholesky(0.5 * (C + C.T), lower=True)
    lam, _ = nnls(L.T, -sla.solve_triangular(L, q, lower=True), maxiter=50 * q.size)
    pressed = lam > 0
    w = q + C @ lam
    w[pressed] = 0.0
    return ContactSolution(lam, np.maximum(w, 0.0), pressed, steps, "nnls")
