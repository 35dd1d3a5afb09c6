"""Speed fluctuation, tacho and order tracking before the TSA."""
import math

import numpy as np
import pytest

from hubvib.signal.records import synchronous_average
from hubvib.signal.accelerometer import sampled
from hubvib.signal.speed import SpeedProfile, angle_from_tacho

P = 4096
PHI = 2 * math.pi * np.arange(P) / P
#: one revolution: mesh lines and a local modulation, orders well below the Nyquist order
REVOLUTION = (np.cos(63 * PHI) + 0.4 * np.cos(129 * PHI + 1.0)) * (
    1 + 0.3 * np.exp(-((PHI - math.pi) / 0.1) ** 2))


def test_tacho_pulses_sit_at_whole_revolutions():
    steady = SpeedProfile(7.0)
    np.testing.assert_allclose(steady.pulses(1.0), np.arange(8) / 7.0, atol=1e-14,
                               err_msg="constant speed: a pulse every 1 / f_c")
    varying = SpeedProfile(7.0, 0.1, 1.3)
    pulses = varying.pulses(2.0)
    np.testing.assert_allclose(varying.angle(pulses), 2 * math.pi * np.arange(pulses.size),
                               atol=1e-9, err_msg="phi(t_k) = 2 pi k (closed-form phi)")
    assert pulses.size == int(varying.angle(2.0) // (2 * math.pi)) + 1


@pytest.mark.parametrize("per_revolution, tolerance", [(1, 0.05), (16, 1e-4)])
def test_order_tracking_recovers_the_average_a_constant_speed_assumption_smears(
        per_revolution, tolerance):
    """Tacho spline error ~ p^-4 (speed module): one pulse per revolution leaves a few per
    cent at order 129, sixteen leave < 1e-4."""
    carrier, fs = 7.0, 20000.0
    speed = SpeedProfile(carrier, 0.05, 1.0)
    t, record = sampled(REVOLUTION, carrier, fs, 10 / carrier, speed)
    reference = synchronous_average(2 * math.pi * carrier * sampled(
        REVOLUTION, carrier, fs, 10 / carrier)[0], sampled(REVOLUTION, carrier, fs,
                                                          10 / carrier)[1], 4096)
    tracked = synchronous_average(angle_from_tacho(speed.pulses(t[-1], per_revolution), t,
                                                   per_revolution), record, 4096)
    naive = synchronous_average(2 * math.pi * carrier * t, record, 4096)
    scale = np.abs(reference).max()
    assert np.abs(tracked - reference).max() < tolerance * scale, \
        f"order-tracked TSA vs the constant-speed TSA, {tolerance} (tacho spline)"
    assert np.abs(naive - reference).max() > 0.3 * scale, \
        "5 % speed fluctuation smears the TSA of a constant-speed assumption"


def test_a_single_pulse_is_refused():
    with pytest.raises(ValueError, match="tacho: 1 pulse"):
        angle_from_tacho(np.array([0.0]), np.linspace(0, 1, 10))
