"""Probability of detection from physics: threshold, Monte Carlo POD, FE resolution, records
against the mesh timing."""
import math

import numpy as np
import pytest
from tests.helpers.synthetic_rows import TIMING, synthetic_model

from hubvib.design import preset_design
from hubvib.detection.carrier import MeshTiming, carrier_study, mesh_timing, observed_omega
from hubvib.detection.options import DetectionOptions
from hubvib.detection.pod import measured_threshold, pod_study

OPTIONS = DetectionOptions(samples=600)


def test_family_threshold_gives_the_family_wise_false_alarm_rate():
    # independent check by sampling: 4 modes, each identified twice with normal errors of
    # its own sigma; an alarm when any drop exceeds its threshold (Sidak per-mode rate)
    options = DetectionOptions(watched_modes=4, false_alarm_rate=0.05)
    sigma = np.array([0.4, 1.2, 1.5, 2.0])
    rng = np.random.default_rng(0)
    e = rng.standard_normal((2, 400_000, 4)) * sigma
    alarm = ((e[1] - e[0]) < -measured_threshold(sigma, options.per_mode_rate())).any(axis=1)
    assert alarm.mean() == pytest.approx(0.05, abs=1.5e-3), \
        "sampled family-wise false-alarm rate vs 0.05 (Sidak, independent modes), 4 sigma_MC"
    single = ((e[1] - e[0]) < -measured_threshold(sigma, 0.05)).any(axis=1).mean()
    assert single > 0.18, "uncorrected per-mode 0.05 over 4 modes: about 1 - 0.95^4 = 0.185"


@pytest.fixture(scope="module")
def direct_pod():
    return pod_study(synthetic_model("direct"), OPTIONS, TIMING)


def test_pod_is_the_false_alarm_rate_at_depth_0_and_rises_with_depth(direct_pod):
    pod = direct_pod
    sigma = math.sqrt(0.01 * 0.99 / OPTIONS.samples)
    assert np.allclose(pod.pod[0], OPTIONS.per_mode_rate(), atol=1e-12), \
        "own baseline: an intact reducer shifts by exactly 0, each mode alarms at its rate"
    for T, family in pod.family_pod.items():
        assert family[0] == pytest.approx(OPTIONS.false_alarm_rate, abs=1e-12), \
            f"family-wise false-alarm rate at depth 0, {T} s records"
        assert (np.diff(family) >= -0.02).all()
    assert (pod.family_pod[600.0] >= pod.family_pod[10.0] - 1e-12).all(), \
        "longer records detect at least as well"
    # model baseline: the threshold is the alpha quantile of independent calibration samples,
    # so each estimate scatters by about sqrt(2) binomial sigmas
    rate = OPTIONS.per_mode_rate()
    assert (pod.pod_model[0] <= rate + 5 * math.sqrt(2) * sigma).all()
    assert pod.pod_model[0].mean() <= rate + 2 * sigma
    best = int(np.argmax(pod.pod[-1]))
    assert pod.pod[-1, best] > 0.99
    assert (np.diff(pod.pod[:, best]) >= -0.02).all(), "POD rises with depth"
    assert pod.detectable_depth()[best] <= pod.depths[-1]


def test_shift_distribution_brackets_the_nominal_shift(direct_pod):
    pod = direct_pod
    moving = np.abs(pod.nominal.shift_hz[-1]) > 10 * pod.threshold_hz
    inside = ((pod.shift_p05_hz[-1] <= pod.nominal.shift_hz[-1])
              & (pod.nominal.shift_hz[-1] <= pod.shift_p95_hz[-1]))
    assert inside[moving].all()


def test_a_shift_below_its_own_fe_error_is_not_resolved():
    # the c_ru body error (10 %) exceeds what the crack does to it (5.8 %)
    model = synthetic_model("direct", c_ru_error=1.663e9, c_r_drop=0.0, c_rp_drop=0.0)
    pod = pod_study(model, DetectionOptions(samples=200), TIMING, model_baseline=False)
    carried = pod.nominal.carried_by[-1]
    assert (carried == "c_ru").sum() >= 3 and set(carried) == {"c_ru", "none"}
    assert not pod.resolved[-1].any()
    assert np.isnan(pod.detectable_depth()).all()
    assert pod.pod[-1].max() > 0.9  # the Monte Carlo alone would have called it detectable
    assert "resolved" in pod.rows()[-1]


