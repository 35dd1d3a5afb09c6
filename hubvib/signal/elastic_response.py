"""The elastic ring's time response: the coupled model with the carrier turning (SI).

The model is :class:`hubvib.signal.elastic_model.ElasticTimeModel`: at carrier position
``p`` (planet 1 nearest ring tooth ``p``) the mean system's modes ``Phi_p``, static state
``q0_p`` and the 2N mesh rows ``g_j``.  With ``q = q0_p + Phi_p eta``, mesh ``j`` of
stiffness ``k_j(t) = kbar_j + dk_j(t)`` and transmission error ``e_j(t)``,

    eta'' + C eta' + (Lambda_p + sum_j dk_j g_j g_j^T) eta
        = sum_j g_j (-dk_j (g_j . q0_p) + k_j e_j) + ambient forces,

``C = diag(2 zeta omega_p)``.  When planet 1 passes half way to the next tooth the
contacts switch: the displacement and velocity carry over (``q`` and ``q'`` continuous),
projected on the new position's modes.  Between the switches the static state follows the
load: a force whose static response is ``|u| (q0_(p+-1) - q0_p)``, ``u`` planet 1's travel
past its load point in pitches (towards the next position's static state ahead of it, from
the previous one's behind), so the equilibrium the system is drawn to moves continuously
with the carrier and the switch does not strike the ring.  Modes above ``keep_hz`` respond quasi-statically:
the mesh terms on the kept modes are condensed with the rows' residual flexibility
(:func:`condensed`).

Integrator: the trapezoidal rule on the first-order form (Newmark average acceleration),
``h = 1 / (sample_rate substeps)``, made exact for each position's modes by prewarping: a
mode's pole ``s = -zeta omega + i omega sqrt(1 - zeta^2)`` is replaced by ``s' = (2/h)
tanh(s h / 2)``, whose trapezoidal pole ``(1 + s'h/2) / (1 - s'h/2) = exp(s h)`` is the exact
one; the mesh-stiffness variation is scaled by ``S = diag(sqrt(tan x / (x cos^2 x)))``, ``x =
omega h / 2``, so that a mode's frequency moves by the same amount per unit of it as in
continuous time (first order).  Each step solves ``(D + (h^2/4) U^T W U) v = r``, ``D``
diagonal, by Woodbury with the rank-2N ``U``.  The sensor's acceleration is taken at every
step from the equation of motion and decimated to the sample rate through an
anti-aliasing FIR (``scipy.signal.resample_poly``).  A run-in of five decay times of the
lowest mode (at most ``MAX_RUN_IN``) is integrated and dropped.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .elastic_model import ElasticTimeModel, carrier_offset
from .mesh_curves import MeshCurves
from .mesh_phase import MeshPhasing

#: steps per block of precomputed rows and capacitances
BLOCK = 4096
#: longest run-in before the record [s]
MAX_RUN_IN = 2.0


@dataclass(frozen=True)
class Operation:
    """Operating point and integration settings.

    Attributes
    ----------
    carrier_speed : float
        [rad/s], >= 0.
    sample_rate : float
        [Hz].
    duration : float
        Record length [s].
    substeps : int
        Integrator steps per sample [-], >= 1.
    transmission_error : float
        First-harmonic static transmission error of every mesh [m].
    ambient_psd : float
        One-sided PSD of each white ambient force [N^2/Hz] (0: none).
    run_in : float or None
        Run-in [s] integrated and dropped (None: five decay times of the lowest mode, at
        most ``MAX_RUN_IN``).
    """

    carrier_speed: float
    sample_rate: float
    duration: float
    substeps: int = 4
    transmission_error: float = 0.0
    ambient_psd: float = 0.0
    run_in: float | None = None


@dataclass(frozen=True)
class ElasticRecord:
    """The sensor's acceleration at the sample times ``t_k = k / sample_rate`` [m/s^2],
    with the integrator's cost [s] and size, and the modal displacement and velocity after
    the last step (``final_state``)."""

    values: np.ndarray
    sample_rate: float
    seconds: float
    steps: int
    modes: int
    final_state: tuple = ()

    @property
    def time(self) -> np.ndarray:
        return np.arange(self.values.size) / self.sample_rate


def prewarped(omega: np.ndarray, zeta: float, h: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Stiffness ``omega'^2`` [1/s^2], damping ``c'`` [1/s] and correction scale ``S`` [-]
    of each mode for the trapezoidal rule at step ``h`` [s] (module docstring)."""
    x = 0.5 * omega * h
    if np.any(x >= 0.5 * math.pi * 0.98):
        raise ValueError(f"a kept mode at {omega.max() / (2 * math.pi):.6g} Hz is above the "
                         f"integrator's Nyquist {1 / (2 * h):.6g} Hz; allowed: more substeps "
                         f"or a lower keep_hz")
    s = -zeta * omega + 1j * omega * math.sqrt(1 - zeta ** 2)
    warped = (2 / h) * np.tanh(0.5 * s * h)
    stiffness = np.abs(warped) ** 2
    damping = -2 * warped.real
    scale = np.sqrt(np.tan(x) / (x * np.cos(x) ** 2))
    return stiffness, damping, scale


