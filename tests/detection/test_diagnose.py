"""hubvib diagnose: crack depth from measured frequencies, its coverage, and bad CSVs."""
import json
import math
import re

import numpy as np
import pytest
from tests.helpers.synthetic_rows import TIMING, synthetic_fe_cases, synthetic_model

from hubvib.cli import main
from hubvib.detection.diagnosis import (CRACK, NO_CRACK, NOT_EXPLAINED, NOT_IDENTIFIABLE,
                                        Posterior, diagnose, reference,
                                        synthetic_measurements)
from hubvib.detection.measured import MeasuredError, parse_measured
from hubvib.detection.options import DetectionOptions
from hubvib.identification.law import fisher_sigma_hz
from hubvib.identification.montecarlo import identified

OPTIONS = DetectionOptions(samples=1000)


@pytest.fixture(scope="module")
def direct():
    model = synthetic_model("direct")
    return model, reference(model, OPTIONS, TIMING)


def student_errors(rng, shape, dof=8):
    """Heavier-tailed identification errors than the diagnosis assumes (Student t with 8
    degrees of freedom, unit variance): a noise model it was not tuned on."""
    return rng.standard_t(dof, size=shape) / math.sqrt(dof / (dof - 2))


@pytest.fixture(scope="module")
def identified_errors():
    """Identification errors from records the diagnosis never saw: 150 simulated records
    (200 Hz, 2 %, 100 s, SNR 100) identified by the shipped Bayesian-FFT method,
    standardised by the bound the diagnosis uses, resampled."""
    f, zeta, T, snr = 200.0, 0.02, 100.0, 100.0
    pool = (identified(f, zeta, T, snr, records=150, seed=4) - f) / fisher_sigma_hz(
        f, zeta, T, snr)
    return lambda rng, shape: rng.choice(pool, size=shape)


def _verdicts(posterior, frequency, own, modes, truth=None):
    covered, verdicts = 0, []
    for j in range(frequency.shape[0]):
        result = posterior.diagnose(frequency[j, modes] - own[j, modes], "measured")
        verdicts.append(result.verdict)
        if truth is not None and result.depth_low is not None:
            covered += result.depth_low <= truth[j] <= result.depth_high
    return covered, verdicts


def _coverage(direct, errors, modes):
    model, ref = direct
    trials = 200
    truth = np.random.default_rng(11).uniform(0, model.depths[-1], trials)
    frequency, own = synthetic_measurements(model, OPTIONS, TIMING, truth, seed=12,
                                            errors=errors)
    covered, verdicts = _verdicts(Posterior(ref, np.array(modes), True), frequency, own,
                                  modes, truth)
    assert 0.80 <= covered / trials <= 0.97, \
        f"90 % interval covered the true depth in {covered}/{trials} trials (80-97 %)"
    assert verdicts.count(NOT_EXPLAINED) <= 8, "crack patterns are explained by a crack"


@pytest.mark.parametrize("modes", [[11], pytest.param([15, 16, 17], marks=pytest.mark.slow)])
def test_90_percent_interval_covers_the_true_depth_at_its_rate(direct, modes):
    _coverage(direct, student_errors, modes)


@pytest.mark.slow
@pytest.mark.parametrize("modes", [[11], [15, 16, 17]])
def test_coverage_with_errors_of_identified_records(direct, identified_errors, modes):
    _coverage(direct, identified_errors, modes)


def _intact(direct, errors):
    model, ref = direct
    trials = 300
    frequency, own = synthetic_measurements(model, OPTIONS, TIMING, np.zeros(trials), seed=21,
                                            errors=errors)
    modes = [11, 15, 16, 17]
    _, verdicts = _verdicts(Posterior(ref, np.array(modes), True), frequency, own, modes)
    crack = verdicts.count(CRACK) / trials
    assert verdicts.count(NO_CRACK) / trials >= 0.9, ">= 90 % 'no crack indicated'"
    assert crack <= OPTIONS.false_alarm_rate + 3 * math.sqrt(0.01 * 0.99 / trials), \
        f"crack verdicts on intact reducers {crack:.3f} vs false-alarm rate 0.01 (+3 sigma)"


