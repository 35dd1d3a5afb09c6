"""``[signal]`` scene table, ``hubvib signal`` end to end, and every bad input."""
import csv
import json
import math

import numpy as np
import pytest

from hubvib.cli import main
from hubvib.studies.scene import SceneError
import hubvib.signal.signature_study as signal_study
from hubvib.signal.mesh_curves import synthetic_curves
from hubvib.signal.options import SignalOptions, parse_signal_table
from hubvib.design import preset_design

RABA = preset_design("raba118")  # the reference case (hubvib.design.presets)


SCENE = """
[reducer]
preset = "raba118"
[crack]
depths = {depths}
accuracy = "fast"
[signal]
sun_speed_rpm = 6000.0
noise_seeds = 2
roc_records = {roc}
{extra}
[output]
plots = {plots}
"""


def test_defaults_and_a_valid_table():
    assert parse_signal_table({}) == SignalOptions()
    options = parse_signal_table({"sensor_angle_deg": -30, "damping_ratio": 0.0,
                                  "integrator": "central"})
    assert options.sensor_angle_deg == -30.0 and options.damping_ratio == 0.0


@pytest.mark.parametrize("key, value, message", [
    ("sun_speed_rpm", 0.0, "[signal] sun_speed_rpm = 0.0; allowed: a finite number in (0, inf)"),
    ("sun_speed_rpm", -5, "sun_speed_rpm = -5"),
    ("sun_speed_rpm", float("nan"), "sun_speed_rpm = nan"),
    ("sun_torque_N_m", 0, "[signal] sun_torque_N_m = 0; allowed"),
    ("sun_torque_N_m", float("nan"), "sun_torque_N_m = nan"),
    ("revolutions", 0.5, "[signal] revolutions = 0.5; allowed: a finite number in [2, 10000]"),
    ("damping_ratio", 1.0, "[signal] damping_ratio = 1.0; allowed: a finite number in [0, 1)"),
    ("damping_ratio", -0.01, "damping_ratio = -0.01"),
    ("sensor_angle_deg", float("inf"), "[signal] sensor_angle_deg = inf; allowed: a finite"),
    ("sensor_angle_deg", float("nan"), "sensor_angle_deg = nan"),
    ("mesh_harmonics", 0, "[signal] mesh_harmonics = 0; allowed: an integer in 1..50"),
    ("integrator", "euler", "[signal] integrator = 'euler'; allowed: newmark, central"),
    ("colour", 1, "unknown key(s) ['colour'] at [signal]"),
])
def test_bad_table_values_name_the_key_and_range(key, value, message):
    with pytest.raises(SceneError) as error:
        parse_signal_table({key: value})
    assert message in str(error.value)


def test_sample_rate_is_checked_against_the_scenes_own_mesh_frequency():
    """Nyquist: fs >= 2 k f_mesh with f_mesh = z_r f_s z_s / (z_s + z_r) of the scene's design
    (Raba 64/26 at 1500 rpm and k = 3: 2 x 3 x 64 x 25 x 26/90 = 2773.33 Hz; hub4 80/24:
    2 x 3 x 80 x 25 x 24/104 = 2769.23 Hz), printed rounded up so that the printed rate passes)."""
    from hubvib.studies.scene import parse_scene

    for design, needed in (('[reducer]\npreset = "raba118"', "2773.34"),
                           ('[design]\npreset = "hub4"', "2769.24")):
        with pytest.raises(SceneError, match=f"sample_rate_hz = 2000; allowed: >= {needed} Hz"):
            parse_scene(f"{design}\n[crack]\ndepths = [0.0]\n[signal]\n"
                        "sample_rate_hz = 2000.0\n", "x")


@pytest.fixture
def fake_fe(monkeypatch):
    """Synthetic mesh curves instead of the FE stage (constant tooth compliances)."""
    def curves(scene, options, progress=None):
        p = scene.params
        return [synthetic_curves(RABA, crack_factor=1 + 40 * d, depth=d).to_preset(p.c_sp, p.c_rp)
                for d in scene.crack.depths]
    monkeypatch.setattr(signal_study, "curves_for", curves)


def _scene(tmp_path, extra="revolutions = 3", plots="false", depths=(0.0, 0.012), roc=20):
    path = tmp_path / "signal.toml"
    path.write_text(SCENE.format(extra=extra, plots=plots, depths=list(depths), roc=roc))
    return path