def _mesh_terms(model: ElasticTimeModel, curves: MeshCurves, phasing: MeshPhasing,
                angle: np.ndarray, pos: np.ndarray, transmission_error: float):
    """Rows U (B, 2N, n), stiffness changes W (B, 2N) [N/m] and row forces phi (B, 2N) [N]
    (the modal force is ``U^T phi``) at carrier angles ``angle`` [rad], positions ``pos``."""
    theta = angle[:, None] + model.theta[None, :]                              # (B, N)
    s_ring = phasing.ring_roll(theta)
    s_sun = phasing.sun_roll(theta)
    N = model.n_planets
    k = np.hstack([model.mean[0] / curves.sun_mean * curves.sun(s_sun),
                   model.mean[N] / curves.ring_mean * curves.ring(s_ring)])
    W = k - model.mean[None, :]
    phi = -W * model.preload[pos]
    if transmission_error:
        roll = np.hstack([s_sun, s_ring])
        phi = phi + k * transmission_error * np.cos(2 * np.pi * roll / curves.base_pitch)
    return model.rows[pos], W, phi


def condensed(U: np.ndarray, W: np.ndarray, phi: np.ndarray, omega_high: np.ndarray):
    """The rows' correction on the kept modes with the higher modes static: for
    ``K = diag(omega^2) + U^T diag(W) U`` split into kept (l) and high (h) modes, the kept
    modes see ``U_l^T W~ U_l`` with ``W~ = W (I + R W)^-1`` and the force ``U_l^T (I + W R)^-1
    phi``, ``R = U_h diag(omega_h^-2) U_h^T`` the rows' residual flexibility [m/N] (static
    condensation, exact for massless high modes); ``omega_high`` (B, n_h) [rad/s].  Returns
    (W~ (B, p, p), forces (B, p))."""
    p = W.shape[1]
    Uh = U[:, :, U.shape[2] - omega_high.shape[1]:]
    R = (Uh / omega_high[:, None, :] ** 2) @ Uh.transpose(0, 2, 1)
    inverse = np.linalg.inv(np.eye(p)[None] + R * W[:, None, :])              # (I + R W)^-1
    weights = W[:, :, None] * inverse
    weights = 0.5 * (weights + weights.transpose(0, 2, 1))
    forces = np.einsum("bji,bj->bi", inverse, phi)                            # (I + W R)^-1 phi
    return weights, forces


def run_in_seconds(model: ElasticTimeModel) -> float:
    """Five decay times of the lowest mode, at most ``MAX_RUN_IN`` [s]."""
    return min(MAX_RUN_IN, 5.0 / (model.damping_ratio * float(model.omega[:, 0].min())))


def _moving_equilibrium(model: ElasticTimeModel, lam: np.ndarray, S: np.ndarray):
    """Per position, the (scaled) modal force whose static response is the move of the
    static state towards the next (``[0]``) and from the previous (``[1]``) position's,
    per pitch of carrier travel: with it the static state moves with the carrier between
    the switches (continuous across them) instead of jumping at each."""
    m = lam.shape[1]
    z = model.teeth
    out = np.empty((2, z, m))
    for p in range(z):
        Phi = model.shapes[p][:, :m] * model.mass[:, None]
        ahead = Phi.T @ (model.static[(p + 1) % z] - model.static[p])
        behind = Phi.T @ (model.static[(p - 1) % z] - model.static[p])
        out[0, p] = lam[p] * ahead / S[p]
        out[1, p] = lam[p] * behind / S[p]
    return out


def _switch(model: ElasticTimeModel, old: int, new: int, m: int):
    """Map of the kept modal state from position ``old`` to ``new``: (T (m, m), shift (m,)),
    ``eta_new = T eta_old + shift`` (the same physical displacement)."""
    Phi_new = model.shapes[new][:, :m] * model.mass[:, None]
    T = Phi_new.T @ model.shapes[old][:, :m]
    return T, Phi_new.T @ (model.static[old] - model.static[new])


def elastic_record(model: ElasticTimeModel, curves: MeshCurves, phasing: MeshPhasing,
                   operation: Operation, sensor_angle: float, rng=None,
                   initial=None) -> ElasticRecord:
    """The sensor's radial acceleration [m/s^2] at polar angle ``sensor_angle`` [rad] of the
    ring (the mid-rim circle of the probe) over ``operation.duration``; ``rng`` draws the
    ambient forces (required when ``operation.ambient_psd > 0``); ``initial``: kept modal
    displacement and velocity at t = 0 (default: the static state of the first position).
    """
    from hubvib.foundation.blas import blas_threads

    with blas_threads(1):  # small matrices, one step after another: threads only contend
        return _record(model, curves, phasing, operation, sensor_angle, rng, initial)


