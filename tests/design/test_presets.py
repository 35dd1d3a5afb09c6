"""One preset registry (hubvib.design.PRESETS).  A preset registered at run time
(here a copy of hub4 under another name) works in ``design check``, ``spectrum``,
``mesh``, ``stiffness`` and a scene with no other edit, and gives hub4's numbers."""
import dataclasses
import json

import numpy as np
import pytest

from hubvib.reducer import bearing_stiffness, lumped_preset, mass_properties
from hubvib.cli import main
from hubvib.design import PRESETS, DesignError, preset_design, register_preset
from hubvib.design.presets import hub4
from hubvib.lumped import natural_modes

NAME = "hub4_registry_copy"


@pytest.fixture
def copy_of_hub4():
    register_preset(NAME, lambda: dataclasses.replace(hub4(), name=NAME))
    yield NAME
    PRESETS.pop(NAME)


def _json(capsys, argv):
    assert main(argv) == 0, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)


@pytest.mark.slow
def test_registered_preset_runs_in_design_check_spectrum_mesh_and_a_scene(
        copy_of_hub4, capsys, tmp_path):
    original = _json(capsys, ["design", "check", "hub4", "--json"])
    copy = _json(capsys, ["design", "check", NAME, "--json"])
    assert copy.pop("name") == NAME and original.pop("name") == "hub4"
    assert copy == original, "design check of the copy vs hub4 (same design, exact)"

    spectrum = [_json(capsys, ["spectrum", "--preset", name, "--json"]) for name in ("hub4", NAME)]
    assert spectrum[0] == spectrum[1], "spectrum of the copy vs hub4 (exact)"

    info = _json(capsys, ["mesh", "sun", "--preset", NAME, "--size", "4e-3",
                          "--out", str(tmp_path / "mesh"), "--json"])
    assert abs(info["relative_error"]) < 1e-5, "P2 area vs the exact area (closed form)"
    assert info["mass_kg"] == pytest.approx(mass_properties(hub4())["m_s"], rel=1e-4), (
        "meshed sun mass vs the exact section area x width x density (build.mass_properties)")

    scene = tmp_path / "copy.toml"
    scene.write_text(f'[reducer]\npreset = "{NAME}"\n\n[study]\nparameter = "c_ru"\n'
                     'values = [4e7]\n\n[output]\nplots = false\n')
    assert main(["run", str(scene), "--out", str(tmp_path / "run")]) == 0
    data = json.loads((tmp_path / "run" / "results.json").read_text())
    expected = natural_modes(lumped_preset("hub4")).omega
    got = [row["omega_rad_s"] for row in data["baseline_spectrum"]]
    np.testing.assert_allclose(got, expected, rtol=1e-12,
                               err_msg="scene on the copy vs hub4's lumped model (natural_modes)")


def test_unknown_preset_is_refused_with_the_registered_names(capsys):
    with pytest.raises(SystemExit) as stop:  # argparse: the registered names are the choices
        main(["spectrum", "--preset", "no_such_preset"])
    assert stop.value.code == 2 and "'hub4', 'raba118'" in capsys.readouterr().err
    with pytest.raises(DesignError, match="unknown design preset 'no_such_preset'; allowed: "
                                          "raba118, hub4"):
        preset_design("no_such_preset")
    with pytest.raises(DesignError, match="already registered"):
        register_preset("raba118", hub4)


@pytest.mark.slow
def test_registered_preset_runs_in_stiffness(copy_of_hub4, capsys):
    intact = _json(capsys, ["stiffness", "--preset", NAME, "--json"])["cases"]["intact"]
    bearings = bearing_stiffness(hub4())
    for key in ("c_p", "c_c"):
        assert intact[key]["value_N_m"] == bearings[key]["tangent_N_m"], (
            key, "Palmgren tangent stiffness of hub4's bearings (build.bearing_stiffness)")
    for key in ("c_sp", "c_rp"):
        ratio = intact[key]["value_N_m"] / intact[key]["iso_c_gamma_N_m"]
        assert 1 / 2 < ratio < 2, (key, ratio, "ISO 6336-1 c_gamma_alpha b")
    for key in ("c_ru", "c_r"):
        assert intact[key]["error_N_m"] < 0.01 * intact[key]["value_N_m"], (
            key, "FE estimate within 1 % of its fine-minus-coarse error")
