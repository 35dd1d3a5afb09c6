"""The coupled modes a record of the running reducer shows: Floquet modes over the mesh cycle (SI).

The eigen model of the elastic ring (:mod:`hubvib.lumped.elastic_ring`) holds every mesh at
its mean stiffness.  Running, each mesh stiffness follows its mesh cycle (the mesh curves
swing by tens of per cent between one and two tooth pairs) at the mesh frequency, which on
a hub reducer exceeds the half-power bandwidth of the ring's modes; modes that load the
meshes are then parametric: over one mesh period ``T`` the state
``x = (eta, eta')`` of :class:`~hubvib.signal.elastic_model.ElasticTimeModel` at a carrier
position obeys ``x' = A(t) x`` with ``A`` periodic, and its solutions are Floquet modes
``exp(s t) p(t)``, ``p`` periodic.  Their exponents ``s`` are the eigenvalues of the
monodromy matrix ``Phi(T)`` (``log(mu) / T``), their frequency known modulo the mesh
frequency; a Floquet mode's record pole is ``s_n = s + 2 pi i n / T`` with ``n`` the
harmonic of ``p`` that carries the most modal amplitude, its natural frequency ``|s_n| / 2
pi`` and damping ``-Re s / |s_n|`` (as the identifier fits them), and it is attributed to
the mean-stiffness mode that dominates that harmonic (of several, the one nearest it).  With constant meshes the Floquet modes
are the eigen modes.

``Phi(T)`` is the ordered product of the matrix exponentials of ``A`` held constant over
each of ``steps`` sub-intervals (mid-point values); the contacts stay on the position's
teeth over the period (the carrier's travel of one tooth pitch).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

from .elastic_model import ElasticTimeModel
from .elastic_response import _mesh_terms
from .mesh_curves import MeshCurves
from .mesh_phase import MeshPhasing


#: sub-intervals of the mesh period per harmonic up to the highest kept mode
STEPS_PER_HARMONIC = 2
#: fewest sub-intervals of the mesh period
MIN_STEPS = 64


@dataclass(frozen=True)
class FloquetModes:
    """Per kept mean-stiffness mode (the model's order), the frequency and damping of the
    Floquet mode attributed to it; NaN where none is.

    Attributes
    ----------
    frequency_hz : ndarray
        Natural frequency of the record pole [Hz] (the dominant harmonic of the Floquet
        mode).
    damping_ratio : ndarray
        Its damping ratio [-].
    mean_hz : ndarray
        The mean-stiffness (eigen model) frequency of each mode at the position [Hz].
    mesh_hz : float
        The mesh frequency [Hz].
    exponents : ndarray (2 m,)
        Every Floquet exponent ``log(mu) / T`` (principal logarithm) [1/s].
    """

    frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    mean_hz: np.ndarray
    mesh_hz: float
    exponents: np.ndarray

    def record_hz(self) -> np.ndarray:
        """The record frequency of every mode, the mean-stiffness one where no Floquet
        mode is attributed [Hz]."""
        return np.where(np.isfinite(self.frequency_hz), self.frequency_hz, self.mean_hz)


def floquet_modes(model: ElasticTimeModel, curves: MeshCurves, phasing: MeshPhasing,
                  carrier_speed: float, position: int, steps: int | None = None
                  ) -> FloquetModes:
    """The Floquet modes of the kept modes at carrier ``position`` over one mesh period.

    Parameters
    ----------
    model : ElasticTimeModel
    curves, phasing
        The mesh stiffness curves and their phases (as for the time response).
    carrier_speed : float
        [rad/s], > 0: the mesh period is one ring tooth pitch of carrier travel.
    position : int
        Carrier position (planet 1 on this ring tooth), 0 <= position < teeth.
    steps : int or None
        Sub-intervals of the mesh period, >= 8 and enough to hold the highest kept mode's
        harmonic; None: ``STEPS_PER_HARMONIC`` per harmonic of the mesh frequency up to the
        highest kept mode, at least ``MIN_STEPS``.
    """
    if not (math.isfinite(carrier_speed) and carrier_speed > 0):
        raise ValueError(f"carrier_speed = {carrier_speed!r} rad/s; allowed: > 0 (a standing "
                         "carrier has no mesh cycle: its modes are the eigen model's)")
    if not 0 <= position < model.teeth:
        raise ValueError(f"position = {position!r}; allowed: 0 .. {model.teeth - 1}")
    needed = _harmonics(model, position, carrier_speed)
    if steps is None:
        steps = default_steps(model, position, carrier_speed)
    if steps < max(8, needed):
        raise ValueError(f"steps = {steps!r}; allowed: >= {max(8, needed)} (the highest "
                         "kept mode's harmonic of the mesh frequency)")
    from hubvib.foundation.blas import blas_threads

    with blas_threads(1):
        return _floquet(model, curves, phasing, float(carrier_speed), int(position),
                        int(steps))


def _harmonics(model, position: int, carrier_speed: float) -> int:
    """Sub-intervals the highest kept mode's harmonic of the mesh frequency needs."""
    mesh_hz = carrier_speed * model.teeth / (2 * math.pi)
    return 2 * int(math.ceil(model.omega[position, model.kept - 1] / (2 * math.pi)
                             / mesh_hz)) + 2


def default_steps(model, position: int, carrier_speed: float) -> int:
    """Sub-intervals of the mesh period :func:`floquet_modes` takes by default:
    ``STEPS_PER_HARMONIC`` per harmonic up to the highest kept mode, at least ``MIN_STEPS``."""
    return max(MIN_STEPS, STEPS_PER_HARMONIC * _harmonics(model, position, carrier_speed))


def transition_path(model, curves, phasing, speed: float, position: int, steps: int,
                    scale: float = 1.0) -> tuple:
    """``(period, omega, path)``: the mesh period [s], the kept modes' mean-stiffness
    angular frequencies [rad/s] at ``position`` and the state transition matrices from the
    period's start to the end of each of its ``steps`` sub-intervals, (steps, 2 m, 2 m),
    ``path[-1]`` the monodromy matrix; the mesh stiffness variation scaled by ``scale`` [-]
    (1: the running reducer; 0: the eigen model)."""
    m = model.kept
    pitch = 2 * math.pi / model.teeth
    period = pitch / speed
    dt = period / steps
    centre = model.patch_angles[position] - model.theta[0]
    angle = centre + ((np.arange(steps) + 0.5) / steps - 0.5) * pitch
    U, W, _ = _mesh_terms(model, curves, phasing, angle, np.full(steps, position), 0.0)
    omega = model.omega[position, :m]
    damping = np.diag(2 * model.damping_ratio * omega)
    zero, one = np.zeros((m, m)), np.eye(m)
    transition = np.eye(2 * m)
    path = np.empty((steps, 2 * m, 2 * m))
    for b in range(steps):
        rows = U[b][:, :m]
        K = np.diag(omega ** 2) + scale * rows.T @ (W[b][:, None] * rows)
        transition = expm(np.block([[zero, one], [-K, -damping]]) * dt) @ transition
        path[b] = transition
    return period, omega, path


def _floquet(model, curves, phasing, speed, p, steps):
    m = model.kept
    period, omega, full = transition_path(model, curves, phasing, speed, p, steps)
    dt = period / steps
    transition, path = full[-1], full[:, :m]
    mu, vectors = np.linalg.eig(transition)
    s = np.log(mu) / period
    t = (np.arange(steps) + 1) * dt
    harmonic = np.fft.fftfreq(steps, 1.0 / steps)
    frequency = np.full(m, np.nan)
    zeta = np.full(m, np.nan)
    mean_hz = omega / (2 * math.pi)
    for k in np.flatnonzero(s.imag >= 0):
        periodic = (path @ vectors[:, k]) * np.exp(-s[k] * t)[:, None]   # (steps, m)
        content = np.abs(np.fft.fft(periodic, axis=0))
        n, j = np.unravel_index(np.argmax(content), content.shape)
        pole = complex(s[k].real, abs(s[k].imag + 2 * math.pi * harmonic[n] / period))
        f = abs(pole) / (2 * math.pi)
        if not np.isfinite(frequency[j]) or abs(f - mean_hz[j]) < abs(frequency[j] - mean_hz[j]):
            frequency[j] = f
            zeta[j] = -pole.real / abs(pole)
    return FloquetModes(frequency, zeta, mean_hz, 1.0 / period, s)
