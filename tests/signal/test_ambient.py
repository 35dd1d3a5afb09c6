"""The ambient part of the simulated record (hubvib.signal.ambient) against the lumped
model's own transfer function, and the line notch of the identifier."""
import math

import numpy as np
import pytest
from scipy.signal import welch

from hubvib.identification.bfft import identify_mode, line_mask
from hubvib.identification.records import simulate
from hubvib.signal.ambient import FORCED, AmbientForcing, ambient_record, engaged_ratio
from hubvib.signal.dynamics import planetary_dynamics
from hubvib.signal.mesh_curves import synthetic_curves
from hubvib.signal.mesh_phase import design_phasing
from hubvib.signal.accelerometer import hann_window
from hubvib.studies.scene import load_scene

FS = 20000.0


def _raba(damping=0.05, crack_factor=1.0):
    scene = load_scene("raba118_signal")
    curves = synthetic_curves(scene.design, crack_factor=crack_factor, depth=0.01)
    curves = curves.to_preset(scene.params.c_sp, scene.params.c_rp)
    return scene, curves, planetary_dynamics(scene.params, curves, damping, 1000.0)


def _psd_from_transfer(dynamics, weights, f, forcing):
    """One-sided PSD [(m/s^2)^2/Hz] of a = sum_i w_i kbar_i g_i . q / m_r under independent
    forces of one-sided PSD G on the central coordinates: G sum_j |c H(f) e_j|^2, H the
    receptance (K - w^2 M + i w C)^-1 of the lumped model (an independent computation in
    the frequency domain)."""
    s = dynamics.system
    N = dynamics.n_planets
    c = (weights * dynamics.mean[N:]) @ s.rows[N:] / dynamics.params.m_r
    M = np.diag(s.mass)
    out = []
    for fk in f:
        w = 2 * math.pi * fk
        h = np.linalg.solve((s.stiffness - w * w * M + 1j * w * s.damping).T, c)
        out.append(forcing.psd * np.sum(np.abs(h[list(FORCED)]) ** 2))
    return np.array(out)


@pytest.mark.slow
def test_ambient_record_has_the_psd_of_the_lumped_transfer_function():
    # the carrier held at 0: the sensor window is fixed, the ambient response stationary;
    # Welch PSD (0.1 s segments, 8 s) against the frequency-domain PSD, averaged over
    # +-3 % around each resonance above 1 kHz (about 4 % statistical scatter: tolerance 12 %)
    scene, curves, dynamics = _raba()
    forcing = AmbientForcing(2.0)
    angle = np.zeros(int(8 * FS))
    record = ambient_record(dynamics, curves, design_phasing(scene.design), forcing, angle, FS,
                            0.0, 0, np.random.default_rng(3))
    f, P = welch(record, FS, nperseg=2048)
    theta = np.array(scene.params.theta)
    weights = hann_window(theta, dynamics.n_planets)
    exact = _psd_from_transfer(dynamics, weights, f, forcing)
    peaks = [fn for fn in dynamics.omega / (2 * math.pi) if 1000 < fn < 0.45 * FS]
    checked = 0
    for fn in peaks:
        band = (f > 0.97 * fn) & (f < 1.03 * fn)
        if not band.any() or exact[band].mean() < 1e-3 * exact.max():
            continue  # a mode the central forces and this sensor barely see
        checked += 1
        assert P[band].mean() == pytest.approx(exact[band].mean(), rel=0.12), \
            f"Welch PSD at {fn:.0f} Hz vs the receptance's (exact discretisation), 12 %"
    assert checked >= 3


def test_engaged_ratio_of_a_softer_tooth_is_below_one():
    # a cracked tooth twice as compliant softens the mesh over its window; without a crack
    # the ratio is 1 exactly
    scene, _, _ = _raba()
    assert engaged_ratio(synthetic_curves(scene.design)) == 1.0
    ratio = engaged_ratio(synthetic_curves(scene.design, crack_factor=2.0))
    assert 0.5 < ratio < 0.99, "one of one-to-two pairs twice as compliant: ratio in (0.5, 1)"


def test_line_mask_finds_mesh_lines_and_spares_a_clean_band():
    # exponential ordinates: the family-wise rate of a false line is 1e-3 per band
    rng = np.random.default_rng(0)
    clean = rng.exponential(1.0, (200, 2000))
    false = np.mean([line_mask(p).any() for p in clean])
    assert false < 0.01, "line_mask flags a line-free band at most at ~1e-3 (200 bands)"
    p = clean[0].copy()
    p[[100, 700, 1500]] += 60.0
    assert set(np.flatnonzero(line_mask(p))) == {100, 700, 1500}


