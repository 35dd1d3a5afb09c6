"""Detection and diagnosis through the spectrum-model protocol: the rigid-ring model
unchanged through it, the elastic ring's Monte Carlo (batched solve, zero scatter, POD),
its calibration on a noise model the diagnosis was not tuned on, and ``hubvib diagnose
--ring``."""
import math
from dataclasses import replace

import numpy as np
import pytest
from tests.helpers.synthetic_rows import TIMING, synthetic_model

from hubvib.cli import main
from hubvib.detection.budget import chunked_frequencies
from hubvib.detection.calibration import calibrate, student_errors
from hubvib.detection.diagnosis import reference, synthetic_measurements
from hubvib.detection.drift import drift_model
from hubvib.detection.pod import family_pod, monte_carlo_shifts as sampled_shifts
from hubvib.detection.elastic_model import (ElasticSamples, batched_hz,
                                                  elastic_spectrum_model, unscattered)
from hubvib.detection.options import DetectionOptions
from hubvib.detection.spectrum_model import RigidSpectrum, SpectrumModel, as_spectrum_model
from hubvib.detection.uncertainty import draw, nominal, observed_frequencies

OPTIONS = DetectionOptions(samples=400)


# ---------------------------------------------------------------- a small elastic ring

def _synthetic_cases(depths=(0.0, 0.004, 0.008, 0.012)):
    """Elastic cases of a small synthetic ring (8 coordinates, 12 teeth, M = I) coupled to
    the Raba lumped model: ring modes at 1.5-9 kHz, a crack softening the ring along one
    shape in proportion to its depth, a foundation part of its stiffness."""
    from hubvib.reducer.stages import lumped_parameters
    from hubvib.design.presets import preset_design
    from hubvib.elastic.cases import ElasticCase
    from hubvib.elastic.content import mode_content, multiplicities
    from hubvib.elastic.model import ElasticSpectrum
    from hubvib.lumped.elastic_ring import RingOperators, coupled_modes

    params = lumped_parameters(preset_design("raba118"))
    rng = np.random.default_rng(3)
    n, z, probe_points = 8, 12, 16
    q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    omega = 2 * math.pi * np.linspace(1500.0, 9000.0, n)
    body = q @ np.diag(omega ** 2) @ q.T
    f = rng.standard_normal((n, 2))
    foundation = 0.05 * omega[0] ** 2 * (f @ f.T) / n
    crack = rng.standard_normal(n)
    crack = np.outer(crack, crack) / (crack @ crack) * 0.15 * omega[3] ** 2
    angles = 2 * math.pi * np.arange(z) / z
    directions = np.column_stack([-np.sin(angles), np.cos(angles)])
    contact = rng.standard_normal((n, z)) * 1e-1
    probe = rng.standard_normal((2 * probe_points, n))
    cases = []
    for depth in depths:
        K = body - depth / depths[-1] * crack + foundation
        ops = RingOperators(0.5 * (K + K.T), np.eye(n), contact, np.ones(z), angles,
                            directions, probe)
        modes = coupled_modes(params, ops, 2, 2e9, max_hz=10e3)
        content = tuple(mode_content(modes, j, 3) for j in range(modes.omega.size))
        away = ElasticSpectrum(modes, content, multiplicities(modes.frequency_hz), 2, None)
        cases.append(ElasticCase(depth, away, away, 2e9, (1e8, 1e6), n, 20.0, None, ops,
                                 foundation, params))
    return cases


@pytest.fixture(scope="module")
def small():
    depths = (0.0, 0.004, 0.008, 0.012)
    cases = _synthetic_cases(depths)
    return cases, elastic_spectrum_model(depths, cases)


def test_both_models_implement_the_protocol(small):
    _, model = small
    assert isinstance(model, SpectrumModel)
    assert isinstance(as_spectrum_model(synthetic_model("direct")), RigidSpectrum)
    with pytest.raises(TypeError, match="neither a CrackModel nor a SpectrumModel"):
        as_spectrum_model(object())


