"""``hubvib modes`` says what a user can trust: a flag's range by the flag's name, a word
where a mode is not tracked, the design's name as given."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.helpers.cli_output import run_cli

MY5 = Path(__file__).parents[1] / "elastic" / "designs" / "my5.toml"


@pytest.mark.parametrize("tooth", ["99", "64", "-1"])
def test_carrier_tooth_out_of_range_names_the_flag(tooth):
    """Raba's ring has 64 teeth: the line names ``--carrier-tooth`` and 0..63, exit 2."""
    code, out, err = run_cli(["modes", "--preset", "raba118", "--carrier-tooth", tooth])
    assert code == 2 and not out
    assert err.strip() == (f"hubvib: error: --carrier-tooth = {tooth}, allowed 0..63 (a tooth "
                           "of the 64-tooth ring of design 'raba118')"), err


@pytest.mark.parametrize("name", ["my5", "mY5 own", "MY5"])
def test_design_name_prints_as_given(tmp_path, name):
    """The design's name, whatever its case, is printed exactly as the file gives it."""
    path = tmp_path / "design.toml"
    path.write_text(MY5.read_text().replace('name = "my5"', f'name = "{name}"'))
    code, text, err = run_cli(["design", "check", str(path)])
    assert code == 0, err
    assert f"design '{name}'" in text
    others = {name.title(), name.capitalize(), name.upper(), name.lower()} - {name}
    for wrong in others:
        assert wrong not in text, f"{wrong!r} printed for the design named {name!r}"


@pytest.mark.slow
def test_modes_prints_the_design_name_as_given(tmp_path):
    """``hubvib modes`` (rigid ring, text and JSON) on the design named "my5"."""
    path = tmp_path / "own.toml"
    path.write_text(MY5.read_text())
    code, data, err = run_cli(["modes", "--design", str(path), "--ring", "rigid", "--json"])
    assert code == 0, err
    assert data["design"] == "my5"
    code, text, err = run_cli(["modes", "--design", str(path), "--ring", "rigid"])
    assert code == 0, err
    assert "(my5)" in text and "My5" not in text


@pytest.mark.slow
def test_untracked_mode_prints_a_word_not_nan():
    """A 20 mm crack at tooth 0 under load: a mode without an intact counterpart is
    ``null`` in the JSON; the text prints 'not tracked' in its place, never 'nan'."""
    argv = ["modes", "--preset", "raba118", "--crack-depth", "0.02", "--carrier-tooth", "0"]
    code, data, err = run_cli([*argv, "--json"])
    assert code == 0, err
    untracked = [r["mode"] for r in data["modes"]
                 if r["intact_hz"] is None or r["frequency_slip_hz"] is None]
    assert untracked, "this case has a mode without an intact counterpart"
    code, text, err = run_cli(argv)
    assert code == 0, err
    assert not re.search(r"\bnan\b", text, re.IGNORECASE), text
    rows = {int(line.split()[0]): line for line in text.splitlines()
            if re.match(r"^\s*\d+\s+\d", line)}
    for mode in untracked:
        assert "not tracked" in rows[mode], rows[mode]


def test_rigid_modes_name_their_model():
    """Mode numbers of the two ring models mean different modes: the rigid table says
    whose numbers they are, and each JSON row carries the label the report prints
    (``detection.mode_names.rigid_label``: ``rigid K (type, f Hz)``)."""
    code, text, err = run_cli(["modes", "--preset", "raba118", "--ring", "rigid"])
    assert code == 0, err
    assert text.splitlines()[0].startswith("raba118: rigid ring (the 9 + 3N model)")
    code, out, err = run_cli(["modes", "--preset", "raba118", "--ring", "rigid", "--json"])
    assert code == 0, err
    rows = out["modes"]
    assert len(rows) == 18
    for row in rows:
        assert row["label"] == (f"rigid {row['mode']} ({row['kind']}, "
                                f"{row['frequency_hz']:.1f} Hz)"), row
    assert len({row["label"] for row in rows}) == 18, "one label per mode"


@pytest.mark.slow
def test_elastic_modes_carry_the_reports_label():
    """Each coupled mode of ``hubvib modes --ring elastic --json`` carries the label the
    report and detection print (``elastic_label``: nodal diameter, class, frequency), one
    per mode."""
    code, out, err = run_cli(["modes", "--preset", "raba118", "--ring", "elastic", "--json"])
    assert code == 0, err
    rows = out["modes"]
    for row in rows:
        assert row["label"] == (f"elastic n={row['nodal_diameter']} ({row['class']}, "
                                f"{row['frequency_hz']:.1f} Hz)"), row
    assert len({row["label"] for row in rows}) == len(rows), "one label per mode"


@pytest.mark.slow
def test_loaded_record_names_its_modes_as_the_report_does():
    """``hubvib modes --crack-depth`` (the record over the pitch) names each row by the
    intact coupled mode half a pitch from the crack: the labels of the default run's
    elastic ring (committed ``docs/data/raba118_crack/results.json``), mode by mode."""
    import json

    committed = json.loads((Path(__file__).parents[2] / "docs" / "data" / "raba118_crack"
                            / "results.json").read_text())
    labels = [m["label"] for m in committed["elastic_ring"]["modes"]]
    code, out, err = run_cli(["modes", "--preset", "raba118", "--crack-depth", "0.003",
                              "--json"])
    assert code == 0, err
    got = [row["label"] for row in out["modes"]]
    n = min(len(got), len(labels))
    assert n >= 20 and got[:n] == labels[:n]
