"""Fixed-step time integration of ``M x'' + C x' + K(t) x = f(t)`` on a small system (SI).

The stiffness varies through a few springs: ``K(t) = K0 + G^T diag(dk(t)) G``
(rows ``G`` [-], stiffness changes ``dk`` [N/m]) and the force is
``f(t) = G^T r(t) + f_ext(t)`` (row forces ``r`` [N]).  Both schemes are affine
maps of the state ``y = (x, v)`` per step, ``y_{n+1} = A_n y_n + b_n``; the maps
are built for a block of steps at once (whole-array numpy) and then applied in a
short loop, which is what makes an 18-DOF model cost ~2 us per step.

``"newmark"``: average acceleration (beta = 1/4, gamma = 1/2).  For a linear system
it is the trapezoidal rule on the first-order form, unconditionally stable, second
order; each undamped mode turns by exactly ``2 arctan(omega h / 2)`` per step
(so its discrete frequency is ``(2/h) arctan(omega h / 2)``) and its energy is kept
exactly (Hughes, *The Finite Element Method*, 1987, sec. 9.3).

``"central"``: explicit central difference, second order, stable only for
``omega_max h < 2 (sqrt(1 + zeta^2) - zeta)``; used as an independent check.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

BLOCK = 2048  # steps per block of precomputed maps (~20 MB for 18 DOFs)


@dataclass(frozen=True)
class LinearSystem:
    """``M x'' + C x' + (K0 + G^T diag(dk) G) x = G^T r + f_ext``.

    Attributes
    ----------
    mass : ndarray (n,)
        Diagonal mass matrix [kg].
    damping : ndarray (n, n)
        [N s/m].
    stiffness : ndarray (n, n)
        Constant part K0 [N/m].
    rows : ndarray (m, n)
        Rows of the time-varying springs [-].
    """

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    rows: np.ndarray

    @property
    def n(self) -> int:
        return self.mass.size


@dataclass(frozen=True)
class Excitation:
    """Sampled at the step times ``t_k = k h``, k = 0..steps.

    Attributes
    ----------
    dk : ndarray (steps + 1, m)
        Stiffness change of each time-varying spring [N/m].
    r : ndarray (steps + 1, m)
        Force of each time-varying spring row [N].
    f_ext : ndarray (steps + 1, n) or None
        Further generalised forces [N].
    """

    dk: np.ndarray
    r: np.ndarray
    f_ext: np.ndarray | None = None

    @property
    def steps(self) -> int:
        return self.dk.shape[0] - 1

    def force(self, system: LinearSystem, k0: int, k1: int) -> np.ndarray:
        """Generalised force at steps k0..k1-1 [N], shape (k1 - k0, n)."""
        f = self.r[k0:k1] @ system.rows
        return f if self.f_ext is None else f + self.f_ext[k0:k1]


@dataclass(frozen=True)
class TimeResponse:
    """State at every step: ``displacement[k]``, ``velocity[k]`` at ``t = k h`` [m, m/s]."""

    step: float
    displacement: np.ndarray
    velocity: np.ndarray

    @property
    def time(self) -> np.ndarray:
        return self.step * np.arange(self.displacement.shape[0])


def step_maps(system: LinearSystem, h: float, excitation: Excitation, k0: int, k1: int,
              scheme: str = "newmark") -> tuple[np.ndarray, np.ndarray]:
    """Maps ``A_k`` (B, 2n, 2n) and ``b_k`` (B, 2n) of steps k -> k + 1, k = k0..k1-1."""
    stepper = _stepper(system, h, scheme)
    X, b = stepper.maps(excitation, k0, k1)
    return stepper.base[None] + np.matmul(stepper.left[None], X), b


def _stepper(system, h, scheme):
    if scheme == "newmark":
        return _Newmark(system, h)
    if scheme == "central":
        return _Central(system, h)
    raise ValueError(f"scheme = {scheme!r}; allowed: newmark, central")


def _batch_inverse(matrices: np.ndarray) -> np.ndarray:
    """Inverses of (B, m, m) matrices close to the identity (Gauss-Jordan vectorised over
    the batch; falls back to LAPACK when a pivot is small)."""
    a = np.ascontiguousarray(matrices.transpose(1, 2, 0))        # (m, m, B)
    m = a.shape[0]
    inv = np.zeros_like(a)
    inv[np.arange(m), np.arange(m)] = 1.0
    for p in range(m):
        pivot = a[p, p].copy()
        if np.min(np.abs(pivot)) < 1e-8:
            return np.linalg.inv(matrices)
        a[p] /= pivot
        inv[p] /= pivot
        factor = a[:, p].copy()                                     # (m, B)
        factor[p] = 0.0
        a -= factor[:, None, :] * a[p][None]
        inv -= factor[:, None, :] * inv[p][None]
    return inv.transpose(2, 0, 1)


class _Newmark:
    """Trapezoidal rule on y' = F(t) y + g(t), F = [[0, I], [-M^-1 K, -M^-1 C]]:
    (I - h/2 F_{k+1}) y_{k+1} = (I + h/2 F_k) y_k + h/2 (g_k + g_{k+1}), where
    F_k = F0 - L D_k R (L = [0; M^-1 G^T], R = [G, 0], D_k = diag(dk)) is inverted by
    the Woodbury identity: only an m x m matrix per step.  The map of a step is
    ``A_k = base + left X_k`` with constant ``base``, ``left`` (2n x m) and X_k (m x 2n)."""

    def __init__(self, system: LinearSystem, h: float):
        n, m = system.n, system.rows.shape[0]
        self.system, self.h, self.n = system, h, n
        minv = 1.0 / system.mass
        F0 = np.zeros((2 * n, 2 * n))
        F0[:n, n:] = np.eye(n)
        F0[n:, :n] = -minv[:, None] * system.stiffness
        F0[n:, n:] = -minv[:, None] * system.damping
        L = np.zeros((2 * n, m))
        L[n:] = minv[:, None] * system.rows.T
        self.R = np.zeros((m, 2 * n))
        self.R[:, :n] = system.rows
        eye = np.eye(2 * n)
        self.J = np.linalg.inv(eye - 0.5 * h * F0)
        self.base = self.J @ (eye + 0.5 * h * F0)
        self.left = self.J @ L
        self.RJB, self.RJL = self.R @ self.base, self.R @ self.left
        self.minv = minv

    def maps(self, excitation: Excitation, k0: int, k1: int):
        h, n, m = self.h, self.n, self.R.shape[0]
        d_now, d_next = excitation.dk[k0:k1], excitation.dk[k0 + 1:k1 + 1]     # (B, m)
        # E_k = (h/2) D_{k+1} (I + (h/2) RJL D_{k+1})^-1, so (I - h/2 F_{k+1})^-1 = J - JL E RJ
        inner = np.eye(m) + 0.5 * h * self.RJL[None] * d_next[:, None, :]
        E = 0.5 * h * d_next[:, :, None] * _batch_inverse(inner)            # (B, m, m)
        # A_k = (J - JL E RJ)(B0 - h/2 L D_k R) = JB + JL X_k with
        # X_k = -h/2 D_k R - E RJB + h/2 E RJL D_k R
        ED = E @ (self.RJL[None] * d_now[:, None, :])
        X = (0.5 * h * (ED - d_now[:, :, None] * np.eye(m)[None])) @ self.R[None] \
            - E @ self.RJB[None]
        g = np.zeros((k1 - k0 + 1, 2 * n))
        g[:, n:] = self.minv * excitation.force(self.system, k0, k1 + 1)
        Jg = (0.5 * h * (g[:-1] + g[1:])) @ self.J.T
        b = Jg - np.einsum("bij,bj->bi", E, Jg @ self.R.T) @ self.left.T
        return X, b


class _Central:
    """(M/h^2 + C/2h) x_{k+1} = f_k - (K_k - 2M/h^2) x_k - (M/h^2 - C/2h) x_{k-1};
    the state is (x_k, x_{k-1}); the map is ``base + left X_k`` as for Newmark."""

    def __init__(self, system: LinearSystem, h: float):
        n = system.n
        self.system, self.n = system, n
        M = np.diag(system.mass)
        self.lhs = np.linalg.inv(M / h ** 2 + system.damping / (2 * h))
        self.base = np.zeros((2 * n, 2 * n))
        self.base[:n, :n] = self.lhs @ (2 * M / h ** 2 - system.stiffness)
        self.base[:n, n:] = -self.lhs @ (M / h ** 2 - system.damping / (2 * h))
        self.base[n:, :n] = np.eye(n)
        self.left = np.zeros((2 * n, system.rows.shape[0]))
        self.left[:n] = -self.lhs @ system.rows.T

    def maps(self, excitation: Excitation, k0: int, k1: int):
        n, rows = self.n, self.system.rows
        X = np.zeros((k1 - k0, rows.shape[0], 2 * n))
        X[:, :, :n] = excitation.dk[k0:k1, :, None] * rows[None]
        b = np.zeros((k1 - k0, 2 * n))
        b[:, :n] = excitation.force(self.system, k0, k1) @ self.lhs.T
        return X, b


def march(system: LinearSystem, h: float, excitation: Excitation, y0: np.ndarray,
          scheme: str = "newmark") -> np.ndarray:
    """States ``y_k`` for k = 0..steps (shape (steps + 1, 2n)) from ``y0``."""
    stepper = _stepper(system, h, scheme)
    base, left = stepper.base, stepper.left
    steps = excitation.steps
    out = np.empty((steps + 1, y0.size))
    out[0] = y0
    y = out[0]
    for k0 in range(0, steps, BLOCK):
        k1 = min(k0 + BLOCK, steps)
        X, b = stepper.maps(excitation, k0, k1)
        block = out[k0 + 1:k1 + 1]
        block[:] = b
        for j in range(k1 - k0):
            u = X[j] @ y
            nxt = block[j]
            nxt += base @ y
            nxt += left @ u
            y = nxt
    return out


def period_map(system: LinearSystem, h: float, excitation: Excitation,
               scheme: str = "newmark") -> tuple[np.ndarray, np.ndarray]:
    """The map over all steps of ``excitation``: ``y_steps = Phi y_0 + c``."""
    stepper = _stepper(system, h, scheme)
    base, left = stepper.base, stepper.left
    size = 2 * system.n
    state = np.zeros((size, size + 1))      # [Phi | c]
    state[:, :size] = np.eye(size)
    steps = excitation.steps
    for k0 in range(0, steps, BLOCK):
        k1 = min(k0 + BLOCK, steps)
        X, b = stepper.maps(excitation, k0, k1)
        for j in range(k1 - k0):
            state = base @ state + left @ (X[j] @ state)
            state[:, size] += b[j]
    return state[:, :size], state[:, size]


def periodic_start(system: LinearSystem, h: float, excitation: Excitation,
                   scheme: str = "newmark") -> np.ndarray:
    """The state that repeats after ``excitation.steps`` steps: the steady state of a
    periodic excitation sampled over exactly one period, ``y_0 = (I - Phi)^-1 c``
    (in the scheme's own state, see :func:`integrate`).

    Raises
    ------
    ValueError
        When the one-period map has an eigenvalue 1 (an undamped rigid-body motion or
        exact parametric resonance): there is no steady state.
    """
    Phi, c = period_map(system, h, excitation, scheme)
    lhs = np.eye(Phi.shape[0]) - Phi
    if np.linalg.cond(lhs) > 1e12:
        raise ValueError("damping_ratio: the one-period map has an eigenvalue 1 (no damped "
                         "steady state); allowed: damping_ratio > 0")
    return np.linalg.solve(lhs, c)


def integrate(system: LinearSystem, h: float, excitation: Excitation, x0=None, v0=None,
              scheme: str = "newmark", y0=None) -> TimeResponse:
    """Response at every step from ``x0``, ``v0`` [m, m/s] (default 0), or from the
    scheme's own state ``y0``: ``(x, v)`` for ``"newmark"``, ``(x_0, x_-1)`` for
    ``"central"`` (as :func:`periodic_start` gives it)."""
    n = system.n
    if y0 is None:
        x0 = np.zeros(n) if x0 is None else np.asarray(x0, dtype=float)
        v0 = np.zeros(n) if v0 is None else np.asarray(v0, dtype=float)
        y0 = np.concatenate([x0, v0])
        if scheme == "central":  # x_-1 from the Taylor start x0 - h v0 + h^2/2 a0
            f0 = excitation.force(system, 0, 1)[0]
            K0 = system.stiffness + system.rows.T @ (excitation.dk[0][:, None] * system.rows)
            a0 = (f0 - system.damping @ v0 - K0 @ x0) / system.mass
            y0 = np.concatenate([x0, x0 - h * v0 + 0.5 * h ** 2 * a0])
    states = march(system, h, excitation, np.asarray(y0, dtype=float), scheme)
    x = states[:, :n]
    if scheme == "central":
        return TimeResponse(h, x, np.gradient(x, h, axis=0, edge_order=2))
    return TimeResponse(h, x, states[:, n:])


def acceleration(system: LinearSystem, excitation: Excitation, response: TimeResponse,
                 dofs) -> np.ndarray:
    """Acceleration of ``dofs`` at every step from the equation of motion [m/s^2]."""
    dofs = np.atleast_1d(dofs)
    x, v = response.displacement, response.velocity
    f = excitation.force(system, 0, excitation.steps + 1)
    Kx = x @ system.stiffness.T + (excitation.dk * (x @ system.rows.T)) @ system.rows
    rhs = f - v @ system.damping.T - Kx
    return rhs[:, dofs] / system.mass[dofs]


def central_stability_limit(omega_max: float, damping_ratio: float) -> float:
    """Largest stable step of the central difference scheme [s] (undamped: 2/omega)."""
    return 2.0 / omega_max * (math.sqrt(1 + damping_ratio ** 2) - damping_ratio)
