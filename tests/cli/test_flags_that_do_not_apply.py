"""A flag given where it changes nothing, and a file of the wrong kind, are refused: one line
naming the flag (or the file) and what it needs, exit 2, no traceback, nothing written."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from hubvib.cli import main

INPUTS = Path(__file__).parents[2] / "docs" / "data" / "inputs"

REFUSED = [
    (["mesh", "ring", "--crack-half-length", "0.004"], "--crack-half-length = 0.004",
     "--crack-front semi_elliptic"),
    (["mesh", "ring", "--crack-depth", "0.003", "--crack-half-length", "0.004"],
     "--crack-half-length", "--dim 3"),
    (["mesh", "ring", "--dim", "3", "--crack-depth", "0.003", "--crack-front", "through",
      "--crack-half-length", "0.004"], "--crack-half-length", "semi_elliptic"),
    (["mesh", "ring", "--crack-front", "semi_elliptic"], "--crack-front", "--dim 3"),
    (["mesh", "ring", "--crack-angle", "10"], "--crack-angle = 10.0", "--crack-depth D"),
    (["mesh", "ring", "--crack-tooth", "3"], "--crack-tooth = 3", "--crack-depth D"),
    (["mesh", "planet", "--crack-start", "rim"], "--crack-start = 'rim'", "ring crack"),
    (["efficiency", "--ratio", "7", "--satellite", "roller", "--ball-diameter-mm", "12"],
     "--ball-diameter-mm = 12.0", "--satellite ball or both"),
    (["efficiency", "--ratio", "7", "--satellite", "ball", "--roller-diameter-mm", "8"],
     "--roller-diameter-mm = 8.0", "--satellite roller or both"),
    (["efficiency", "--table", "--curve"], "--curve applies only", "not --table"),
    (["efficiency", "--ratio", "7", "--curve", "--json"], "--curve applies only", "--json"),
    (["torus-screw", "--fingers", "cylindrical", "--finger-spacing", "0.02"],
     "--finger-spacing = 0.02", "--fingers spherical or both"),
    (["efficiency", "--table", "--input-power-w", "100"], "--input-power-w = 100.0",
     "with --json or --out"),
    (["benchmark", "--quick", "--no-3d-scene"], "--no-3d-scene applies only to a full run",
     "--quick skips"),
]


@pytest.mark.parametrize("argv,flag,needs", REFUSED, ids=[" ".join(a[:3]) for a, _, _ in REFUSED])
def test_a_flag_that_does_not_apply_is_refused(argv, flag, needs, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "out"
    extra = ["--out", str(out)] if argv[0] in ("mesh", "torus-screw") else []
    assert main(argv + extra) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("hubvib: error: "), err
    assert flag in err and needs in err, f"{argv}: the line names the flag and when it applies: {err}"
    assert not out.exists(), "nothing written"


def test_the_flags_work_where_they_apply(capsys):
    assert main(["efficiency", "--ratio", "7", "--satellite", "ball",
                 "--ball-diameter-mm", "12"]) == 0
    assert main(["torus-screw", "--fingers", "spherical", "--finger-spacing", "0.012"]) == 0
    assert main(["efficiency", "--ratio", "7", "--curve"]) == 0
    assert "alpha1" in capsys.readouterr().out


def test_a_design_file_given_as_a_scene_is_named_as_one(tmp_path, monkeypatch, capsys):
    """The user's report: hubvib run on a design file said '[study] values = None'."""
    monkeypatch.chdir(tmp_path)
    shutil.copy(INPUTS / "demo.toml", tmp_path / "my5.toml")
    assert main(["run", "my5.toml"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert "'my5.toml' is a design file" in err and "hubvib design check my5.toml" in err
    assert '[design] file = "my5.toml"' in err and "values = None" not in err
    assert not (tmp_path / "hubvib-out").exists()


def test_a_scene_given_to_design_check_is_named_as_one(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text('[design]\nfile = "demo.toml"\n[study]\nvalues = [1e5]\n')
    assert main(["design", "check", "s.toml"]) == 2
    err = capsys.readouterr().err
    assert "'s.toml' is a scene, not a design file (it has [study])" in err, err
    assert "hubvib run s.toml" in err


def test_the_scene_tables_design_check_knows_are_the_scene_loaders():
    """One fact in two layers: the tables that make a file a scene (hubvib.design.parse
    cannot import the studies layer)."""
    from hubvib.design.parse import SCENE_TABLES
    from hubvib.studies.kind_registry import study_tables
    from hubvib.studies.scene import TOP_LEVEL

    assert SCENE_TABLES == (TOP_LEVEL | study_tables()) - {"design"}


@pytest.mark.parametrize("argv,names", [
    (["stiffness", "--crack-depth", "abc"], "argument --crack-depth: invalid float value: 'abc'"),
    (["mesh", "ring", "--dim", "4"], "argument --dim: invalid choice: 4 (choose from 2, 3)"),
    (["nosuch"], "invalid choice: 'nosuch'"),
], ids=["type", "choice", "command"])
def test_a_usage_error_is_one_line_naming_the_flag_and_its_choices(argv, names, capsys):
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and names in err and "--help lists the flags" in err, err
