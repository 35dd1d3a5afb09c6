from pathlib import Path

import pytest

from hubvib.cli import main
from hubvib.scene import SceneError, default_scene_text, load_scene, parse_scene

SCENES = sorted((Path(__file__).parents[1] / "scenes").glob("*.toml"))


def test_scene_folder_is_not_empty():
    assert len(SCENES) >= 2


@pytest.mark.parametrize("scene", SCENES, ids=[s.stem for s in SCENES])
def test_every_scene_runs(scene, tmp_path, capsys):
    assert main(["run", str(scene), "--out", str(tmp_path)]) == 0
    report = (tmp_path / "report.md").read_text()
    assert "## Baseline spectrum" in report and "## Detection" in report
    for name in ("baseline_spectrum.csv", "shifts.csv", "detection.csv", "results.json"):
        assert (tmp_path / name).stat().st_size > 0


def test_default_scene_is_the_shipped_raba_scene():
    shipped = Path(__file__).parents[1] / "scenes" / "raba118_c_ru.toml"
    assert default_scene_text() == shipped.read_text()


def test_default_run_detects_the_crack_in_rotational_modes_only(tmp_path, capsys):
    assert main(["run", "--out", str(tmp_path)]) == 0
    from hubvib.study import run_study

    result = run_study(load_scene(None))
    detected = {r["kind"] for r in result.detection() if r["detectable_at"] is not None}
    assert detected == {"rotational"}
    assert (tmp_path / "frequency_vs_parameter.png").stat().st_size > 10_000


@pytest.mark.parametrize("text, message", [
    ("[study]\nvalues = [1e5]\ncolour = 1\n", r"unknown key\(s\) \['colour'\] at \[study\]"),
    ("[nonsense]\n", r"unknown key\(s\) \['nonsense'\] at top level"),
    ("[study]\nvalues = [-1.0]\n", r"values\[0\]: c_ru = -1.0, but it must be >= 0.0"),
    ("[study]\nvalues = []\n", "non-empty list of numbers"),
    ("[study]\nvalues = [1e5]\nparameter = 'theta'\n", "parameter = 'theta'; allowed"),
    ("[study]\nvalues = [1e5]\nmethod = 'qr'\n", "method = 'qr'; allowed: jacobi"),
    ("[study]\nvalues = [1e5]\ndetection_threshold_percent = 0\n", "must be a number > 0"),
    ("[reducer]\npreset = 'x'\n[study]\nvalues = [1e5]\n", r"\[reducer\]: unknown preset 'x'"),
    ("[reducer.parameters]\nc_ru = 'soft'\n[study]\nvalues = [1e5]\n", "c_ru = 'soft'"),
    ("[output]\nplots = 'yes'\n[study]\nvalues = [1e5]\n", "plots = 'yes'"),
    ("study = [\n", "not valid TOML"),
])
def test_scene_errors_name_the_key(text, message):
    with pytest.raises(SceneError, match=message):
        parse_scene(text, "bad")


def test_bad_scene_writes_nothing(tmp_path, capsys):
    scene = tmp_path / "bad.toml"
    out = tmp_path / "out"
    scene.write_text(f"[study]\nvalues = [1e5]\nfoo = 1\n[output]\nfolder = '{out}'\n")
    assert main(["run", str(scene)]) == 2
    assert "unknown key(s) ['foo']" in capsys.readouterr().err
    assert not out.exists()


def test_missing_scene_file(tmp_path, capsys):
    assert main(["run", str(tmp_path / "none.toml")]) == 2
    assert "cannot read scene" in capsys.readouterr().err
