"""What ``pip install .`` puts into site-packages: only the ``hubvib`` namespace."""
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest


ROOT = Path(__file__).parents[2]


@pytest.mark.slow
def test_wheel_installs_only_hubvib_with_every_scene(tmp_path):
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps",
                    "-q", "-w", str(tmp_path), "."], check=True, cwd=ROOT)
    wheel, = tmp_path.glob("hubvib-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    top = {n.split("/")[0] for n in names}
    assert {t for t in top if not t.endswith(".dist-info")} == {"hubvib"}, top
    listed = [name for name in tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
              ["packages"]]
    source = [p.parent.relative_to(ROOT).as_posix() for p in ROOT.glob("hubvib/*/__init__.py")]
    assert {f"hubvib.{s.split('/')[1]}" for s in source} <= set(listed), "pyproject packages"
    for package in ("lumped", "fem", "meshing", "validation", "design", "commands", "signal",
                    "detection", "companion"):
        assert f"hubvib/{package}/__init__.py" in names, package
    assert "hubvib/scenes/raba118_crack.toml" in names and "hubvib/scenes/hub4_crack.toml" in names


@pytest.mark.slow
def test_shipped_scenes_run_by_name_from_any_folder(tmp_path, monkeypatch, capsys):
    from hubvib.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["scenes"]) == 0
    listed = capsys.readouterr().out.splitlines()
    assert any(line.startswith("raba118_crack ") and "(default)" in line for line in listed)
    assert any(line.startswith("hub4_crack ") for line in listed)
    assert main(["run", "raba118_c_ru", "--out", str(tmp_path / "out")]) == 0
    assert (tmp_path / "out" / "report.md").exists()
    assert main(["run", "no_such_scene"]) == 2
    assert "shipped: " in capsys.readouterr().err
