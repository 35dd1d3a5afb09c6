from pathlib import Path

import pytest

from hubvib.cli import main
from hubvib.studies.scene import SceneError, default_scene_text, load_scene, parse_scene

SCENES = sorted((Path(__file__).parents[2] / "scenes").glob("*.toml"))
FE_SCENES = [s for s in SCENES if "[crack]" in s.read_text()]
#: run by test_crack_growth.test_shipped_3d_scene_on_a_local_cluster (some 10 minutes)
SOLID_SCENES = [s for s in SCENES if 'model = "solid"' in s.read_text()]


def test_shipped_scenes_are_the_scene_files():
    """What an installed package ships (importlib.resources, ``hubvib scenes``) is exactly
    the TOML files of scenes/, the default and an FE scene among them, each described by a
    first comment line: so the parametrised run below (and the solid crack-growth test)
    covers every shipped scene."""
    from hubvib.studies.scene import DEFAULT_SCENE, shipped_scenes

    shipped = shipped_scenes()
    assert sorted(shipped) == [s.stem for s in SCENES], "package data vs scenes/*.toml"
    assert DEFAULT_SCENE in shipped and FE_SCENES and SOLID_SCENES
    for scene in SCENES:
        first = scene.read_text(encoding="utf-8").splitlines()[0]
        assert first.startswith("# ") and shipped[scene.stem], f"{scene.name}: no description"


#: scenes another slow test runs too: their FE work goes to the run's shared cache
SHARED_CACHE_SCENES = ("raba118_crack_path", "raba118_signal", "raba118_closed_loop")


@pytest.mark.parametrize("scene", [pytest.param(s, marks=pytest.mark.slow) if s in FE_SCENES
                                   else s for s in SCENES if s not in SOLID_SCENES],
                         ids=[s.stem for s in SCENES if s not in SOLID_SCENES])
def test_every_scene_runs(scene, tmp_path, capsys, monkeypatch, request):
    """Each shipped scene from an empty cache, except three whose cache is the run's shared
    one (conftest ``shared_cache``) so that their FE work is done once in the run: the
    predicted-path scene (the Raba path, minutes of FE growth keyed on design, tooth and
    step, also parsed by test_crack_kinds.test_predicted_path_key), the closed-loop scene
    (its FE cases, also run by test_signal_closed_loop) and the signal scene
    (its FE cases and mesh curves, also run by
    test_signal_cli.test_shipped_signal_scene_has_a_monotone_indicator)."""
    if scene.stem in SHARED_CACHE_SCENES:
        request.getfixturevalue("shared_cache")
    else:
        monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    out = tmp_path / "out"
    assert main(["run", str(scene), "--out", str(out)]) == 0
    report = (out / "report.md").read_text()
    if scene in FE_SCENES:
        assert "## FE stiffness against crack depth" in report and "## Modes" in report
        names = ("stiffness_vs_depth.csv", "frequency_vs_depth.csv", "modes.csv", "results.json")
    else:
        assert "## Baseline spectrum" in report and "## Detection" in report
        names = ("baseline_spectrum.csv", "shifts.csv", "detection.csv", "results.json")
        if load_scene(scene).plots:
            assert (out / "frequency_vs_parameter.png").stat().st_size > 10_000
    for name in names:
        assert (out / name).stat().st_size > 0
    if "[signal]" in scene.read_text():
        assert "## Vibration signature" in report
        assert "## Vibration signature" in (out / "signal" / "report.md").read_text()
        assert (out / "signal" / "indicators.csv").stat().st_size > 0


def test_default_scene_is_the_shipped_crack_scene():
    shipped = Path(__file__).parents[2] / "scenes" / "raba118_crack.toml"
    assert default_scene_text() == shipped.read_text()
    assert load_scene(None).crack.depths[-1] > 0.024  # through the rim


def test_fig4_scene_detects_the_crack_in_rotational_modes_only(fig4_sweep):
    """The files of the run (plots included) are checked in test_every_scene_runs."""
    detected = {r["kind"] for r in fig4_sweep.detection() if r["detectable_at"] is not None}
    assert detected == {"rotational"}


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
    ("[crack]\ndepths = [0.0, 0.5]\n", r"depths\[1\]: crack.depth = 0.5 m is deeper than"),
    ("[crack]\ndepths = [0.002, 0.001]\n", "allowed ascending values from 0"),
    ("[crack]\napply = 'both'\n", "apply = 'both'; allowed: .*ratio, direct"),
    ("[crack]\nworkers = 0\n", r"workers = 0; allowed integers 1..64"),
    ("[crack]\ntooth = 64\n", r"tooth = 64.* 64 teeth"),
    ("[crack]\nangle_deg = 75\n", "angle_deg = 75; allowed -90..60"),
    ("[crack]\ncolour = 1\n", r"unknown key\(s\) \['colour'\] at \[crack\]"),
    ("[output]\nrenders = true\n[study]\nvalues = [1e5]\n", "renders = true needs a"),
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


def test_unwritable_output_folder(tmp_path, capsys):
    import os

    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    if os.access(locked, os.W_OK):  # root ignores permissions
        pytest.skip("running as root: permissions are not enforced")
    assert main(["run", "--out", str(locked / "out")]) == 2
    assert "cannot write the output folder" in capsys.readouterr().err


def test_output_folder_that_is_a_file(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    assert main(["run", "--out", str(blocker / "out")]) == 2
    assert "cannot write the output folder" in capsys.readouterr().err


def test_fe_scene_without_fe_extras(tmp_path, capsys, monkeypatch):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "gmsh" else real(name, *a))
    assert main(["run", "--out", str(tmp_path / "out")]) == 2
    assert "pip install 'hubvib[fem]'" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()
