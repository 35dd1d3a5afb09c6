"""hubvib diagnose: crack depth from measured frequencies, its coverage, and bad CSVs."""
import json
import re
import numpy as np
import pytest
from test_detection_helpers import TIMING, synthetic_fe_rows, synthetic_model

from hubvib.cli import main
from hubvib.detection.diagnosis import (CRACK, NO_CRACK, NOT_IDENTIFIABLE, Posterior,
                                        diagnose, reference, synthetic_measurements)
from hubvib.detection.measured import MeasuredError, parse_measured
from hubvib.detection.options import DetectionOptions

OPTIONS = DetectionOptions(samples=1000)


@pytest.fixture(scope="module")
def direct():
    model = synthetic_model("direct")
    return model, reference(model, OPTIONS, TIMING)


@pytest.mark.parametrize("modes, baseline", [([11], True), ([15, 16, 17], True)])
def test_90_percent_interval_covers_the_true_depth_at_its_rate(direct, modes, baseline):
    model, ref = direct
    trials = 200
    truth = np.random.default_rng(11).uniform(0, model.depths[-1], trials)
    frequency, own = synthetic_measurements(model, OPTIONS, TIMING, truth, seed=12)
    posterior = Posterior(ref, np.array(modes), measured_baseline=baseline)
    covered = 0
    for j in range(trials):
        y = frequency[j, modes] - (own[j, modes] if baseline else ref.nominal_hz[0, modes])
        result = posterior.diagnose(y, "measured")
        covered += result.depth_low <= truth[j] <= result.depth_high
    assert 0.85 <= covered / trials <= 0.95, \
        f"90 % interval covered the true depth in {covered}/{trials} trials (85-95 % asked)"


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
    blind = Posterior(soft_ref, np.array([0]), True).diagnose(np.array([-0.5]), "measured")
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
    import hubvib.studies.crack_sweep

    monkeypatch.setattr(hubvib.studies.crack_sweep, "run_fe_cases",
                        lambda sweep, progress=True: (synthetic_fe_rows(sweep.depths), 0))
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
    assert data["depth_low_m"] <= data["depth_m"] <= data["depth_high_m"]
    assert abs(data["depth_m"] - 0.02) < 0.005
    assert cli("mode,frequency_hz,baseline_hz\n" + rows + "\n") == 0
    assert "verdict: crack indicated: depth" in capsys.readouterr().out


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
    ("frequency_hz,mode\n53.5,40\n", "line 2: mode = 40, but the model has 18 modes"),
    ("frequency_hz\n" + "\n".join(str(50 + 10 * i) for i in range(19)) + "\n",
     "19 frequencies, but the model has only 18 modes"),
    ("frequency_hz\n70.8\n25000\n", "line 3: frequency_hz = 25000 Hz is far from every model"),
    ("frequency_hz,mode\n303.7,1\n", r"line 2: frequency_hz = 303.7 Hz lies outside the range "
                                     r"of its mode 1"),
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