def test_rigid_protocol_reproduces_todays_reference():
    """The rigid model through the protocol gives the reference the functions of
    ``uncertainty`` gave before it, bit for bit (same draws, same solves)."""
    model = synthetic_model("series")
    ref = reference(model, OPTIONS, TIMING)
    rng = np.random.default_rng(OPTIONS.seed + 1)
    fraction, long = TIMING.engaged_fraction, TIMING.long_record(OPTIONS.record_length)
    samples = chunked_frequencies(model, draw(model, OPTIONS, OPTIONS.samples, rng), fraction,
                                  long)
    nominal_hz = observed_frequencies(model, nominal(model), fraction, long)[0]
    drift = drift_model(model.parameters(0), nominal_hz[0], OPTIONS, model.method)
    assert np.array_equal(ref.frequency_hz, samples)
    assert np.array_equal(ref.nominal_hz, nominal_hz)
    assert np.array_equal(ref.drift_cov, drift.covariance())
    assert np.array_equal(ref.sigma_hz, OPTIONS.sigma_hz(nominal_hz[0]))
    assert ref.mesh_stiffness == model.mesh_stiffness() and ref.ring == "rigid"


def test_rigid_synthetic_measurements_unchanged_through_the_protocol():
    """``synthetic_measurements`` on the wrapper and on the CrackModel itself: identical."""
    model = synthetic_model("series")
    depths = np.array([0.0, 0.01, 0.02])
    a = synthetic_measurements(model, OPTIONS, TIMING, depths, seed=4)
    b = synthetic_measurements(RigidSpectrum(model), OPTIONS, TIMING, depths, seed=4)
    at = model.at_depths(np.concatenate([[0.0], depths]))
    rng = np.random.default_rng(4)
    f = observed_frequencies(at, draw(at, OPTIONS, depths.size, rng),
                             TIMING.engaged_fraction,
                             TIMING.long_record(OPTIONS.record_length),
                             depth_index=np.arange(1, 4))
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
    sigma = OPTIONS.sigma_hz(observed_frequencies(at, nominal(at), TIMING.engaged_fraction,
                                                  True)[0, 0])
    noise = rng.standard_normal(f.shape) * sigma
    assert np.array_equal(a[1], f[:, 0] + noise[:, 0])


def test_zero_scatter_gives_the_nominal_spectra(small):
    """Every factor 1 and no FE error: the batched solve gives each case's own coupled
    spectrum (``coupled_modes``, generalised eigh) to round-off (1e-9 relative)."""
    cases, model = small
    values = model.frequencies_of(unscattered(model, 3))
    for k, case in enumerate(cases):
        expected = case.away.frequency_hz[model.operators[k].slot]
        assert np.allclose(values[:, k], expected, rtol=1e-9, atol=0), k


def test_batched_solve_equals_coupled_modes_on_the_scattered_operators(small):
    """A sample with scattered masses, springs, k_rest, foundation and ring mass equals
    ``lumped.elastic_ring.coupled_modes`` of the same reducer built directly (the
    parameters replaced, the ring's foundation and mass scaled) to 1e-9 relative."""
    from hubvib.lumped.elastic_ring import coupled_modes

    cases, model = small
    case, op = cases[2], model.operators[2]
    factors = {"m_s": 1.03, "m_c": 0.98, "m_p": 1.02, "mu_s": 0.97, "mu_c": 1.01,
               "mu_p": 1.04}
    springs = {"c_c": 1.1, "c_su": 0.9, "c_cu": 1.2, "c_p": 0.85, "c_sp": 1.15}
    samples = ElasticSamples({k: np.array([v]) for k, v in factors.items()},
                             np.array([0.97]),
                             {**{k: np.array([v]) for k, v in springs.items()},
                              "k_rest": np.array([0.92]), "foundation": np.array([1.3])},
                             np.zeros(1))
    mine = batched_hz(op, samples, model.masks)[0]
    p = case.params.replace(**{name: getattr(case.params, name) * v
                               for name, v in {**factors, **springs}.items()})
    ops = case.operators
    ring = replace(ops, K=ops.K + 0.3 * case.foundation_K, M=0.97 * ops.M)
    direct = coupled_modes(p, ring, case.away.carrier_tooth, 0.92 * case.k_rest).frequency_hz
    assert set(model.stiffness_names) == set(springs) | {"k_rest", "foundation"}
    assert np.allclose(mine, direct, rtol=1e-9, atol=0)