@pytest.mark.parametrize("extra, message", [
    ("integrator = 'central'\ntime_step_s = 1e-4",
     "[signal] time_step_s = 0.0001; allowed: < 4.3"),
    ("time_step_s = 1e-3", "[signal] time_step_s = 0.001; allowed: <= 0.0002"),
    ("sun_torque_N_m = -1.0", "[signal] sun_torque_N_m = -1.0"),
    ("revolutions = 0.9", "[signal] revolutions = 0.9"),
    ("sample_rate_hz = 5000.0", "[signal] sample_rate_hz = 5000; allowed: >= 11093.4 Hz"),
    ("planet_position_errors_m = [5e-5, 0.0]",
     "[signal] planet_position_errors_m has 2 value(s), but the reducer has 3 planets"),
    ("noise_level = 0.0", "[signal] noise_level = 0 with roc_records > 0"),
    ("speed_fluctuation = 0.7", "[signal] speed_fluctuation = 0.7; allowed: a finite number "
                                "in [0, 0.5]"),
], ids=["unstable-step", "step-over-half-mesh-period", "torque", "duration", "aliasing",
        "errors-per-planet", "roc-without-noise", "speed-fluctuation"])
def test_bad_input_is_one_line_exit_2_and_nothing_written(tmp_path, capsys, fake_fe, extra,
                                                          message):
    out = tmp_path / "out"
    assert main(["signal", str(_scene(tmp_path, extra)), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err, err
    assert not out.exists()


@pytest.mark.slow
def test_signal_command_writes_signal_spectrum_and_indicators(tmp_path, capsys, fake_fe):
    out = tmp_path / "out"
    assert main(["signal", str(_scene(tmp_path)), "--out", str(out), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert abs(data["carrier_hz"] - 6000 / 60 * 26 / 90) < 1e-12
    assert abs(data["mesh_hz"] - 64 * data["carrier_hz"]) < 1e-9
    assert data["sample_rate_hz"] == 20000.0 and len(data["depths"]) == 2
    for depth in data["depths"]:
        assert set(depth["indicators"]) == {"rms", "kurtosis", "crest_factor", "fm0", "fm4",
                                            "na4", "nb4", "m6a", "m8a", "er", "ser"}
        assert depth["non_multiple_fraction"] < 1e-18, \
            "no errors: the energy off the multiples of N is round-off (McFadden & Smith 1985)"
        assert min(depth["contact"]["min_force_ratio"].values()) > 0, "no contact loss here"
        assert max(depth["contact"]["separated_fraction"].values()) == 0
        with open(depth["signal_csv"]) as handle:
            rows = list(csv.DictReader(handle))
        assert list(rows[0]) == ["time_s", "acceleration_m_s2"]
        assert abs(len(rows) - 3 / data["carrier_hz"] * 20000) <= 1
    from scipy.io import wavfile

    rate, wav = wavfile.read(data["depths"][-1]["signal_wav"])
    assert rate == 20000 and wav.size == len(rows)
    assert data["monotone_indicators"], "a softer cracked tooth must move an indicator"
    assert data["checks"]["non_multiple_of_N_relative"] < 1e-9
    assert [r["fraction"] for r in data["non_multiple_fraction"]] == \
        [d["non_multiple_fraction"] for d in data["depths"]]
    np.testing.assert_allclose(data["load_sharing"], 1.0, atol=1e-9,
                               err_msg="no errors: equal load sharing")
    roc = data["roc"]
    assert roc["records_per_depth"] == 20 and roc["training_records"] == 60
    assert set(roc["indicators"]) == set(data["depths"][0]["indicators"])
    for row in roc["indicators"].values():
        assert len(row["pod"]) == 2 and len(row["roc"]) == 1 and 0 <= row["auc"][1] <= 1
    assert "### Detection rates (ROC / POD)" in (out / "report.md").read_text()
    report = (out / "report.md").read_text()
    assert "## Vibration signature" in report and "Monotone with depth" in report
    for name in ("order_spectrum.csv", "indicators.csv", "harmonics.csv", "results.json"):
        assert (out / name).stat().st_size > 0


@pytest.mark.slow
def test_signal_command_with_speed_fluctuation_writes_the_tacho(tmp_path, capsys, fake_fe):
    from hubvib.signal.speed import SpeedProfile

    out = tmp_path / "out"
    extra = "revolutions = 3\nspeed_fluctuation = 0.05\nspeed_fluctuation_hz = 2.0"
    assert main(["signal", str(_scene(tmp_path, extra, roc=0)), "--out", str(out),
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    rows = (out / "tacho.csv").read_text().splitlines()
    assert rows[0] == "pulse_time_s" and data["tacho_csv"] == str(out / "tacho.csv")
    pulses = np.array([float(r) for r in rows[1:]])
    speed = SpeedProfile(data["carrier_hz"], 0.05, 2.0)
    np.testing.assert_allclose(speed.angle(pulses), 2 * math.pi / 16 * np.arange(pulses.size),
                               atol=1e-9, err_msg="16 pulses per revolution (default)")
    assert data["depths"][-1]["indicators"]["fm4"]["mean"] > \
        data["depths"][0]["indicators"]["fm4"]["mean"]


@pytest.mark.slow
def test_signal_command_plots(tmp_path, capsys, fake_fe):
    out = tmp_path / "out"
    assert main(["signal", str(_scene(tmp_path, plots="true", depths=(0.0, 0.006, 0.012))),
                 "--out", str(out)]) == 0
    assert "monotone with depth:" in capsys.readouterr().out
    for name in ("order_spectrum.png", "spectrogram.png", "indicators.png", "tsa.png"):
        assert (out / name).stat().st_size > 10_000


@pytest.mark.slow
def test_shipped_signal_scene_has_a_monotone_indicator(tmp_path, capsys, shared_cache):
    """The default Raba signal scene with the FE stage (its FE cases in the run's shared
    cache, which test_scenes.test_every_scene_runs[raba118_signal] fills too)."""
    pytest.importorskip("skfem")
    out = tmp_path / "out"
    assert main(["signal", "raba118_signal", "--out", str(out), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["monotone_indicators"], "at least one indicator monotone with depth"
    assert data["checks"]["step_halving"]["relative_change"] < 0.02
    assert np.isfinite(data["depths"][-1]["indicators"]["fm0"]["mean"])
    # Ideal planets leave round-off off the multiples of N at every depth; with
    # every mesh harmonic and its first sidebands removed, FM4 goes from ~3 intact to
    # "about 36 at 3 mm" (reconstruction from order_spectrum.csv; 30 % here)
    assert max(r["fraction"] for r in data["non_multiple_fraction"]) < 1e-18
    fm4 = [d["indicators"]["fm4"]["mean"] for d in data["depths"]]
    assert 2.5 < fm4[0] < 3.6 and 25 < fm4[1] < 47, fm4
    assert data["roc"]["indicators"]["fm4"]["pod"][1] == 1.0


@pytest.mark.slow
def test_several_sensors_relative_to_the_crack(tmp_path, capsys, fake_fe):
    """A sensor at 0 deg from the cracked tooth (tooth 0) is the study's own sensor at 0 deg:
    same numbers.  Intact, a sensor 120 deg on sees the same signal a third of a revolution
    later (N = 3 symmetry): the same RMS and kurtosis, to the cubic-spline angle
    resampling of the TSA (the samples fall elsewhere on the revolution), 1e-3.  (Without
    noise the small lines (sidebands, difference signal) carry that resampling error
    (3.6 samples per period of mesh harmonic 3 at 6000 rpm and 20 kHz), so SER, FM4 & co.
    are left out of this comparison.)"""
    out = tmp_path / "out"
    extra = "sensor_angles_from_crack_deg = [0.0, 120.0, 180.0]\nnoise_level = 0.0"
    assert main(["signal", str(_scene(tmp_path, extra, roc=0)), "--out", str(out),
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    own, at120, at180 = data["sensors"]
    assert [s["angle_from_crack_deg"] for s in data["sensors"]] == [0.0, 120.0, 180.0]
    for depth, row in zip(data["depths"], own["depths"]):
        for name, value in depth["indicators"].items():
            assert value["mean"] == pytest.approx(row["indicators"][name]["mean"], rel=1e-12)
    for name in ("rms", "kurtosis"):
        assert at120["depths"][0]["indicators"][name]["mean"] == pytest.approx(
            own["depths"][0]["indicators"][name]["mean"], rel=1e-3), name
    cracked = [s["depths"][-1]["indicators"]["fm4"]["mean"] for s in (own, at180)]
    assert cracked[0] != pytest.approx(cracked[1], rel=1e-6), \
        "cracked: the view depends on where the sensor sits"
    assert "from the cracked tooth" in (out / "report.md").read_text()
