"""The ambient (broadband) part of the sensor record: random forcing of the lumped model (SI).

Natural frequencies show in a running reducer's record through its broadband
excitation (torque ripple, friction, road input), not through the periodic mesh
lines.  Here independent random forces act on the nine central coordinates
(x, y, u of sun, carrier and ring; u in the lumped model's translational units),
each white, of one-sided PSD ``G`` [N^2/Hz].

The response is sampled exactly.  The state ``x = [q, q']`` obeys
``dx = A x dt + B dW``; one sample step ``dt`` maps ``x_{k+1} = A_d x_k + w_k``
with ``A_d = expm(A dt)`` and ``cov(w_k) = Q`` by Van Loan's method (1978), and
the record starts in the stationary state (``A P + P A^T + B B^T = 0``), so the
samples have the continuous process's statistics, not an integrator's.

The crack: while the cracked ring tooth is in its engagement window with planet
``i`` (the window of :class:`hubvib.signal.mesh_curves.MeshCurves`), that
planet's ring mesh has the window's mean stiffness ratio cracked / intact times
its mean stiffness; otherwise every mesh has its mean.  The model thus switches
between N + 1 linear systems at sample instants (the carrier angle of each sample),
each step exact.  The mesh-cycle variation of the stiffness is left out of the
ambient part (its effect is the periodic part's lines).

The sensor sees the ambient forces through the periodic part's transfer path
(:mod:`hubvib.signal.accelerometer`): ``a = (1 / m_r) sum_i w(theta_i - theta_s) F_i``
with ``F_i = k_i g_i . q`` the ring-mesh force of planet ``i``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm, solve_continuous_lyapunov

from .mesh_curves import MeshCurves
from .mesh_phase import MeshPhasing
from .accelerometer import hann_window

#: the forced coordinates: the nine central ones (lumped.network.CENTRAL_DOFS)
FORCED = tuple(range(9))
#: samples per block of the exact recursion (memory: states x block complex numbers)
BLOCK = 1 << 15
#: largest decay exponent summed in one block of the modal recursion (round-off e^GROWTH eps)
GROWTH = 20.0


@dataclass(frozen=True)
class AmbientForcing:
    """Broadband forcing of the central coordinates.

    Attributes
    ----------
    psd : float
        One-sided PSD of each independent force [N^2/Hz] (0: none).
    """

    psd: float


def engaged_ratio(curves: MeshCurves) -> float:
    """Mean ring-mesh stiffness over the cracked tooth's engagement window, cracked over
    intact (trapezoidal in the roll length) [-]; 1 without a cracked curve."""
    if curves.cracked_s is None:
        return 1.0
    s = np.asarray(curves.cracked_s)
    intact = curves.ring(s)
    return float(np.trapezoid(curves.cracked_k, s) / np.trapezoid(intact, s))


def engaged_planet(phasing: MeshPhasing, curves: MeshCurves, carrier_angle: np.ndarray,
                   theta, tooth: int) -> np.ndarray:
    """Per sample, the planet (0-based) whose ring mesh holds the cracked tooth in its
    engagement window, or -1 [-]."""
    out = np.full(np.shape(carrier_angle), -1, dtype=int)
    if curves.cracked_s is None:
        return out
    low, high = curves.cracked_s[0], curves.cracked_s[-1]
    for i, th in enumerate(theta):
        s = phasing.ring_roll(np.asarray(carrier_angle) + th, tooth)
        out[(s >= low) & (s <= high) & (out < 0)] = i
    return out


class _Discrete:
    """One linear system sampled at ``dt``: diagonalised transition and noise."""

    def __init__(self, A: np.ndarray, BBt: np.ndarray, dt: float):
        n = A.shape[0]
        van_loan = np.zeros((2 * n, 2 * n))
        van_loan[:n, :n] = -A
        van_loan[:n, n:] = BBt
        van_loan[n:, n:] = A.T
        E = expm(van_loan * dt)
        Ad = E[n:, n:].T
        Q = Ad @ E[:n, n:]
        self.root = _root(0.5 * (Q + Q.T))
        self.lam, self.V = np.linalg.eig(Ad)
        self.Vinv = np.linalg.inv(self.V)
        self.drive = self.Vinv @ self.root
        decay = float(np.max(-np.log(np.abs(self.lam)))) or 1.0
        self.power = self.lam[:, None] ** np.arange(1, max(1, int(GROWTH / decay)) + 1)
        self.A, self.BBt = A, BBt

    def stationary(self) -> np.ndarray:
        """Square root of the stationary state covariance."""
        P = solve_continuous_lyapunov(self.A, -self.BBt)
        return _root(0.5 * (P + P.T))

    def run(self, x0: np.ndarray, e: np.ndarray, out: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """States' ``out`` rows (out @ x) at the m samples from ``x0`` on, and the state
        after the last; ``e``: (states, m) standard normal.

        In the modal coordinates ``z = V^-1 x`` each row obeys ``z_{k+1} = lam z_k + u_k``,
        summed in blocks short enough that ``|lam|^-block`` stays below ``e^GROWTH``:
        ``z_k = lam^k (z_0 + sum_{j<k} lam^-(j+1) u_j)``."""
        u = self.drive.real @ e + 1j * (self.drive.imag @ e)
        z0 = self.Vinv @ x0
        z = np.empty(u.shape, dtype=complex)
        for lo in range(0, u.shape[1], self.power.shape[1]):
            hi = min(u.shape[1], lo + self.power.shape[1])
            power = self.power[:, :hi - lo]
            ahead = power * (z0[:, None] + np.cumsum(u[:, lo:hi] / power, axis=1))
            z[:, lo] = z0
            z[:, lo + 1:hi] = ahead[:, :-1]
            z0 = ahead[:, -1]
        return (out @ self.V @ z).real, (self.V @ z0).real


def _root(C: np.ndarray) -> np.ndarray:
    """A square root R (R R^T = C) of a symmetric positive semi-definite matrix."""
    w, U = np.linalg.eigh(C)
    return U * np.sqrt(np.clip(w, 0.0, None))


def ambient_record(dynamics, curves: MeshCurves, phasing: MeshPhasing, forcing: AmbientForcing,
                   carrier_angle: np.ndarray, sample_rate: float, sensor_angle: float,
                   tooth: int, rng) -> np.ndarray:
    """Sensor acceleration [m/s^2] of the ambient response at the samples
    ``carrier_angle`` [rad] (one per sample, ``1 / sample_rate`` [s] apart).

    ``dynamics``: the :class:`hubvib.signal.dynamics.PlanetaryDynamics` of the depth
    (mean system, its modal damping); ``curves``: its mesh curves (the cracked window);
    ``tooth``: the cracked ring tooth.
    """
    system = dynamics.system
    params = dynamics.params
    N = params.n_planets
    mass = np.asarray(system.mass, dtype=float)
    ndof = mass.size
    ring_rows = system.rows[N:]
    kbar = dynamics.mean[N:]
    n = 2 * ndof
    intensity = 0.5 * forcing.psd  # two-sided PSD: the white noise's intensity [N^2/Hz]
    S = np.zeros((ndof, len(FORCED)))
    S[list(FORCED), range(len(FORCED))] = 1.0
    BBt = np.zeros((n, n))
    force = S / mass[:, None]
    BBt[ndof:, ndof:] = intensity * force @ force.T
    ratio = engaged_ratio(curves)
    systems = []
    for planet in range(-1, N):
        K = np.asarray(system.stiffness, dtype=float).copy()
        if planet >= 0:
            g = ring_rows[planet]
            K += (ratio - 1.0) * kbar[planet] * np.outer(g, g)
        A = np.zeros((n, n))
        A[:ndof, ndof:2 * ndof] = np.eye(ndof)
        A[ndof:2 * ndof, :ndof] = -K / mass[:, None]
        A[ndof:2 * ndof, ndof:2 * ndof] = -np.asarray(system.damping) / mass[:, None]
        systems.append(_Discrete(A, BBt, 1.0 / sample_rate))
    theta = np.array(params.theta)
    carrier_angle = np.asarray(carrier_angle, dtype=float)
    label = engaged_planet(phasing, curves, carrier_angle, theta, tooth) \
        if ratio != 1.0 else np.full(carrier_angle.shape, -1)
    out = np.zeros((N, n))
    out[:, :ndof] = ring_rows
    x = systems[label[0] + 1].stationary() @ rng.standard_normal(n)
    displacement = np.empty((carrier_angle.size, N))
    changes = np.flatnonzero(np.diff(label)) + 1
    edges = np.concatenate([[0], changes, [carrier_angle.size]])
    for start, stop in zip(edges[:-1], edges[1:]):
        for lo in range(start, stop, BLOCK):
            hi = min(stop, lo + BLOCK)
            rows, x = systems[label[lo] + 1].run(x, rng.standard_normal((n, hi - lo)), out)
            displacement[lo:hi] = rows.T
    stiffness = np.broadcast_to(kbar, displacement.shape).copy()
    engaged = label >= 0
    stiffness[engaged, label[engaged]] *= ratio
    window = hann_window(carrier_angle[:, None] + theta[None, :] - sensor_angle, N)
    return (window * stiffness * displacement).sum(axis=1) / params.m_r