@pytest.mark.slow
def test_intact_reducer_is_called_intact(direct):
    _intact(direct, student_errors)


@pytest.mark.slow
def test_intact_reducer_with_errors_of_identified_records(direct, identified_errors):
    _intact(direct, identified_errors)


def test_intervals_widen_with_identification_noise(direct):
    model, ref = direct
    modes = np.array([15, 16, 17])
    y = ref.nominal_hz[5, modes] - ref.nominal_hz[0, modes]
    widths = []
    for scale in (1.0, 3.0, 9.0):
        result = Posterior(ref, modes, True, ref.sigma_hz[modes] * scale).diagnose(y, "m")
        widths.append(result.depth_high - result.depth_low)
    assert widths[0] < widths[1] < widths[2], f"interval widths {widths} m"


def test_patterns_no_ring_crack_produces_are_not_explained(direct):
    model, ref = direct
    modes = np.array([11, 15, 16, 17])
    f0 = ref.nominal_hz[0, modes]
    posterior = Posterior(ref, modes, True)
    deepest = ref.nominal_hz[-1, modes] - f0
    patterns = {"every mode +1 %": 0.01 * f0, "every mode -1 %": -0.01 * f0,
                "one mode 10 sigma above its baseline": np.array([0, 0, 0, 10]) * (
                    np.sqrt(2) * ref.sigma_hz[modes]),
                "nine times the largest shift": 9 * deepest,
                "one mode moving alone": np.where(np.arange(4) == 3, 3 * deepest, 0.0)}
    for name, y in patterns.items():
        result = posterior.diagnose(y, "measured", f0)
        assert result.verdict == NOT_EXPLAINED, f"{name}: {result.verdict}"
        assert result.fit_p_value < ref.fit_false_alarm_rate and result.depth is None
    uniform = posterior.diagnose(0.01 * f0, "measured", f0)
    assert uniform.uniform_shift == pytest.approx(0.01, rel=1e-9), "GLS on an exact pattern"
    assert uniform.uniform_p_value > 0.5 and "uniform relative shift of +1 %" in \
        uniform.explanation()
    rise = posterior.diagnose(patterns["one mode 10 sigma above its baseline"], "m", f0)
    assert rise.worst_mode == 18 and rise.worst_z > 3


def test_verdicts(direct):
    model, ref = direct
    true = 0.8 * model.depths[-1]
    frequency, own = synthetic_measurements(model, OPTIONS, TIMING, np.array([0.0, true]),
                                            seed=3)
    modes = np.array([11, 15])
    posterior = Posterior(ref, modes, measured_baseline=True)
    intact = posterior.diagnose(frequency[0, modes] - own[0, modes], "measured")
    deep = posterior.diagnose(frequency[1, modes] - own[1, modes], "measured")
    assert intact.verdict == NO_CRACK and intact.depth == 0.0 and intact.depth_high > 0
    assert deep.verdict == CRACK and deep.depth_low <= true <= deep.depth_high
    # mode 1 follows c_ru: behind the identified 1e6 N/m mounting it cannot tell anything
    soft = synthetic_model("series")
    soft_ref = reference(soft, DetectionOptions(samples=200), TIMING)
    blind = Posterior(soft_ref, np.array([0]), True).diagnose(np.array([-0.1]), "measured")
    assert blind.verdict == NOT_IDENTIFIABLE and blind.depth is None
    assert json.loads(json.dumps(blind.to_dict(), allow_nan=False))["depth_low_m"] is None


def test_pairing_by_nearest_value_and_model_baseline(direct):
    model, ref = direct
    f0 = ref.nominal_hz[0]
    measured = parse_measured("frequency_hz\n" + "\n".join(f"{f:.4f}" for f in f0[[15, 11]]))
    result = diagnose(measured, ref)
    assert result.modes == (16, 12) and result.baseline == "model"


SCENE = """
[reducer]
preset = "raba118"
[crack]
depths = [0.0, 0.003075, 0.00615, 0.009225, 0.0123, 0.015375, 0.01845, 0.021525, 0.0246]
apply = "direct"
accuracy = "fast"
[detection]
samples = 300
[output]
plots = false
"""