def test_notched_identification_ignores_strong_lines_near_the_mode():
    # a single mode (Au's simulation) plus sinusoids at exact frequency lines: the
    # notched fit returns the mode, within 4 Cramer-Rao standard deviations of the truth
    fn, zeta, T = 1500.0, 0.02, 20.0
    record = simulate(fn, zeta, T, FS, 100.0, np.random.default_rng(5))
    t = np.arange(record.values.size) / FS
    amplitude = 30 * record.values.std()
    lines = sum(amplitude * np.cos(2 * math.pi * (fn + d) * t) for d in (-21.0, 7.0, 28.0))
    notched = identify_mode(record.values + lines, FS, fn, 0.02, lines=True)
    assert abs(notched.frequency_hz - fn) < 4 * notched.sigma_hz, \
        "notched fit within 4 sigma (Cramer-Rao) of the simulated mode"
    plain = identify_mode(record.values + lines, FS, fn, 0.02)
    assert abs(plain.frequency_hz - fn) > abs(notched.frequency_hz - fn), \
        "without the notch the lines pull the fit away"


@pytest.mark.parametrize("key, value", [("ambient_force_psd_N2_Hz", -1.0),
                                        ("ambient_force_psd_N2_Hz", float("nan")),
                                        ("ambient_seed", 1.5)])
def test_ambient_keys_are_checked(key, value):
    from hubvib.foundation.errors import SceneError
    from hubvib.signal.options import parse_signal_table

    with pytest.raises(SceneError, match=rf"\[signal\] {key} = "):
        parse_signal_table({key: value})
    assert parse_signal_table({}).ambient_force_psd_N2_Hz == 0.0, "default: no ambient part"


def test_frequency_route_false_alarm_and_growing_pod():
    # depth 0: the Bonferroni test's exact family-wise rate 1 - (1 - alpha/m)^m <= alpha;
    # a softer cracked tooth lowers the frequencies and raises the POD
    from hubvib.signal.frequency_route import frequency_route

    scene, _, _ = _raba()
    p = scene.params
    curves = [synthetic_curves(scene.design, crack_factor=k, depth=0.001 * k).to_preset(
        p.c_sp, p.c_rp) for k in (1.0, 1.5, 3.0)]
    route = frequency_route(p, curves, design_phasing(scene.design), 0.01, 600.0, FS, 0.05)
    m = len(route["modes"])
    assert m >= 3
    assert route["pod"][0] == pytest.approx(1 - (1 - 0.05 / m) ** m, rel=1e-9), \
        "Sidak: exact family-wise rate of m independent one-sided tests at alpha / m"
    assert route["pod"][0] <= 0.05 and route["pod"][0] <= route["pod"][1] <= route["pod"][2]
    assert max(route["shift_hz"][2]) <= 1e-9 and min(route["shift_hz"][2]) < 0, \
        "a softer ring mesh lowers every frequency (Rayleigh)"


def test_observed_frequencies_are_those_of_the_time_averaged_stiffness():
    # first-order averaging (Nayfeh & Mook): the mean of the engaged / free eigenvalues
    # against the eigenvalues of the time-averaged stiffness matrix (every planet softened
    # for its share of the time), for the distinct modes: they differ in second order, within
    # 5 % of the shift for a tooth 1.3 times as compliant
    from hubvib.lumped import natural_modes
    from hubvib.signal.frequency_route import observed_hz

    scene, _, _ = _raba()
    p = scene.params
    phasing = design_phasing(scene.design)
    curves = synthetic_curves(scene.design, crack_factor=1.3, depth=0.003).to_preset(
        p.c_sp, p.c_rp)
    ratio = engaged_ratio(curves)
    span = (curves.cracked_s[-1] - curves.cracked_s[0]) / phasing.ring_base_radius
    share = span / (2 * math.pi)  # of the time each planet holds the cracked window
    averaged = natural_modes(p.replace(c_rp_factors=(1 + share * (ratio - 1),) * 3)).omega
    intact = natural_modes(p).omega
    seen = observed_hz(p, curves, phasing) * 2 * math.pi
    distinct = [j for j in range(intact.size)
                if np.min(np.abs(np.delete(intact, j) - intact[j])) > 1e-3 * intact[j]]
    for j in distinct:
        assert seen[j] - intact[j] == pytest.approx(averaged[j] - intact[j], rel=0.05,
                                                    abs=1e-6 * intact[j]), \
            f"mode {j + 1}: averaged eigenvalues vs the averaged stiffness, 5 % of the shift"