def test_mesh_timing_of_the_raba_design():
    from hubvib.cases.sweep import CrackSweep

    timing = mesh_timing(preset_design("raba118"), 15.0)
    assert timing.ring_teeth == 64 and timing.n_planets == 3
    assert 1.0 < timing.contact_ratio < 2.0
    # N eps / z of the time, passes of eps 2 pi / (z Omega)
    assert timing.engaged_fraction == pytest.approx(3 * timing.contact_ratio / 64, rel=1e-15)
    assert timing.pass_seconds == pytest.approx(timing.contact_ratio * 2 * math.pi / 64 / 15)


def _floquet_omega(w_in, w_out, fraction, period, near):
    """Characteristic frequency of x'' + w(t)^2 x = 0, w switching between w_in (for
    fraction * period) and w_out: from the exact monodromy matrix, the branch nearest
    ``near`` (frequencies are defined modulo 2 pi / period)."""
    def step(w, t):
        return np.array([[math.cos(w * t), math.sin(w * t) / w],
                         [-w * math.sin(w * t), math.cos(w * t)]])
    monodromy = step(w_in, fraction * period) @ step(w_out, (1 - fraction) * period)
    theta = math.acos(np.clip(np.trace(monodromy) / 2, -1, 1))
    n = round((near * period - theta) / (2 * math.pi))
    branches = [(2 * math.pi * m + s * theta) / period for m in (n - 1, n, n + 1)
                for s in (1, -1)]
    return min(branches, key=lambda w: abs(w - near))


@pytest.mark.parametrize("drop", [0.002, 0.02])
def test_long_record_sees_the_time_averaged_stiffness(drop):
    # mode 13 of Raba 118/76 (4548 Hz) dropping while planet 1 passes the crack, one pass
    # per planet at 150 rpm: averaging method vs the exact Floquet exponent
    w_out = 2 * math.pi * 4548.0
    w_in = w_out * (1 - drop)
    period = 2 * math.pi / (TIMING.n_planets * TIMING.carrier_speed)
    averaged = float(observed_omega(np.array(w_in), np.array(w_out),
                                    TIMING.engaged_fraction, True))
    exact = _floquet_omega(w_in, w_out, TIMING.engaged_fraction, period, averaged)
    shift = averaged / w_out - 1
    assert abs(exact / averaged - 1) < 0.02 * abs(shift), \
        "first-order averaging vs exact monodromy, within 2 % of the shift"
    assert float(observed_omega(np.array(w_in), np.array(w_out), 0.1, False)) == w_in


def test_carrier_study_steps_in_and_out_of_the_engagement():
    model = synthetic_model("series")
    study = carrier_study(model, TIMING, 10.0)
    inside = (study.angle >= 0) & (study.angle <= TIMING.pass_angle)
    np.testing.assert_array_equal(study.omega_angle[inside], np.broadcast_to(
        study.omega_in[-1], (inside.sum(), study.omega_in.shape[1])))
    np.testing.assert_array_equal(study.omega_angle[~inside][0], study.omega_out[-1])
    assert (study.omega_angle_min[inside][0] <= study.omega_angle[inside][0] + 1e-9).all()
    assert study.modulation_index[0].max() == 0.0
    fraction = MeshTiming(64, 1.5, 4, 1.0).engaged_fraction
    assert fraction == pytest.approx(4 * 1.5 / 64)


def test_one_batch_of_variants_gives_each_variant_s_own_frequencies():
    # nominal_shifts solves its seven variants in one batch; each point is one LAPACK call,
    # so the frequencies equal those of the variants solved on their own, to the last bit
    from dataclasses import replace

    from hubvib.detection.uncertainty import nominal, observed_frequencies, observed_frequencies_of

    model = synthetic_model("series")
    variants = [model, replace(model, c_ru_body=(model.c_ru_body[0],) * len(model.depths)),
                replace(model, c_rp_ratio=(1.0,) * len(model.depths))]
    fraction, long = TIMING.engaged_fraction, TIMING.long_record(10.0)
    joined = observed_frequencies_of([(v, nominal(v)) for v in variants], fraction, long)
    for v, together in zip(variants, joined):
        assert np.array_equal(together, observed_frequencies(v, nominal(v), fraction, long))
    with pytest.raises(ValueError, match="share their params"):
        observed_frequencies_of([(model, nominal(model)),
                                 (replace(model, params=model.params.replace(c_rp=1e9)),
                                  nominal(model))], fraction, long)