def test_pod_at_depth_zero_is_the_false_alarm_rate_and_rises_with_depth(small):
    """Own intact record as baseline: at depth 0 every sampled reducer's shift is 0, so
    the family POD is the Sidak family rate exactly; it does not fall as the synthetic
    crack deepens and reaches 1 at the deepest."""
    _, model = small
    options = DetectionOptions(samples=300)
    shifts = sampled_shifts(model, options)
    sigma = options.sigma_hz(model.nominal_hz(None, None)[0])
    watched = (3, 4, 5)
    rate = options.per_mode_rate(len(watched))
    pod = family_pod(shifts, sigma, watched, rate)
    assert abs(pod[0] - options.false_alarm_rate) < 1e-9, pod
    assert np.all(np.diff(pod) >= -1e-12) and pod[-1] > 0.99, pod


def test_fe_error_scales_each_change_by_one_common_factor(small):
    """The FE error: one z per sample, ``z FE_CHANGE_ERROR |change|`` on every mode."""
    _, model = small
    base = unscattered(model, 1)
    moved = replace(base, z=np.array([2.0]))
    change = model.frequencies_of(moved)[0] - model.frequencies_of(base)[0]
    nominal = model.nominal_grid_hz - model.nominal_grid_hz[0]
    assert np.allclose(change, 2.0 * model.fe_change_error * np.abs(nominal), atol=1e-9)


@pytest.mark.slow
def test_elastic_calibration_on_student_t_noise(small):
    """Student-t errors (8 degrees of freedom, unit variance), a noise model the diagnosis
    was not tuned on, on the small elastic ring: intervals over depths uniform on the
    sweep hold the true depth at the nominal 90 % within 3 binomial standard errors, and
    intact reducers are called cracked at about the 1 % false-alarm rate."""
    from hubvib.detection.diagnosis import NO_CRACK

    _, model = small
    options = DetectionOptions(samples=400)
    ref = reference(model, options, TIMING)
    trials = 150
    result = calibrate(model, options, TIMING, ref, [4, 5, 6], trials)
    tolerance = 3 * math.sqrt(0.9 * 0.1 / trials)
    assert abs(result.coverage - 0.9) <= tolerance, (
        f"Student-t (dof 8) noise: coverage {result.coverage:.3f} against 0.9 +- "
        f"{tolerance:.3f}")
    assert result.intact.get("crack indicated", 0.0) <= 0.01 + 3 * math.sqrt(0.01 / trials), (
        f"Student-t (dof 8) noise: intact reducers called cracked {result.intact}")
    assert result.intact.get(NO_CRACK, 0.0) > 0.9


def test_elastic_at_depths_interpolates_linearly(small):
    """Between two sweep depths a sample's frequency is the linear interpolation."""
    _, model = small
    halfway = model.at_depths([0.0, 0.002, 0.004])
    values = halfway.nominal_hz(None, None)
    assert np.allclose(values[1], 0.5 * (model.nominal_grid_hz[0] + model.nominal_grid_hz[1]))
    assert np.array_equal(values[2], model.nominal_grid_hz[1])
    with pytest.raises(ValueError, match="within the sweep"):
        model.at_depths([0.0, 0.02])


# ------------------------------------------------------------------ the command

def _csv(tmp_path, text="frequency_hz,baseline_hz\n4700,4710\n"):
    path = tmp_path / "m.csv"
    path.write_text(text)
    return path


