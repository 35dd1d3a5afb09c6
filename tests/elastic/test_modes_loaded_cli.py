"""``hubvib modes`` with the loaded crack: flags that do not apply are refused in one line
(exit 2), the record's JSON holds what it promises, and the intact ring prints the crack
study's numbers (one mesh, one number)."""
from __future__ import annotations

import numpy as np
import pytest

from hubvib.cli import main
from tests.helpers.cli_output import run_cli


ANNULUS = ["--annulus", "0.1", "0.12", "0.02"]


@pytest.mark.parametrize("argv, words", [
    (["modes", *ANNULUS, "--ring", "rigid"], "--ring rigid"),
    (["modes", *ANNULUS, "--crack-depth", "0.003"], "--crack-depth"),
    (["modes", *ANNULUS, "--torque", "500"], "--torque"),
    (["modes", "--preset", "raba118", "--E", "1e9"], "--E"),
    (["modes", "--design", "hub4", "--nu", "0.2", "--density", "7000"], "--nu, --density"),
    (["modes", "--ring", "rigid", "--torque", "500"], "--torque"),
    (["modes", "--ring", "rigid", "--closure-gap", "1e-6"], "--closure-gap"),
    (["modes", "--ring", "rigid", "--mesh", "fine"], "--mesh"),
    (["modes", "--ring", "rigid", "--open"], "--open"),
    (["modes", "--torque", "500"], "--torque"),
    (["modes", "--crack-depth", "0.003", "--closed", "--torque", "500"], "--closed"),
    (["modes", "--crack-depth", "0.003", "--torque", "0"], "--torque = 0"),
    (["modes", "--crack-depth", "0.003", "--closure-gap=-1e-6"], "--closure-gap"),
    (["modes", "--crack-depth", "0.003", "--mounting", "free"], "--mounting free"),
    (["modes", "--crack-depth", "0.003", "--open", "--closed"], "--closed and --open"),
    (["modes", "--open"], "--open"),
])
def test_flags_that_do_not_apply_are_refused(argv, words):
    code, _, err = run_cli(argv)
    assert code == 2, f"{argv}: exit 2 expected"
    assert err.count("\n") == 1 and words in err, err


@pytest.mark.slow
def test_intact_ring_prints_the_crack_studys_numbers(tmp_path, monkeypatch):
    """``hubvib modes --ring elastic`` uses the crack study's ring (``ElasticScene``): its
    intact spectrum at tooth 0 is the study's intact case's ``on`` spectrum, exactly."""
    from hubvib.design.presets import preset_design
    from hubvib.elastic.cases import elastic_case
    from hubvib.elastic.options import ElasticScene
    from hubvib.elastic.rest import rest_stiffness

    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path))
    code, data, _ = run_cli(["modes", "--preset", "raba118", "--json"])
    assert code == 0 and data["mesh"] == "study"
    design = preset_design("raba118")
    scene = ElasticScene()
    case = elastic_case(design, None, scene, rest_stiffness(design, scene.options.rest))
    np.testing.assert_allclose([m["frequency_hz"] for m in data["modes"]],
                               case.on.frequency_hz, rtol=1e-12,
                               err_msg="one mesh, one number: modes vs the study's intact case")


@pytest.mark.slow
def test_record_json(tmp_path, monkeypatch):
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path))
    code, data, _ = run_cli(["modes", "--preset", "raba118", "--crack-depth", "0.003", "--json"])
    assert code == 0
    states = data["crack_state"]
    assert len(states) == 22 and [s["carrier_tooth"] for s in states] == list(range(22)), (
        "Raba: z = 64, N = 3: planet 1 on teeth 0..21 over one pitch")
    assert data["open_share"] == pytest.approx(np.mean([s["open_length_m"] > 0
                                                        for s in states]))
    assert data["torque_N_m"] == 1000.0 and data["closure_gap_m"] == 0.0
    for m in data["modes"]:
        if m["frequency_hz"] is None:
            continue
        assert m["instantaneous_min_hz"] <= m["frequency_hz"] <= m["instantaneous_max_hz"], (
            "the record's frequency lies within the instantaneous range")
        assert set(m) >= {"intact_hz", "frequency_slip_hz", "regime"}


def test_mode_files_with_a_loaded_crack_are_refused(tmp_path, capsys):
    """The loaded crack is a spectrum over the pitch: ``--out``/``--render`` (files of one
    ring's modes) need the faces fixed, said in one line, exit 2, nothing written."""
    from hubvib.cli import main

    out = tmp_path / "out"
    code = main(["modes", "--preset", "raba118", "--ring", "elastic", "--crack-depth",
                 "0.003", "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "--open or --closed" in err[0], err
    assert not out.exists()
