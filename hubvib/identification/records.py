"""Simulated ambient vibration records of known modes (SI).

Each mode is a single-degree-of-freedom oscillator ``x'' + 2 zeta w x' + w^2 x =
u(t)`` driven by independent white noise; its state is sampled exactly (the
discrete transition ``expm(A dt)`` and the covariance of the integrated noise by
Van Loan's method, 1978), so the record has the continuous process's statistics
at the sample times, not those of an integration scheme.  The record is the sum
of the modes' displacements plus white measurement noise.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import cholesky, expm
from scipy.signal import lfilter


@dataclass(frozen=True)
class Record:
    """A sampled response.

    Attributes
    ----------
    values : ndarray
        Samples [m] (displacement units; the identification does not care).
    sample_rate : float
        [Hz]
    """

    values: np.ndarray
    sample_rate: float

    @property
    def duration(self) -> float:
        """Record length T [s]."""
        return self.values.size / self.sample_rate


def _mode_filters(natural_hz: float, damping_ratio: float, dt: float):
    """Transfer from two unit white sequences to the sampled displacement of one mode
    (unit force PSD): numerators (2, 3) and denominator (3,)."""
    w = 2 * math.pi * natural_hz
    A = np.array([[0.0, 1.0], [-w * w, -2 * damping_ratio * w]])
    B = np.array([[0.0], [1.0]])
    n = 2
    van_loan = np.zeros((2 * n, 2 * n))
    van_loan[:n, :n] = -A
    van_loan[:n, n:] = B @ B.T
    van_loan[n:, n:] = A.T
    E = expm(van_loan * dt)
    Ad = E[n:, n:].T
    Q = Ad @ E[:n, n:]
    L = cholesky(0.5 * (Q + Q.T), lower=True)
    a11, a12, a21, a22 = Ad.ravel()
    den = np.array([1.0, -(a11 + a22), a11 * a22 - a12 * a21])
    # x1 = [(z - a22) w1 + a12 w2] / det(zI - A), w = L e
    num_w1, num_w2 = np.array([0.0, 1.0, -a22]), np.array([0.0, 0.0, a12])
    num = np.array([L[0, 0] * num_w1 + L[1, 0] * num_w2, L[1, 1] * num_w2])
    return num, den


def mode_psd(natural_hz: float, damping_ratio: float, sample_rate: float,
             at_hz) -> np.ndarray:
    """Two-sided PSD [m^2/Hz] of one simulated mode's sampled displacement at ``at_hz``."""
    dt = 1.0 / sample_rate
    num, den = _mode_filters(natural_hz, damping_ratio, dt)
    z = np.exp(-2j * math.pi * np.asarray(at_hz, dtype=float) * dt)
    d = np.polyval(den[::-1], z)
    return dt * sum(np.abs(np.polyval(n[::-1], z) / d) ** 2 for n in num)


def simulate(natural_hz, damping_ratio, duration: float, sample_rate: float, snr: float,
             rng) -> Record:
    """A record of ``duration`` [s] of the modes ``natural_hz`` [Hz] (with
    ``damping_ratio`` [-], scalars or one per mode) under unit white force.

    ``snr``: response PSD of the first mode at its natural frequency over the PSD of the
    white measurement noise [-] (``inf``: no noise).
    """
    f = np.atleast_1d(np.asarray(natural_hz, dtype=float))
    z = np.broadcast_to(np.asarray(damping_ratio, dtype=float), f.shape)
    if f.max() >= 0.5 * sample_rate:
        raise ValueError(f"mode at {f.max():g} Hz is not below the Nyquist frequency "
                         f"{0.5 * sample_rate:g} Hz of the {sample_rate:g} Hz sampling")
    n = int(round(duration * sample_rate))
    dt = 1.0 / sample_rate
    warm = int(10 / (2 * math.pi * (f * z).min() * dt))  # ~10 decay times: stationary
    values = np.zeros(n)
    for fi, zi in zip(f, z):
        num, den = _mode_filters(fi, zi, dt)
        e = rng.standard_normal((2, n + warm))
        values += (lfilter(num[0], den, e[0]) + lfilter(num[1], den, e[1]))[warm:]
    if math.isfinite(snr):
        peak = float(mode_psd(f[0], z[0], sample_rate, f[0]))
        values += math.sqrt(peak / snr / dt) * rng.standard_normal(n)
    return Record(values, float(sample_rate))
