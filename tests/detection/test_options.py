"""The scene's [detection] table: defaults, SI conversion, every bad value named."""
import math

import pytest

from hubvib.cli import main
from hubvib.detection.options import DetectionOptions, detection_options
from hubvib.studies.scene import SceneError, load_scene, parse_scene

LUMPED = "[study]\nvalues = [1e5]\n"


def test_defaults_without_a_table_and_si_conversion():
    scene = parse_scene(LUMPED, "s")
    assert detection_options(scene) == DetectionOptions()
    options = parse_scene(LUMPED + "[detection]\nscatter_masses_percent = 5\n"
                          "carrier_speed_rpm = 60\nrecord_length_s = 4\n", "s").tables["detection"]
    assert options.scatter_masses == pytest.approx(0.05)
    assert options.carrier_speed == pytest.approx(2 * math.pi), "60 rpm = 2 pi rad/s"
    assert options.resolution_hz == pytest.approx(0.25), "resolution 1/T"


def test_shipped_default_scene_states_the_documented_defaults():
    assert load_scene(None).tables["detection"] == DetectionOptions()


@pytest.mark.parametrize("line, message", [
    ("record_length_s = 0", r"\[detection\] record_length_s = 0; allowed: a number in \(0, inf\)"),
    ("record_length_s = -2.5", r"record_length_s = -2.5; allowed"),
    ("record_length_s = nan", r"record_length_s = nan; allowed"),
    ("scatter_masses_percent = -1", r"scatter_masses_percent = -1; allowed: a number in \[0, 100\]"),
    ("scatter_stiffnesses_percent = 101", r"scatter_stiffnesses_percent = 101; allowed"),
    ("scatter_mounting_percent = 'x'", r"scatter_mounting_percent = 'x'; allowed"),
    ("false_alarm_rate = 0.5", r"false_alarm_rate = 0.5; allowed: a number in \(0, 0.5\)"),
    ("samples = 10", r"samples = 10; allowed: an integer in \[100, 1e\+06\]"),
    ("samples = 200.5", r"samples = 200.5; allowed: an integer"),
    ("mount_min_N_m = 0", r"mount_min_N_m = 0; allowed"),
    ("mount_min_N_m = 1e9\nmount_max_N_m = 1e8", "must be below mount_max_N_m"),
    ("detection_probability = 0.005", "must exceed false_alarm_rate"),
    ("colour = 1", r"unknown key\(s\) \['colour'\] at \[detection\]"),
])
def test_bad_values_name_the_key_and_the_range(line, message):
    with pytest.raises(SceneError, match=message):
        parse_scene(LUMPED + f"[detection]\n{line}\n", "bad")


@pytest.mark.parametrize("text", ["[crack]\napply = 'series'\nc_ru_mount = -1e6\n",
                                  "[crack]\napply = 'series'\nc_r_mount = 0\n",
                                  "[crack]\napply = 'series'\nc_ru_mount = nan\n"])
def test_bad_mount_stiffness_is_refused(text):
    with pytest.raises(SceneError, match=r"\[crack\] c_r?u?_mount = .*; allowed: a finite "
                                         r"stiffness > 0 \[N/m\]"):
        parse_scene(text, "bad")


def test_bad_table_on_the_command_line_exits_2_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "out"
    scene = tmp_path / "bad.toml"
    scene.write_text(LUMPED + "[detection]\nrecord_length_s = -1\n")
    assert main(["run", str(scene), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("hubvib: error: [detection] record_length_s = -1") and \
        err.count("\n") == 1 and "Traceback" not in err
    assert not out.exists()
