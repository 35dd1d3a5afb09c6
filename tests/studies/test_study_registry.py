"""The scene is a tagged union of registered study kinds.  A study kind defined
here, registered at run time with no other edit, is selected by its own scene table and run
by ``hubvib run``; its spectrum is checked against ``hubvib.lumped.natural_modes`` called
directly.  The registry's errors name the tables."""
from __future__ import annotations

import csv
import json
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from hubvib.cli import main
from hubvib.reducer import lumped_preset
from hubvib.foundation.errors import SceneError
from hubvib.foundation.output import write_csv, write_text
from hubvib.lumped import natural_modes
from hubvib.studies.kinds import STUDIES, study_of
from hubvib.studies.scene import load_scene, parse_scene
from hubvib.studies.kind_registry import Study, check_keys, register_study, string_key

KIND = "lumped_spectrum"


@dataclass(frozen=True)
class SpectrumOptions:
    file: str


@dataclass
class SpectrumResult:
    rows: list[dict]
    files: list[Path] = field(default_factory=list)


def _parse(data: dict, design, params) -> SpectrumOptions:
    table = data[KIND]
    if not isinstance(table, dict):
        raise SceneError(f"[{KIND}] must be a table, got {table!r}")
    check_keys(table, KIND, {"file"})
    name = string_key(table, KIND, "file", "spectrum.csv")
    if not name.endswith(".csv") or "/" in name:
        raise SceneError(f"[{KIND}] file = {name!r}; allowed: a file name ending .csv")
    return SpectrumOptions(name)


def _run(scene, staged: Path) -> SpectrumResult:
    rows = natural_modes(scene.params, scene.method).rows()
    result = SpectrumResult(rows)
    result.files.append(write_csv(staged / scene.study.file, rows))
    section = ["# Lumped spectrum", "", f"## Natural frequencies of {scene.name}", "",
               "| mode | f [Hz] |", "|---:|---:|"]
    section += [f"| {r['mode']} | {r['frequency_hz']:.6g} |" for r in rows]
    result.files.append(write_text(staged / "report.md", "\n".join(section) + "\n"))
    return result


def _summary(scene, result: SpectrumResult, folder: Path, files: list) -> dict:
    return {"scene": scene.name, "folder": str(folder), "files": [str(f) for f in files],
            "modes": len(result.rows)}


def _lines(scene, result: SpectrumResult, folder: Path) -> list[str]:
    return [f"scene {scene.name!r}: {len(result.rows)} modes", f"report: {folder / 'report.md'}"]


SPECTRUM = Study(KIND, _run, _summary, _lines, _parse, tables=frozenset({KIND}))

SCENE = f"""# the lumped spectrum of the Raba 118/76 reducer
[reducer]
preset = "raba118"
[study]
method = "jacobi"
[{KIND}]
file = "modes.csv"
[output]
plots = false
"""


@pytest.fixture
def registered():
    """The test kind, registered for one test and removed after it."""
    register_study(SPECTRUM)
    yield SPECTRUM
    STUDIES.pop(KIND)


def test_a_kind_registered_at_run_time_runs_through_hubvib_run(registered, tmp_path, capsys):
    scene_file = tmp_path / "spectrum.toml"
    scene_file.write_text(SCENE, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["run", str(scene_file), "--out", str(out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    expected = natural_modes(lumped_preset("raba118"), "jacobi")
    assert summary["modes"] == len(expected.omega) == 9 + 3 * 3, "9 + 3N DOF (N = 3 planets)"
    assert sorted(Path(f).name for f in summary["files"]) == ["modes.csv", "report.md"]
    with open(out / "modes.csv", encoding="utf-8", newline="") as handle:
        rows = list(csv.DictReader(handle))
    got = [float(r["frequency_hz"]) for r in rows]
    assert got == pytest.approx(list(expected.frequency_hz), rel=1e-12, abs=1e-9), (
        "CSV frequencies against hubvib.lumped.natural_modes(lumped_preset('raba118')) called directly "
        "(float repr round trip: rel 1e-12)")
    assert [r["kind"] for r in rows] == list(expected.kind), "mode types as natural_modes gives"
    report = (out / "report.md").read_text(encoding="utf-8")
    assert "## Natural frequencies of spectrum" in report
    highest = expected.frequency_hz[-1]
    assert f"| {len(rows)} | {highest:.6g} |" in report, "report row of the highest mode"


def test_the_scene_names_its_kind_and_options(registered):
    scene = parse_scene(SCENE, "spectrum")
    assert scene.kind == KIND and study_of(scene) is SPECTRUM
    assert scene.study == SpectrumOptions("modes.csv") and scene.crack is None


def test_a_kind_parses_its_own_table(registered):
    with pytest.raises(SceneError, match=r"\[lumped_spectrum\] file = 'modes.txt'; allowed"):
        parse_scene(SCENE.replace("modes.csv", "modes.txt"), "spectrum")
    with pytest.raises(SceneError, match=r"unknown key\(s\) \['x'\] at \[lumped_spectrum\]"):
        parse_scene(SCENE.replace('file = "modes.csv"', "x = 1"), "spectrum")


def test_unregistered_table_is_an_unknown_key(tmp_path, capsys):
    scene_file = tmp_path / "spectrum.toml"
    scene_file.write_text(SCENE, encoding="utf-8")
    assert main(["run", str(scene_file), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("hubvib: error: unknown key(s) ['lumped_spectrum'] at top level")
    assert err.count("\n") == 1 and not (tmp_path / "out").exists(), "one line, nothing written"


def test_two_kinds_tables_together_select_none(registered, tmp_path, capsys):
    text = SCENE + "[crack]\ndepths = [0.0, 0.005]\n"
    with pytest.raises(SceneError, match=r"no study kind is selected by \[crack\] \+ "
                                         r"\[lumped_spectrum\]; allowed: one of sweep"):
        parse_scene(text, "both")
    scene_file = tmp_path / "both.toml"
    scene_file.write_text(text, encoding="utf-8")
    assert main(["run", str(scene_file), "--out", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err.startswith("hubvib: error: no study kind is selected by")


def test_ambiguous_kinds_are_named(registered):
    twin = Study("twin", _run, _summary, _lines, _parse, tables=frozenset({KIND}))
    register_study(twin)
    try:
        with pytest.raises(SceneError, match=r"\[lumped_spectrum\] select several study kinds "
                                             r"\(lumped_spectrum, twin\)"):
            parse_scene(SCENE, "spectrum")
    finally:
        STUDIES.pop("twin")


def test_a_kind_name_registers_once(registered):
    with pytest.raises(ValueError, match="lumped_spectrum.*registered already"):
        register_study(SPECTRUM)


@pytest.mark.parametrize("name, kind", [
    ("raba118_c_ru", "sweep"), ("raba118_five_planets", "sweep"), ("raba118_crack", "crack"),
    ("hub4_crack", "crack"), ("raba118_signal", "crack"), ("raba118_crack_3d", "growth")])
def test_shipped_scenes_select_their_kind(name, kind):
    scene = load_scene(name)
    assert scene.kind == kind, f"shipped scene {name} is a {kind} study"
    assert (scene.crack is None) == (kind == "sweep")
