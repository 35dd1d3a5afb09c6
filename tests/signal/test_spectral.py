"""Order spectrum, angle resampling, band-limited sampling, labels and condition indicators."""
import math

import numpy as np
import pytest

from hubvib.signal.indicators import GearOrders, indicators, residual
from hubvib.signal.accelerometer import hann_window, sampled
from hubvib.signal.spectral import (angle_domain, label_order, order_spectrum, record_spectrum,
                                    spectrogram)
from hubvib.signal.signature_study import harmonic_rules
from hubvib.design import preset_design

RABA = preset_design("raba118")  # the reference case (hubvib.design.presets)


GEAR = GearOrders(ring_teeth=64, n_planets=3, harmonics=3)


def test_order_spectrum_gives_c_k_and_phi_k_of_seed_000_eq_5():
    P = 512
    phi = 2 * math.pi * np.arange(P) / P
    lines = {1: (0.3, 0.4), 7: (0.05, -2.0), 63: (1.2, 1.0)}
    F = 0.25 + sum(c * np.cos(k * phi + p) for k, (c, p) in lines.items())
    s = order_spectrum(F)
    assert abs(s.amplitude[0] / 2 - 0.25) < 1e-14, "c_0 / 2 is the mean"
    for k, (c, p) in lines.items():
        assert abs(s.amplitude[k] - c) < 1e-13 and abs(s.phase[k] - p) < 1e-12
    np.testing.assert_allclose(s.rebuild(P), F, atol=1e-12,
                               err_msg="eq. (5) with c_k, phi_k must rebuild F")
    assert s.nyquist_order == 255


def test_angle_resampling_of_a_non_integer_number_of_samples_per_revolution():
    fc, fs = 7.2222, 20000.0                           # 2769.2 samples per revolution
    t = np.arange(int(10.3 * fs / fc)) / fs
    angle = 2 * math.pi * fc * t
    x = 2.0 * np.cos(63 * angle + 0.5) + 0.7 * np.cos(129 * angle)
    record = angle_domain(angle, x, 4096)
    assert record.revolutions == 10 and abs(record.leftover - 0.3) < 1e-3
    s = order_spectrum(record.synchronous_average())
    assert abs(s.amplitude[63] - 2.0) < 1e-4 and abs(s.amplitude[129] - 0.7) < 1e-4, \
        "cubic resampling keeps the lines to 1e-4 at 14 samples per period"
    whole = record_spectrum(record)
    assert abs(whole.amplitude[63 * 10] - 2.0) < 1e-4 and whole.orders[630] == 63


def test_band_limited_sampling_of_a_periodic_signal():
    M = 19200
    phi = 2 * math.pi * np.arange(M) / M
    one = np.cos(5 * phi + 0.3) + 0.5 * np.sin(1300 * phi) + 0.2 * np.cos(2000 * phi)
    t, v = sampled(one, 7.2222, 20000.0, 10 / 7.2222)
    angle = 2 * math.pi * 7.2222 * t
    expected = np.cos(5 * angle + 0.3) + 0.5 * np.sin(1300 * angle)   # 2000 > Nyquist 1384
    assert np.abs(v - expected).max() < 1e-5, "ideal anti-aliasing and 1e-5 interpolation"


def test_hann_windows_of_equally_spaced_planets_add_up_to_one():
    angle = np.linspace(-7, 7, 1001)
    total = sum(hann_window(angle + 2 * math.pi * i / 3, 3) for i in range(3))
    np.testing.assert_allclose(total, 1.0, atol=1e-15)
    assert hann_window(0.0, 3) == 1.0 and hann_window(2 * math.pi / 3, 3) == 0.0


@pytest.mark.parametrize("order, label", [
    (64, "z_r"), (63, "21xN (z_r - 1)"), (66, "22xN (z_r + 2)"), (129, "43xN (2xz_r + 1)"),
    (192, "3xz_r"), (9, "3xN"), (1, "carrier"), (90 / 26, "sun"), (65, "unexplained"),
    (4, "unexplained")])
def test_carrier_order_labels(order, label):
    assert label_order(order, harmonic_rules(3, RABA))[0] == label


def test_indicators_of_signals_with_known_values():
    P = 4096
    phi = 2 * math.pi * np.arange(P) / P
    sine = np.cos(63 * phi)
    v = indicators(sine, GEAR, [np.var(residual(sine, GEAR)) or 1.0])
    assert abs(v.kurtosis - 1.5) < 1e-12, "kurtosis of a sine is 3/2"
    assert abs(v.crest_factor - math.sqrt(2)) < 1e-12, "crest factor of a sine is sqrt 2"
    assert abs(v.fm0 - 2.0) < 1e-12, "FM0 of a pure mesh line: peak-to-peak 2A over A"
    assert abs(v.rms - 1 / math.sqrt(2)) < 1e-12
    sidebands = sine + 0.1 * np.cos(60 * phi) + 0.05 * np.cos(69 * phi)
    assert abs(indicators(sidebands, GEAR, [1.0]).ser - 0.15) < 1e-12, \
        "SER: sidebands at +-nN (0.1 + 0.05) over the mesh line (1)"
    noise = np.random.default_rng(3).standard_normal(2 ** 16)
    r = residual(noise, GEAR)
    assert abs(indicators(noise, GEAR, [np.var(r)]).na4 - 3.0) < 0.1, \
        "NA4 of Gaussian noise against its own variance is its kurtosis, 3"


def test_spectrogram_finds_a_tone():
    fs = 20000.0
    t = np.arange(20000) / fs
    s = spectrogram(np.sin(2 * math.pi * 462.0 * t), fs, 1024)
    peak = s.frequency_hz[s.amplitude.mean(axis=1).argmax()]
    assert abs(peak - 462.0) < fs / 1024