def _record(model, curves, phasing, operation, sensor_angle, rng, initial):
    from scipy.signal import resample_poly

    started = time.perf_counter()
    r = int(operation.substeps)
    if r < 1:
        raise ValueError(f"substeps = {r}; allowed: >= 1")
    h = 1.0 / (operation.sample_rate * r)
    m = model.modes
    z = model.teeth
    warped = [prewarped(model.omega[p, :m], model.damping_ratio, h) for p in range(z)]
    lam = np.array([w[0] for w in warped])
    c = np.array([w[1] for w in warped])
    S = np.array([w[2] for w in warped])
    run_in = run_in_seconds(model) if operation.run_in is None else float(operation.run_in)
    skip = int(math.ceil(run_in * operation.sample_rate)) * r
    samples = int(math.floor(operation.duration * operation.sample_rate + 1e-9))
    steps = skip + samples * r + (8 * r if r > 1 else 0) - 1  # r > 1: the FIR's tail
    N = model.n_planets
    hh, q = 0.5 * h, 0.25 * h * h
    ambient = operation.ambient_psd > 0
    if ambient and rng is None:
        raise ValueError("ambient forcing needs a random generator (rng)")
    force_sd = math.sqrt(operation.ambient_psd / (2 * h)) if ambient else 0.0
    base_inv = 1.0 / (1.0 + hh * c + q * lam)                                 # (z, m)
    sensors = model.sensor_rows(sensor_angle)[:, :m] * S
    switches = {}
    moving = _moving_equilibrium(model, lam, S) if operation.carrier_speed else None
    out = np.empty(steps + 1)
    eta = np.zeros(m) if initial is None else np.array(initial[0], dtype=float)
    v = np.zeros(m) if initial is None else np.array(initial[1], dtype=float)
    here = None
    prev = None
    for k0 in range(0, steps + 1, BLOCK):
        k1 = min(k0 + BLOCK, steps + 1)
        angle = operation.carrier_speed * h * np.arange(k0, k1)
        pos, offset = carrier_offset(model, angle)
        if here is None:
            here = int(pos[0])
            eta, v = eta / S[here], v / S[here]
        U, W, phi = _mesh_terms(model, curves, phasing, angle, pos,
                                operation.transmission_error)
        if ambient:
            e = force_sd * rng.standard_normal((k1 - k0, 6 + 2 * N))
            phi = phi + e[:, 6:]
        Wt, phi = condensed(U, W, phi, model.omega[pos, m:])
        Sb = S[pos]
        U = U[:, :, :m] * Sb[:, None, :]
        g = np.einsum("bjm,bj->bm", U, phi)
        if ambient:
            g += np.einsum("bk,bkm->bm", e[:, :6], model.central[pos][:, :, :m]) * Sb
        if moving is not None:  # the static state follows the load between positions
            ahead = offset >= 0
            g += np.abs(offset)[:, None] * np.where(ahead[:, None], moving[0][pos],
                                                    moving[1][pos])
        P = U * base_inv[pos][:, None, :]
        qWt = q * Wt
        cap_inv = np.linalg.inv(np.eye(2 * N)[None] + qWt @ (P @ U.transpose(0, 2, 1)))
        for j in range(k1 - k0):
            p = pos[j]
            Uj, Wj = U[j], Wt[j]
            if p != here:  # the contacts move on: same displacement and velocity
                if (here, p) not in switches:
                    switches[here, p] = _switch(model, here, p, m)
                T, shift = switches[here, p]
                eta = (T @ (eta * S[here]) + shift) / S[p]
                v = (T @ (v * S[here])) / S[p]
                here = p
                K_eta = lam[p] * eta + Uj.T @ (Wj @ (Uj @ eta))
                prev = (g[j], K_eta)
            if prev is not None:
                g_prev, K_eta = prev
                r1 = eta + hh * v
                r2 = v - hh * (K_eta + c[p] * v) + hh * (g_prev + g[j])
                rhs = r2 - hh * (lam[p] * r1 + Uj.T @ (Wj @ (Uj @ r1)))
                Pj = P[j]
                v = base_inv[p] * rhs - Pj.T @ (cap_inv[j] @ (qWt[j] @ (Pj @ rhs)))
                eta = r1 + hh * v
            K_eta = lam[p] * eta + Uj.T @ (Wj @ (Uj @ eta))
            out[k0 + j] = sensors[p] @ (g[j] - c[p] * v - K_eta)
            prev = (g[j], K_eta)
    values = resample_poly(out[skip:], 1, r)[:samples] if r > 1 else out[skip:]
    return ElasticRecord(values, float(operation.sample_rate), time.perf_counter() - started,
                         steps, m, (eta * S[here], v * S[here]))