@pytest.mark.parametrize("apply", ["series", "direct"])
@pytest.mark.parametrize("per_sample_depth", [False, True], ids=["every depth", "depth_index"])
def test_drawn_samples_at_every_depth_in_one_call_are_the_per_depth_solves(apply,
                                                                           per_sample_depth):
    # observed_frequencies tiles the samples over the depths and builds every depth's
    # changes in one call: each (sample, depth) point must be the one a separate call per
    # depth gives (the code before the tiling), to the last bit, on scattered samples
    from hubvib.detection.uncertainty import changes, draw, observed_frequencies
    from hubvib.lumped.batch import batch_frequencies

    model = synthetic_model(apply)
    samples = draw(model, DetectionOptions(), 40, np.random.default_rng(3))
    fraction, long = TIMING.engaged_fraction, TIMING.long_record(10.0)
    depth_index = (np.random.default_rng(4).integers(0, len(model.depths), samples.n)
                   if per_sample_depth else None)
    ks = [0, depth_index] if per_sample_depth else list(range(len(model.depths)))
    omega = np.stack([np.stack([batch_frequencies(model.params,
                                                  changes(model, samples, k, engaged)).omega
                                for k in ks], axis=1) for engaged in (True, False)])
    reference = observed_omega(omega[0], omega[1], fraction, long) / (2 * math.pi)
    together = observed_frequencies(model, samples, fraction, long, depth_index=depth_index)
    assert together.shape == (samples.n, len(ks), reference.shape[-1])
    assert np.array_equal(together, reference)


def test_variants_must_scatter_the_same_fields():
    from hubvib.detection.uncertainty import draw, nominal, observed_frequencies_of

    model = synthetic_model("series")
    drawn = draw(model, DetectionOptions(), 5, np.random.default_rng(0))
    with pytest.raises(ValueError, match="the samples must scatter the same fields"):
        observed_frequencies_of([(model, nominal(model)), (model, drawn)],
                                TIMING.engaged_fraction, TIMING.long_record(10.0))


def test_map_pod_without_family_curves_has_the_same_per_mode_numbers():
    # the detectability map skips the family curves, the drift model and the reference
    # modes; what it keeps (per-mode POD, nominal shifts, thresholds) must not change
    model = synthetic_model("series")
    options = DetectionOptions(samples=200)
    full = pod_study(model, options, TIMING, model_baseline=False)
    lean = pod_study(model, options, TIMING, model_baseline=False, family_curves=False)
    assert full.family_pod and not lean.family_pod and lean.drift is None
    for name in ("pod", "threshold_hz", "sigma_hz", "shift_mean_hz", "watched"):
        assert np.array_equal(getattr(full, name), getattr(lean, name)), name
    assert np.array_equal(full.nominal.frequency_hz, lean.nominal.frequency_hz)
    assert np.array_equal(full.detectable_depth(), lean.detectable_depth(), equal_nan=True)


def test_other_method_pod_is_the_full_pod_s_family_curve():
    # compare_methods runs the other c_rp method's POD without the model baseline and
    # the drift curves (nothing reads them); its family POD is the full run's, bit for bit
    from hubvib.detection.mesh_stiffness import compare_methods

    model = synthetic_model("series")
    options = DetectionOptions(samples=200)
    comparison = compare_methods(model, TIMING, options.record_length, options)
    full = pod_study(model.with_c_rp_method(comparison.other), options, TIMING)
    other = comparison.other_pod
    assert other.pod_model is None and not other.family_pod_drift
    assert sorted(other.family_pod) == sorted(full.family_pod)
    for T, values in full.family_pod.items():
        assert np.array_equal(other.family_pod[T], values), f"{T} s records"
    assert np.array_equal(other.pod, full.pod)
