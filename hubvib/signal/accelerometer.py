"""Accelerometer on the ring: planet-position window, rigid path, sampling, noise, files (SI).

Transfer path (McFadden & Smith 1985, "An explanation for the asymmetry of the
modulation sidebands about the tooth meshing frequency in epicyclic gear
vibration", Proc. IMechE 199 C; Inalpolat & Kahraman 2009, J. Sound Vib. 323):
the dynamic ring-mesh force of planet ``i`` reaches a sensor fixed at angle
``theta_s`` weighted by a window of the planet's angular distance to it,

    a(t) = (1 / m_r) sum_i w(theta_i(t) - theta_s) F_i(t) + rho (x_r'' cos theta_s
           + y_r'' sin theta_s),

``F_i`` the dynamic ring-mesh force plus the deviation of the planet's static force
from the mean (unequal load sharing: a load turning with the carrier; zero when the
planets share equally),

with ``w`` a Hann window of half-width one planet spacing ``2 pi / N`` (the
windows of all planets add up to 1 at every instant), ``1 / m_r`` the ring
mass's inertance [1/kg] as the path gain, and ``rho`` the weight of the ring's
rigid-body (radial) acceleration, the optional second path.

The steady state repeats every carrier revolution, so the record at any sample
rate is the band-limited Fourier series of one revolution (orders below the
Nyquist frequency: an ideal anti-aliasing filter), evaluated at ``t_k = k / f_s``.
"""
from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.io import wavfile

from hubvib.foundation.output import atomic_path, write_text

from hubvib.signal.simulation import Simulation


def hann_window(angle, n_planets: int) -> np.ndarray:
    """Hann window of half-width ``2 pi / N`` at angular distance ``angle`` [rad] (wrapped)."""
    wrapped = (np.asarray(angle, dtype=float) + math.pi) % (2 * math.pi) - math.pi
    half = 2 * math.pi / n_planets
    w = 0.5 * (1 + np.cos(math.pi * wrapped / half))
    return np.where(np.abs(wrapped) < half, w, 0.0) if n_planets > 1 else w


def sensor_signal(sim: Simulation, sensor_angle: float, rigid_path: float = 0.0) -> np.ndarray:
    """Sensor acceleration at every step of the simulation [m/s^2]."""
    params = sim.dynamics.params
    theta = sim.carrier_angle[:, None] + np.array(params.theta)[None, :]
    window = hann_window(theta - sensor_angle, params.n_planets)
    static = sim.dynamics.static_force[params.n_planets:]
    forces = sim.ring_forces + (static - static.mean())[None, :]
    signal = (window * forces).sum(axis=1) / params.m_r
    if rigid_path:
        signal = signal + rigid_path * (sim.ring_acceleration[:, 0] * math.cos(sensor_angle)
                                        + sim.ring_acceleration[:, 1] * math.sin(sensor_angle))
    return signal


def order_coefficients(one_revolution: np.ndarray, max_order: int) -> np.ndarray:
    """Complex Fourier coefficients X_k, k = 0..max_order, of a periodic signal sampled at
    M equal steps over one revolution (endpoint excluded): x = Re sum_k X_k e^{i k phi}
    with X_0 the mean and X_k = 2 FFT_k / M."""
    M = one_revolution.size
    X = np.fft.rfft(one_revolution) / M
    X[1:] *= 2
    if M % 2 == 0:
        X[-1] /= 2
    return X[:max_order + 1]


def sampled(one_revolution: np.ndarray, carrier_hz: float, sample_rate: float,
            duration: float, speed=None) -> tuple[np.ndarray, np.ndarray]:
    """The periodic signal band-limited below ``sample_rate / 2`` at ``t_k = k / f_s``,
    0 <= t_k < duration [s]; returns (time [s], values).  With ``speed`` (a
    :class:`hubvib.signal.speed.SpeedProfile`) the signal is read at its carrier angle
    phi(t_k) and band-limited below the Nyquist order of the highest speed.

    The kept orders are put on a grid 16 times finer than the Nyquist order (inverse
    FFT) and a periodic cubic spline reads it at the sample angles: relative error
    below 1e-5 at the highest kept order.
    """
    top_hz = carrier_hz if speed is None else speed.top_hz
    nyquist_order = int(math.ceil(sample_rate / 2 / top_hz)) - 1
    max_order = min(nyquist_order, one_revolution.size // 2 - 1)
    X = np.fft.rfft(one_revolution)
    grid = 2 ** int(math.ceil(math.log2(32 * (max_order + 1))))
    spectrum = np.zeros(grid // 2 + 1, dtype=complex)
    spectrum[:max_order + 1] = X[:max_order + 1] * (grid / one_revolution.size)
    fine = np.fft.irfft(spectrum, n=grid)
    angle = np.linspace(0.0, 2 * math.pi, grid + 1)
    spline = CubicSpline(angle, np.append(fine, fine[0]), bc_type="periodic")
    time = np.arange(int(math.floor(duration * sample_rate + 1e-9))) / sample_rate
    angle = 2 * math.pi * carrier_hz * time if speed is None else speed.angle(time)
    return time, spline(np.mod(angle, 2 * math.pi))


def add_noise(values: np.ndarray, rms: float, seed: int) -> np.ndarray:
    """``values`` plus Gaussian white noise of this RMS [same unit], repeatable by seed."""
    return values + rms * np.random.default_rng(seed).standard_normal(values.size)


def write_signal_csv(path: Path, time: np.ndarray, values: np.ndarray) -> Path:
    """CSV with columns ``time_s, acceleration_m_s2`` (written atomically)."""
    buffer = io.StringIO()
    buffer.write("time_s,acceleration_m_s2\n")
    np.savetxt(buffer, np.column_stack([time, values]), delimiter=",", fmt="%.9g")
    return write_text(path, buffer.getvalue())


def write_wav(path: Path, values: np.ndarray, sample_rate: float) -> Path:
    """32-bit float WAV of ``values`` scaled to peak 1, at the sample rate rounded to
    whole Hz (written atomically)."""
    peak = float(np.max(np.abs(values))) or 1.0
    with atomic_path(path) as tmp:
        wavfile.write(tmp, int(round(sample_rate)), (values / peak).astype(np.float32))
    return Path(path)