@pytest.fixture
def cli(tmp_path, monkeypatch):
    """A scene whose FE rows are synthetic (no FE stage) and a CSV writer."""
    import hubvib.detection.diagnosis

    def fe_cases(sweep, progress=True):
        return synthetic_fe_cases(sweep.depths), 0

    monkeypatch.setattr(hubvib.detection.diagnosis, "crack_cases", fe_cases)
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE)

    def run(csv_text, *flags):
        path = tmp_path / "measured.csv"
        path.write_text(csv_text)
        before = sorted(tmp_path.rglob("*"))
        code = main(["diagnose", "--scene", str(scene), "--measured", str(path), *flags])
        assert sorted(tmp_path.rglob("*")) == before, "diagnose writes nothing"
        return code
    return run


def test_cli_json_holds_depth_interval_and_verdict(cli, capsys, direct):
    model, ref = direct
    frequency, own = synthetic_measurements(model, OPTIONS, TIMING, np.array([0.02]), seed=5)
    rows = "\n".join(f"{m + 1},{frequency[0, m]:.4f},{own[0, m]:.4f}" for m in (11, 15))
    assert cli("mode,frequency_hz,baseline_hz\n" + rows + "\n", "--json") == 0
    data = json.loads(capsys.readouterr().out)
    assert data["verdict"] == CRACK and data["baseline"] == "measured"
    assert 0 < data["fit_p_value"] <= 1 and len(data["sigma_hz"]) == 2
    assert data["depth_low_m"] <= data["depth_m"] <= data["depth_high_m"]
    assert abs(data["depth_m"] - 0.02) < 0.005
    assert cli("mode,frequency_hz,baseline_hz\n" + rows + "\n") == 0
    assert "verdict: crack indicated: depth" in capsys.readouterr().out


class _ClosedPipe:
    """A standard output whose reader is gone: every write raises ``BrokenPipeError``."""

    def write(self, text):
        raise BrokenPipeError(32, "Broken pipe")

    def flush(self):
        pass

    def fileno(self):
        raise OSError("not a real file")


@pytest.mark.parametrize("stdout", [_ClosedPipe(), None], ids=["closed pipe", "no stdout"])
@pytest.mark.parametrize("flags", [(), ("--json",)], ids=["table", "json"])
def test_cli_with_stdout_closed_exits_141_quietly(cli, capsys, monkeypatch, direct, stdout,
                                                  flags):
    """A diagnosis whose standard output is closed (``| head -0``, or ``>&-``: Python's
    ``sys.stdout`` is None) ends as every command's does: exit 141, nothing on stderr."""
    model, ref = direct
    frequency, own = synthetic_measurements(model, OPTIONS, TIMING, np.array([0.02]), seed=5)
    rows = "\n".join(f"{m + 1},{frequency[0, m]:.4f},{own[0, m]:.4f}" for m in (11, 15))
    with monkeypatch.context() as patch:
        patch.setattr("sys.stdout", stdout)
        code = cli("mode,frequency_hz,baseline_hz\n" + rows + "\n", *flags)
    assert (code, capsys.readouterr().err) == (141, "")