def test_bad_ring_flag_is_one_line_and_exit_2(tmp_path, capsys):
    code = main(["diagnose", "--scene", "raba118_crack", "--measured", str(_csv(tmp_path)),
                 "--ring", "flexible"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "--ring" in err[0] and "rigid, elastic" in err[0]


def test_scene_ring_chooses_the_models():
    from types import SimpleNamespace

    from hubvib.commands.diagnose import rings_of
    from hubvib.elastic.options import ElasticScene

    both = SimpleNamespace(elastic=ElasticScene(ring="both"))
    rigid = SimpleNamespace(elastic=ElasticScene())
    assert rings_of(both, None) == ("rigid", "elastic")
    assert rings_of(rigid, None) == ("rigid",)
    assert rings_of(both, "elastic") == ("elastic",)
    with pytest.raises(ValueError, match="--ring"):
        rings_of(rigid, "both")


@pytest.mark.slow
def test_diagnose_on_the_elastic_ring_of_the_default_scene(tmp_path, capsys):
    """The default scene runs both rings: a measured 18 Hz drop of the elastic ring's
    intact n = 4 mode against its own baseline is a crack on the elastic ring (its record
    under the working load); the JSON
    gives both verdicts, the rigid ring's at the top level."""
    import json

    from hubvib.detection.diagnosis import scene_reference
    from hubvib.studies.scene import load_scene

    ref, _ = scene_reference(load_scene("raba118_crack"), False, ring="elastic")
    i = int(np.argmin(np.abs(ref.nominal_hz[0] - 4715.6)))
    f0 = ref.nominal_hz[0, i]
    path = _csv(tmp_path, f"mode,frequency_hz,baseline_hz\n{i + 1},{f0 - 18:.3f},{f0:.3f}\n")
    assert main(["diagnose", "--scene", "raba118_crack", "--measured", str(path),
                 "--ring", "elastic", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ring"] == "elastic" and out["verdict"] == "crack indicated", out
    # under the working load this mode's record change is not monotone in depth (it
    # splits where the crack grows deep): one mode's 18 Hz drop lies beyond the 3 mm
    # change and within the sweep's cracks that still have a tip
    assert 0.003 < out["depth_m"] < 0.015
    assert main(["diagnose", "--scene", "raba118_crack", "--measured", str(path),
                 "--json"]) == 0
    both = json.loads(capsys.readouterr().out)
    assert both["elastic"]["verdict"] == "crack indicated"
    assert "error" in both or both["ring"] == "rigid"


@pytest.mark.slow
def test_elastic_calibration_on_the_default_scene():
    """``raba118_crack``'s elastic ring (its cached cases), its four watched modes,
    Student-t identification errors (8 degrees of freedom, unit variance; the diagnosis
    assumes normal ones): 90 % intervals over depths uniform on the sweep hold the true
    depth within 3 binomial standard errors of 0.9, and intact reducers are called cracked
    near the scene's 1 % false-alarm rate (within 3 binomial standard errors)."""
    from hubvib.detection.carrier import mesh_timing
    from hubvib.detection.diagnosis import elastic_scene_model
    from hubvib.detection.options import detection_options
    from hubvib.studies.scene import load_scene

    scene = load_scene("raba118_crack")
    options = detection_options(scene)
    model = elastic_scene_model(scene)
    timing = mesh_timing(scene.crack.reducer, options.carrier_speed)
    ref = reference(model, options, timing)
    labels = ref.labels
    watched = [i + 1 for i, s in enumerate(labels) if "n=4 " in s or "n=3 " in s][:2]
    trials = 300
    result = calibrate(model, options, timing, ref, watched, trials)
    tolerance = 3 * math.sqrt(0.9 * 0.1 / trials)
    assert abs(result.coverage - 0.9) <= tolerance, (
        f"Student-t (dof 8) noise, modes {watched}: coverage {result.coverage:.3f} against "
        f"0.9 +- {tolerance:.3f}")
    rate = options.false_alarm_rate
    assert result.intact.get("crack indicated", 0.0) <= rate + 3 * math.sqrt(
        rate * (1 - rate) / trials), f"Student-t (dof 8) noise: intact {result.intact}"


def test_sorted_order_keeps_the_nominal_identities_of_separated_modes(small):
    """Naming a scattered reducer's modes by sorted order: for modes far from their
    neighbours (relative gap > 10 %, more than the 2-10 % scatter moves them), the mode
    in the nominal's sorted place is the nominal's mode there by subspace match in every
    sample, intact and at the deepest crack."""
    from hubvib.detection.elastic_model import draw_elastic, sorted_order_kept

    cases, model = small
    samples = draw_elastic(model, DetectionOptions(), 60, np.random.default_rng(1))
    f = model.nominal_grid_hz
    for k in (0, len(cases) - 1):
        fk = np.sort(f[k])
        gaps = np.array([min(abs(x - y) for y in fk if y != x) / x for x in f[k]])
        separated = [i for i in range(f.shape[1]) if gaps[i] > 0.1 and f[k, i] > 100]
        assert separated
        kept = sorted_order_kept(model, cases, samples, k, separated)
        assert np.all(kept == 1.0), (k, separated, kept)


# ------------------------------------------------- the diagnosis stays on computed depths

def _pattern(ref, modes, shift_hz):
    from hubvib.detection.measured import Measured

    f0 = ref.nominal_hz[0, modes]
    return Measured(f0 + shift_hz, np.asarray(modes) + 1, f0, tuple(range(2, 2 + len(modes))),
                    "synthetic")


def test_one_mode_moving_alone_is_not_a_ring_crack_and_a_small_pattern_is_below(small):
    """On the small elastic ring, against the reducer's own intact record: the four modes
    the crack moves most (against their scatter) move together; the one of them the
    shallowest crack moves least alone by -10 Hz (about 8 identification standard
    deviations, 10 s records), the others unchanged, is a pattern no computed depth makes
    (the crack that moves it so moves the others by 14-44 Hz): "not explained by a ring
    crack".
    Half the pattern of the shallowest computed crack (4 mm) is a crack, but no depth
    under 4 mm was computed, so the answer is "below 4 mm" with no depth of its own."""
    from hubvib.detection.diagnosis import CRACK, NOT_EXPLAINED, diagnose

    _, model = small
    options = DetectionOptions(samples=400)
    ref = reference(model, options, TIMING)
    first = ref.nominal_hz[1] - ref.nominal_hz[0]
    modes = np.sort(np.argsort(-np.abs(first) / ref.sigma_hz, kind="stable")[:4])
    alone = np.zeros(modes.size)
    alone[int(np.argmin(np.abs(first[modes])))] = -10.0
    lonely = diagnose(_pattern(ref, modes, alone), ref, options)
    assert lonely.verdict == NOT_EXPLAINED, (lonely.verdict, lonely.fit_p_value)
    assert lonely.depth is None and lonely.depth_high is None
    half = diagnose(_pattern(ref, modes, 0.5 * first[modes]), ref, options)
    assert half.verdict == CRACK, (half.verdict, half.fit_p_value)
    assert half.below == ref.depths[1] and half.depth is None, half
    assert half.depth_low == 0.0 and half.depth_high >= ref.depths[1]
    assert half.words.startswith("below 4 mm"), half.words
    full = diagnose(_pattern(ref, modes, first[modes]), ref, options)
    assert full.verdict == CRACK and full.below is None, full.words
    assert full.depth_low <= ref.depths[1] <= full.depth_high, full.words


@pytest.mark.slow
def test_default_scene_elastic_one_mode_alone_and_a_small_pattern():
    """The default scene on the elastic ring (10 s records, own intact record): the
    4715.6 Hz mode (n = 4) alone by -10 Hz with the other watched modes unchanged is not a
    ring crack (the 3 mm crack moves them together by 17.9-45.2 Hz); 0.4 times the 3 mm
    pattern lies between the depths the study adds below 3 mm (0.5-1.5 mm): a depth, not
    "below 3 mm"."""
    from hubvib.detection.diagnosis import CRACK, NOT_EXPLAINED, diagnose, scene_reference
    from hubvib.studies.scene import load_scene

    ref, options = scene_reference(load_scene(None), progress=False, ring="elastic")
    at_3mm = int(np.flatnonzero(np.isclose(ref.depths, 0.003))[0])
    first = ref.nominal_hz[at_3mm] - ref.nominal_hz[0]
    moved = next(i for i, label in enumerate(ref.labels) if "4715.6 Hz" in label)
    assert "n=4 " in ref.labels[moved], ref.labels[moved]
    # the four modes the 3 mm crack moves most against their scatter, and the n = 4 mode
    top = np.argsort(-np.abs(first) / ref.sigma_hz, kind="stable")[:4]
    modes = np.unique(np.append(top, moved))
    alone = np.where(modes == moved, -10.0, 0.0)
    lonely = diagnose(_pattern(ref, modes, alone), ref, options)
    assert lonely.verdict == NOT_EXPLAINED, (lonely.verdict, lonely.fit_p_value)
    small_crack = diagnose(_pattern(ref, modes, 0.4 * first[modes]), ref, options)
    assert small_crack.verdict == CRACK and small_crack.below is None, small_crack.words
    assert 0.0005 <= small_crack.depth < 0.003, small_crack.words


def test_the_loaded_record_swaps_in_through_one_seam(small, monkeypatch):
    """The seam for the loaded crack: with a record track (``hubvib.elastic.loaded``, faked
    here: the record sees 0.6 of each reference change and an intact offset of +0.5 Hz)
    and cases that carry their loaded crack, the nominal spectrum is the record's, the
    Monte Carlo reducers at zero scatter give it exactly, and each sampled change is the
    reference one times the nominal ratio 0.6 (the documented shortcut)."""
    from hubvib.detection import elastic_model

    cases, reference_model = small
    loaded = _with_record(monkeypatch, cases,
                          lambda f0, seen, intact: f0 + 0.5 + 0.6 * (seen - f0))
    model = elastic_model.elastic_spectrum_model(reference_model.grid, loaded)
    base = reference_model.nominal_grid_hz
    expected = base[0] + 0.5 + 0.6 * (base - base[0])
    tracked = np.array([op.tracked for op in model.operators])
    assert np.allclose(model.nominal_grid_hz[tracked], expected[tracked], rtol=0, atol=1e-9)
    zero = unscattered(model, 1)
    assert np.allclose(model.frequencies_of(zero)[0][tracked], expected[tracked], atol=1e-9)
    drawn = ElasticSamples({k: np.full(1, 1.02) for k in model.mass_fields},
                           np.full(1, 0.99), {k: np.full(1, 1.05)
                                              for k in model.stiffness_names}, np.zeros(1))
    change = model.frequencies_of(drawn)[0] - model.frequencies_of(drawn)[0][0]
    plain = reference_model.frequencies_of(drawn)[0]
    moved = (np.abs(base - base[0]) > 1e-6) & tracked  # untracked: the record is the reference
    assert np.allclose(change[moved], 0.6 * (plain - plain[0])[moved], rtol=1e-9), \
        "each sampled change scaled by the nominal ratio"


# ------------------------------------------- the diagnosis on the depths the study adds

def _refining_scene(monkeypatch):
    """``raba118_crack`` with its elastic cases replaced by the small synthetic ring (its
    crack scaled to the scene's deepest elastic depth) and 100 Monte Carlo reducers; the
    cases it is asked for, and the options."""
    from hubvib.detection import diagnosis, elastic_model
    from hubvib.detection import options as detection_options
    from hubvib.studies import elastic_stage
    from hubvib.studies.scene import load_scene

    scene = load_scene("raba118_crack")
    deepest = max(elastic_stage.elastic_depths(scene.crack))
    asked = []

    def case_at(design, crack, table, k_rest):
        asked.append(crack.depth)
        return _synthetic_cases((0.0, crack.depth, deepest))[1 if crack.depth else 0]

    options = replace(detection_options.detection_options(scene), samples=100)
    monkeypatch.setattr(elastic_model, "cached_case", case_at)
    monkeypatch.setattr(detection_options, "detection_options", lambda s: options)
    monkeypatch.setattr(diagnosis, "detection_options", lambda s: options)
    return scene, case_at, asked, options


@pytest.mark.slow
def test_the_elastic_diagnosis_uses_the_depths_the_run_adds(monkeypatch):
    """``diagnosis.elastic_scene_model`` solves the elastic ring at the depths ``hubvib
    run`` does (``studies.elastic_stage.finish_elastic``: the sweep's, less the crack
    through the rim, plus those its refinement adds): same grid, and added depths between
    0.5 mm (``resolution.FLOOR``) and the shallowest depth of the scene."""
    from hubvib.detection.diagnosis import elastic_scene_model
    from hubvib.detection.resolution import FLOOR
    from hubvib.studies import elastic_stage

    scene, _, asked, _ = _refining_scene(monkeypatch)
    run, _, _ = elastic_stage.finish_elastic(scene, elastic_stage.begin_elastic(scene, None))
    model = elastic_scene_model(scene)
    assert run.added_depths, "the synthetic ring's POD crosses below the scene's 3 mm"
    assert model.depths == run.depths, (model.depths, run.depths)
    shallowest = min(d for d in scene.crack.depths if d > 0)
    assert all(FLOOR <= d < shallowest for d in run.added_depths), run.added_depths
    assert set(run.added_depths) <= set(asked)


@pytest.mark.slow
def test_a_shallow_pattern_is_diagnosed_between_the_added_depths(monkeypatch):
    """The mean pattern of a 1 mm crack of the synthetic ring (its four most shifted
    modes, against the reducer's own intact frequencies): on the scene's depths alone the
    diagnosis can only say "below 3 mm"; with the depths the study adds it gives a depth
    whose 90 % interval holds 1 mm and lies below 3 mm (the independent check: the pattern
    is computed from a case at 1 mm itself, not interpolated from the sweep)."""
    from types import SimpleNamespace

    from hubvib.detection.carrier import mesh_timing
    from hubvib.detection.diagnosis import diagnose, elastic_scene_model

    scene, case_at, _, options = _refining_scene(monkeypatch)
    timing = mesh_timing(scene.crack.reducer, options.carrier_speed)
    truth = 0.001
    at = [case_at(None, SimpleNamespace(depth=d), None, None) for d in (0.0, truth)]
    f = elastic_spectrum_model((0.0, truth), at).nominal_hz(options, timing)
    model = elastic_scene_model(scene)
    ref = reference(model, options, timing)
    measured = _resolved_pattern(f, ref, options, truth)
    kept = [d for d in model.depths if d == 0 or d >= 0.003]
    coarse_model = elastic_spectrum_model(
        kept, [case_at(None, SimpleNamespace(depth=d), None, None) for d in kept])
    coarse = diagnose(measured, reference(coarse_model, options, timing), options)
    assert coarse.below == pytest.approx(0.003), coarse.words


@pytest.mark.slow
def test_the_default_scenes_elastic_diagnosis_resolves_a_2_mm_pattern():
    """``raba118_crack`` on the FE elastic ring (its cases through the result cache): the
    diagnosis's depth grid is the run's (the scene's depths less the crack through the
    rim, plus the depths its refinement adds below 3 mm), and the mean pattern of a 2 mm
    crack under the working load (the four modes it moves most against their scatter,
    computed on a 2 mm case of its own, against the reducer's intact frequencies) is
    diagnosed with a 90 % interval holding 2 mm below 3 mm, where the scene's depths alone
    say only "below 3 mm"."""
    from hubvib.cases.sweep import crack_of
    from hubvib.detection import elastic_model
    from hubvib.detection.carrier import mesh_timing
    from hubvib.detection.diagnosis import diagnose, elastic_scene_model
    from hubvib.detection.options import detection_options
    from hubvib.studies import elastic_stage
    from hubvib.studies.scene import load_scene

    scene = load_scene("raba118_crack")
    sweep = scene.crack
    run, _, _ = elastic_stage.finish_elastic(scene, elastic_stage.begin_elastic(scene, None))
    model = elastic_scene_model(scene)
    assert model.depths == run.depths and run.added_depths, (model.depths, run.depths)
    options = detection_options(scene)
    timing = mesh_timing(sweep.reducer, options.carrier_speed)

    def cases(depths):
        return [elastic_model.cached_case(*a) for a in elastic_model.case_arguments(
            sweep.reducer, depths, lambda d: crack_of(sweep, d), scene.elastic)]

    truth = 0.002  # between two depths the refinement adds, detectable with 10 s records
    f = elastic_spectrum_model((0.0, truth), cases((0.0, truth))).nominal_hz(options, timing)
    measured = _resolved_pattern(f, reference(model, options, timing), options, truth)
    kept = tuple(d for d in model.depths if d == 0 or d >= 0.003)
    coarse = diagnose(measured, reference(elastic_spectrum_model(kept, cases(kept)), options,
                                          timing), options)
    assert coarse.below == pytest.approx(0.003), coarse.words


def test_a_record_change_the_reference_hardly_sees_is_added_not_scaled(small, monkeypatch):
    """Where the open crack half a pitch away moves a mode by less than ``RATIO_FLOOR`` of
    what the record sees (here: the reference change times 0.1, plus -5 Hz), a sampled
    reducer's record change is its own reference change plus the nominal difference, so
    the ratio (which would be about 50) does not magnify the sample's scatter."""
    from hubvib.detection import elastic_model

    cases, reference_model = small
    loaded = _with_record(monkeypatch, cases, lambda f0, seen, intact:
                          f0 + 0.1 * (seen - f0) + (0.0 if intact else -5.0))
    model = elastic_model.elastic_spectrum_model(reference_model.grid, loaded)
    base = reference_model.nominal_grid_hz
    tracked = np.array([op.tracked for op in model.operators])
    small_change = np.abs(base - base[0]) < 1.0  # record change -5 Hz dominates
    assert np.all(np.isnan(model.record_ratio[1:][small_change[1:] & tracked[1:]]))
    drawn = ElasticSamples({k: np.full(1, 1.02) for k in model.mass_fields},
                           np.full(1, 0.99), {k: np.full(1, 1.05)
                                              for k in model.stiffness_names}, np.zeros(1))
    change = model.frequencies_of(drawn)[0] - model.frequencies_of(drawn)[0][0]
    plain = reference_model.frequencies_of(drawn)[0]
    added = (model.nominal_grid_hz - model.nominal_grid_hz[0]) - (base - base[0])
    check = small_change & tracked
    check[0] = False
    assert np.allclose(change[check], ((plain - plain[0]) + added)[check], atol=1e-9), \
        "reference change plus the nominal difference where the ratio is not used"


def _with_record(monkeypatch, cases, record_of):
    """``cases`` as cases carrying a loaded crack, with ``hubvib.elastic.loaded.record_track``
    faked: the record frequency ``record_of(f0, seen, intact)`` from the intact reference
    ``f0``, the case's tracked reference spectrum ``seen`` and whether it is the intact
    case."""
    import sys
    import types
    from types import SimpleNamespace

    from hubvib.detection import elastic_model

    fake = types.ModuleType("hubvib.elastic.loaded")

    def record_track(intact, case, torque_fraction=1.0, closure_gap_m=0.0, damping_ratio=0.02,
                     carrier_speed=1.0):
        seen = elastic_model.tracked_to(intact.away, case.away, intact.ring_mass)[0]
        f0 = intact.away.frequency_hz
        return SimpleNamespace(record_hz=record_of(f0, seen, case is intact),
                               intact_record_hz=record_of(f0, f0, True))

    fake.record_track = record_track
    monkeypatch.setitem(sys.modules, "hubvib.elastic.loaded", fake)
    return [SimpleNamespace(**{**{k: getattr(c, k) for k in c.__dataclass_fields__},
                               "pitch": True}) for c in cases]


def _resolved_pattern(f, ref, options, truth):
    """The mean pattern of a ``truth`` [m] crack (``f``: intact and cracked frequencies, the
    four modes it moves most against their scatter) diagnosed on ``ref``: a crack with a 90 %
    interval holding ``truth`` below 3 mm; returns the measured pattern."""
    from hubvib.detection.diagnosis import CRACK, diagnose
    from hubvib.detection.measured import Measured

    modes = np.argsort(-np.abs(f[1] - f[0]) / ref.sigma_hz)[:4]
    measured = Measured(f[1][modes], modes + 1, f[0][modes], (2, 3, 4, 5),
                        f"{1e3 * truth:g} mm pattern")
    refined = diagnose(measured, ref, options)
    assert refined.verdict == CRACK and refined.below is None, refined.words
    assert refined.depth_low <= truth <= refined.depth_high < 0.003, refined.words
    return measured
