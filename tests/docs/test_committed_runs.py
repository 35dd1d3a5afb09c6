"""The committed runs the docs quote are runs of the input files their meta commands name:
a stale output (an input edited, the run not redone) fails here, not silently in a page."""
import json
import re
import shlex
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]
DATA = ROOT / "docs" / "data"


def _commands(entry: str) -> list[list[str]]:
    meta = json.loads((DATA / f"{entry}.meta.json").read_text())
    return [shlex.split(command) for command in meta["command"]]


def test_backup_ratio_runs_are_of_their_design_files():
    """Each ``hubvib crack-path --design F --tooth K --json > OUT`` of the backup-ratio entry
    wrote OUT from F: the design name, the tooth, and the backup ratio equal to F's
    rim_thickness over the run's tooth height (to 1e-9) and to the m_B its file name states
    (the variants are defined as m_B x tooth height, to 1e-9)."""
    checked = 0
    for argv in _commands("crack_path_backup_ratio"):
        out = ROOT / argv[argv.index(">") + 1]
        run = json.loads(out.read_text())
        assert run["tooth"] == int(argv[argv.index("--tooth") + 1]), out.name
        if "--design" not in argv:
            assert run["design"] == "raba118", out.name
            continue
        design = tomllib.loads((ROOT / argv[argv.index("--design") + 1]).read_text())["design"]
        assert run["design"] == design["name"], out.name
        ratio = design["ring"]["rim_thickness"] / run["tooth_height_m"]
        assert run["backup_ratio"] == pytest.approx(ratio, rel=1e-9), (
            f"{out.name}: backup ratio against the design file's rim / tooth height, 1e-9")
        stated = float(re.search(r"mB([\d.]+)\.toml$", argv[argv.index("--design") + 1]).group(1))
        assert run["backup_ratio"] == pytest.approx(stated, rel=1e-9), out.name
        checked += 1
    assert checked >= 9, "the variants of docs/crack_path.md's backup-ratio table"


@pytest.mark.parametrize("entry", ["raba118_signal_planet_error", "raba118_signal_noise0.5",
                                   "raba118_signal_noise2"])
def test_signal_variant_runs_are_of_their_scenes(entry):
    """The committed ``results.json`` of a signal variant holds the options and depths of
    the scene file its command names (every ``[signal]`` key of the file, exactly)."""
    (argv,) = _commands(entry)
    scene = tomllib.loads((ROOT / argv[2]).read_text())
    run = json.loads((DATA / entry / "results.json").read_text())
    for key, value in scene["signal"].items():
        got = run["options"][key]
        assert (list(got) if isinstance(got, (list, tuple)) else got) == value, (
            f"{entry}: [signal] {key} = {value!r} in {argv[2]}, the run has {got!r}")
    assert [d["depth_mm"] for d in run["depths"]] == pytest.approx(
        [1e3 * d for d in scene["crack"]["depths"]], abs=1e-9), f"{entry}: crack depths"
