"""One number per quantity, named by its method: ``design check``, ``stiffness`` and
``spectrum`` print each stiffness once per meaning, as ``key (method)``, and one name holds
one value in every output."""
import json
import tomllib

import pytest

from hubvib.reducer import parse_design
from hubvib.reducer.stages import DESIGN_TABLE, ISO_MESH, ISO_SINGLE
from hubvib.cli import main

from tests.helpers.design_demo import DEMO_TOML

#: the demo stage with both bearings, and a c_p of its own in the lumped table
BEARINGS_TOML = DEMO_TOML + """[design.bearings]
planet = { rollers = 16, roller_length = 0.03 }
carrier = { rollers = 40, roller_length = 0.02, load = 25e3 }
[design.lumped]
c_ru = 1e6
c_r = 1e8
c_su = 1e6
c_cu = 1e6
c_p = 3.7497e9
"""


@pytest.fixture
def design_file(tmp_path):
    path = tmp_path / "bearings.toml"
    path.write_text(BEARINGS_TOML)
    return path


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_design_check_mesh_stiffness_is_iso_c_gamma_b(capsys, design_file):
    """The lumped c_sp, c_rp a design gives are ISO 6336-1's mean mesh stiffness
    c_gamma_alpha b, the quantity ``stiffness`` prints as ``ISO 6336-1 c_gamma b`` beside the
    FE mean over the mesh cycle (the single-pair c' b is a different quantity)."""
    from hubvib.detection.mesh_stiffness import iso_c_rp

    info = _json(capsys, ["design", "check", str(design_file), "--json"])
    design = parse_design(tomllib.loads(BEARINGS_TOML)["design"])
    assert info["lumped"]["c_rp"]["method"] == ISO_MESH
    assert info["lumped"]["c_rp"]["value"] == pytest.approx(iso_c_rp(design), rel=1e-12)
    assert info["lumped_from_geometry"]["c_rp"] == pytest.approx(iso_c_rp(design), rel=1e-12)
    assert info["named_values"][f"c_rp ({ISO_MESH})"] == info["lumped"]["c_rp"]["value"]


def test_design_check_prints_each_field_once_with_the_value_used(capsys, design_file):
    assert main(["design", "check", str(design_file)]) == 0
    lines = capsys.readouterr().out.splitlines()
    for key in ("c_sp", "c_rp", "c_p", "c_c", "c_ru", "d_s"):
        rows = [line for line in lines if line.split()[:1] == [key]]
        assert len(rows) == 1, f"{key}: {rows}"
    [c_p] = [line for line in lines if line.split()[:1] == ["c_p"]]
    assert "3.7497e+09 N/m" in c_p and DESIGN_TABLE in c_p, c_p
    assert "Palmgren tangent at 13.14 kN gives 3.87803e+09 N/m" in c_p, c_p
    [c_sp] = [line for line in lines if line.split()[:1] == ["c_sp"]]
    assert c_sp.endswith(ISO_MESH), c_sp


def test_spectrum_names_each_spring_as_design_check_does(capsys, design_file):
    check = _json(capsys, ["design", "check", str(design_file), "--json"])["lumped"]
    springs = _json(capsys, ["spectrum", "--design", str(design_file), "--json"])["stiffness"]
    for key in ("c_sp", "c_rp", "c_p", "c_c", "c_ru", "c_r", "c_su", "c_cu"):
        assert springs[key]["method"] == check[key]["method"], key
        assert springs[key]["value_N_m"] == pytest.approx(check[key]["value"], rel=1e-12), key
    assert main(["spectrum", "--design", str(design_file)]) == 0
    out = capsys.readouterr().out
    assert f"c_sp 5.49207e+08 ({ISO_MESH})" in out and f"c_p 3.7497e+09 ({DESIGN_TABLE})" in out


def test_spectrum_names_a_set_value_by_its_flag(capsys):
    springs = _json(capsys, ["spectrum", "--set", "c_ru=2e6", "--json"])["stiffness"]
    assert springs["c_ru"] == {"value_N_m": 2e6, "method": "--set"}
    assert springs["c_sp"]["method"] == DESIGN_TABLE


@pytest.mark.slow
def test_one_name_one_value_in_design_check_and_stiffness(capsys, design_file, monkeypatch,
                                                          tmp_path):
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    check = _json(capsys, ["design", "check", str(design_file), "--json"])
    stiffness = _json(capsys, ["stiffness", "--design", str(design_file), "--json"])
    named = stiffness["named_values"]["intact"]
    common = set(check["named_values"]) & set(named)
    assert {f"c_sp ({ISO_MESH})", f"c_rp ({ISO_MESH})", "c_p (Palmgren tangent at 13.14 kN)",
            "c_c (Palmgren tangent at 25 kN)"} <= common, sorted(common)
    for name in common:
        assert named[name] == pytest.approx(check["named_values"][name], rel=1e-12), name
    rows = stiffness["cases"]["intact"]
    assert check["lumped_from_geometry"]["c_sp"] == pytest.approx(
        rows["c_sp"]["iso_c_gamma_N_m"], rel=1e-12), "design check's c_sp is ISO c_gamma b"
    assert named[f"c_sp ({ISO_SINGLE})"] != pytest.approx(named[f"c_sp ({ISO_MESH})"])
    assert stiffness["lumped_from_design_table"]["c_p"] == 3.7497e9
