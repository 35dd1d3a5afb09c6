"""Carrier speed that fluctuates, the tacho that records it, and order tracking (SI).

Speed: ``Omega(t) = Omega_mean (1 + a sin(2 pi f_f t))`` with relative amplitude ``a``
and fluctuation frequency ``f_f`` [Hz], so the carrier angle is

    phi(t) = 2 pi f_c t + (a f_c / f_f) (1 - cos(2 pi f_f t))     [rad].

ASSUMED quasi-static: the fluctuation is slow against the stage's dynamics, so the
vibration stays locked to the carrier angle, ``a(t) = s(phi(t))`` with ``s`` the
steady-state signal of one revolution at the mean speed (what order tracking
presumes).  The tacho gives ``p`` pulses per carrier revolution (an encoder),
at ``phi = 2 pi k / p``.

Order tracking: the angle at every sample is interpolated through the pulses
(``phi(t_k) = 2 pi k / p``, cubic spline; its angle error falls as ``p^-4``: at one
pulse per revolution a 5 % fluctuation at 1/7 of the carrier speed leaves ~6e-4 rad,
enough to blur order 129 by several per cent), the record kept between the first and the
last pulse, then resampled to equal angle steps before the time-synchronous average
(McFadden 1987, "A revised model for the extraction of periodic waveforms by time
domain averaging", MSSP 1; Fyfe & Munck 1997, "Analysis of computed order
tracking", MSSP 11).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline


@dataclass(frozen=True)
class SpeedProfile:
    """Carrier speed over time.

    Attributes
    ----------
    carrier_hz : float
        Mean carrier speed [Hz], > 0.
    fluctuation : float
        Relative amplitude ``a`` of the speed fluctuation [-], in [0, 1).
    fluctuation_hz : float
        Its frequency ``f_f`` [Hz], > 0.
    """

    carrier_hz: float
    fluctuation: float = 0.0
    fluctuation_hz: float = 1.0

    @property
    def top_hz(self) -> float:
        """Highest carrier speed [Hz]."""
        return self.carrier_hz * (1 + self.fluctuation)

    def angle(self, time) -> np.ndarray:
        """Carrier angle phi(t) [rad] (module docstring)."""
        t = np.asarray(time, dtype=float)
        out = 2 * math.pi * self.carrier_hz * t
        if self.fluctuation:
            out = out + self.fluctuation * self.carrier_hz / self.fluctuation_hz * (
                1 - np.cos(2 * math.pi * self.fluctuation_hz * t))
        return out

    def pulses(self, duration: float, per_revolution: int = 1) -> np.ndarray:
        """Tacho pulse times [s] in [0, duration]: phi(t) = 2 pi k / p (Newton on the
        monotone phi, to 1e-13 s)."""
        pitch = 2 * math.pi / per_revolution
        last = int(math.floor(self.angle(duration) / pitch + 1e-12))
        target = pitch * np.arange(last + 1)
        t = target / (2 * math.pi * self.carrier_hz)
        for _ in range(50):
            rate = 2 * math.pi * self.carrier_hz * (
                1 + self.fluctuation * np.sin(2 * math.pi * self.fluctuation_hz * t))
            step = (self.angle(t) - target) / rate
            t = t - step
            if np.abs(step).max() < 1e-13:
                break
        return t


def angle_from_tacho(pulse_times: np.ndarray, time: np.ndarray,
                     per_revolution: int = 1) -> np.ndarray:
    """Carrier angle [rad] at the samples ``time`` [s] up to the last pulse, from the tacho
    pulses (cubic spline through ``(t_k, 2 pi k / p)``); samples after the last pulse
    are left out (the result is shorter than ``time`` then).

    Raises
    ------
    ValueError
        Fewer than two pulses (less than one revolution) or pulses not increasing.
    """
    pulse_times = np.asarray(pulse_times, dtype=float)
    if pulse_times.size < 2 or np.any(np.diff(pulse_times) <= 0):
        raise ValueError(f"tacho: {pulse_times.size} pulse(s); allowed: >= 2 increasing "
                         f"pulse times (one carrier revolution or more)")
    t = np.asarray(time, dtype=float)
    inside = t[(t >= pulse_times[0]) & (t <= pulse_times[-1])]
    pitch = 2 * math.pi / per_revolution
    return CubicSpline(pulse_times, pitch * np.arange(pulse_times.size))(inside)