@pytest.mark.parametrize("text, message", [
    ("freq\n100\n", r"measured.csv line 1: header \['freq'\]; it needs the column frequency_hz"),
    ("mode\n1\n", "it needs the column frequency_hz"),
    ("frequency_hz\n", "no frequencies below the header"),
    ("", "empty"),
    ("frequency_hz\nabc\n", "line 2: frequency_hz = 'abc', but it must be a frequency in Hz"),
    ("frequency_hz\n-53.5\n", r"line 2: frequency_hz = '-53.5', but it must be a frequency"),
    ("frequency_hz\n0\n", r"line 2: frequency_hz = '0'"),
    ("frequency_hz\n53.5\n53.5\n", "line 3: frequency_hz = 53.5 repeats line 2"),
    ("frequency_hz,mode\n53.5,1\n85.4,1\n", "line 3: mode = 1 repeats line 2"),
    ("frequency_hz,mode\n53.5,x\n", "line 2: mode = 'x', but it must be a mode number"),
    ("frequency_hz,baseline_hz\n53.5\n", "line 2: 1 value"),
    ("frequency_hz,mode\n53.5,40\n", "line 2: mode = 40, but the rigid ring's model has 18 modes"),
    ("frequency_hz\n" + "\n".join(str(50 + 10 * i) for i in range(19)) + "\n",
     "19 frequencies, but the rigid ring's model has only 18 modes"),
    ("frequency_hz\n70.8\n25000\n", "line 3: frequency_hz = 25000 Hz is far from every model"),
    ("frequency_hz,damping_ratio\n70.8,0.7\n", r"line 2: damping_ratio = '0.7', but it must be "
                                              r"a damping ratio in \(0, 0.5\)"),
    ("frequency_hz,record_s\n70.8,-1\n", r"line 2: record_s = '-1', but it must be a record"),
    ("frequency_hz,sigma_hz\n70.8,x\n", r"line 2: sigma_hz = 'x', but it must be a standard"),
    ("frequency_hz,sigma_hz,record_s\n70.8,1,10\n", "give either sigma_hz or damping_ratio"),
    ("frequency_hz,mode\n303.7,1\n", r"line 2: frequency_hz = 303.7 Hz lies outside the range "
                                     r"of its rigid mode 1"),
])
def test_bad_measured_csv_exits_2_naming_the_line(cli, capsys, text, message):
    assert cli(text) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.startswith("hubvib: error: ") and captured.err.count("\n") == 1
    assert re.search(message, captured.err), captured.err


def test_missing_file_and_scene_without_crack(tmp_path, capsys):
    assert main(["diagnose", "--scene", "raba118_c_ru", "--measured",
                 str(tmp_path / "none.csv")]) == 2
    assert "cannot read --measured" in capsys.readouterr().err
    path = tmp_path / "m.csv"
    path.write_text("frequency_hz\n53.5\n")
    assert main(["diagnose", "--scene", "raba118_c_ru", "--measured", str(path)]) == 2
    assert "has no [crack] study" in capsys.readouterr().err
    assert main(["diagnose", "--scene", "raba118_crack_3d", "--measured", str(path)]) == 2
    assert "needs a plane crack sweep" in capsys.readouterr().err


def test_parse_keeps_file_lines():
    measured = parse_measured("\nfrequency_hz,baseline_hz\n\n53.5,53.6\n85.0,85.4\n")
    assert measured.lines == (4, 5)
    np.testing.assert_array_equal(measured.baseline_hz, [53.6, 85.4])
    with pytest.raises(MeasuredError):
        parse_measured("frequency_hz,frequency_hz\n1,2\n")



def test_csv_damping_and_record_length_set_the_identification_scatter(direct):
    model, ref = direct
    f = ref.nominal_hz[0, [15, 16]]
    rows = "\n".join(f"{m},{v:.3f},{v:.3f},0.05,60" for m, v in zip((16, 17), f))
    measured = parse_measured("mode,frequency_hz,baseline_hz,damping_ratio,record_s\n" + rows)
    result = diagnose(measured, ref, OPTIONS)
    expected = [fisher_sigma_hz(v, 0.05, 60.0, OPTIONS.snr) for v in f]
    np.testing.assert_allclose(result.sigma_hz, expected, rtol=1e-6,
                               err_msg="per-row damping and record length")
    given = parse_measured("mode,frequency_hz,sigma_hz\n16,%.3f,0.7\n" % f[0])
    assert diagnose(given, ref).sigma_hz[0] == 0.7
    default = parse_measured("mode,frequency_hz\n16,%.3f\n" % f[0])
    assert diagnose(default, ref).sigma_hz[0] == pytest.approx(
        fisher_sigma_hz(ref.nominal_hz[0, 15], 0.02, 10.0, 100.0), rel=1e-6), \
        "scene defaults: 2 % damping, 10 s, SNR 100"


@pytest.mark.slow
def test_calibration_table_of_the_docs(direct):
    from hubvib.detection.calibration import calibrate

    model, ref = direct
    result = calibrate(model, OPTIONS, TIMING, ref, [12, 16, 17, 18], trials=60)
    assert result.intact.get(NO_CRACK, 0.0) >= 0.8
    assert result.patterns["every mode +1 %"][0] == NOT_EXPLAINED
    table = result.table()
    assert len(table) == 2 + 5 + len(result.patterns) and "90 % intervals" in table[5]
