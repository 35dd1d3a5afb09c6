"""The reducer design: file parsing, every assembly rule, derived fields, scenes and commands."""
import json
import math

import pytest

from hubvib.cli import main
from hubvib.reducer import parse_design
from hubvib.design import DesignError, preset_design
from hubvib.reducer.stages import centre_distances, derived_lumped_fields, lumped_parameters
from tests.helpers.design_demo import DEMO_TOML, demo

def test_demo_assembles_with_iso_21771_geometry():
    design = parse_design(demo())
    a_sp, a_rp = centre_distances(design)
    # ISO 21771: inv a_w = inv a + 2 tan a (x1 + x2) / (z1 + z2); a = m z_sum cos a / (2 cos a_w)
    inv = math.tan(math.radians(20)) - math.radians(20) + 2 * math.tan(math.radians(20)) * 0.4 / 51
    lo, hi = 0.1, 0.6
    for _ in range(60):  # bisection of inv(a_w) = tan a_w - a_w
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if math.tan(mid) - mid < inv else (lo, mid)
    expected = 2.5e-3 * 51 / 2 * math.cos(math.radians(20)) / math.cos(lo)
    assert a_sp == pytest.approx(expected, rel=1e-12), "ISO 21771 working centre distance"
    assert a_rp == pytest.approx(a_sp, abs=1e-12)
    fields = derived_lumped_fields(design)
    assert fields["d_s"] == pytest.approx(2.5e-3 * 20 * math.cos(math.radians(20)), rel=1e-14)
    assert fields["d_c"] == pytest.approx(2 * a_sp, rel=1e-14)


def test_raba_preset_reproduces_the_papers_geometry():
    """The paper's table (seed 004): base diameters 79.404 / 58.026 / 195.45 mm, 25.28 deg."""
    fields = derived_lumped_fields(preset_design("raba118"), skip={"m_s"})
    for key, paper in (("d_s", 79.404e-3), ("d_p", 58.026e-3), ("d_r", 195.45e-3)):
        assert fields[key] == pytest.approx(paper, rel=5e-5), f"{key} vs the paper's table"
    assert math.degrees(fields["alpha_s"]) == pytest.approx(25.28, abs=1e-12)
    assert math.degrees(fields["alpha_r"]) == pytest.approx(25.28, abs=1e-12)


@pytest.mark.parametrize("changes, message", [
    ({"n_planets": 4}, r"\(z_s \+ z_r\) / N an integer.*102"),
    ({"ring.shift": 0.5}, "working centre distances differ.*ring.shift = 0.600000"),
    ({"planet_angles_deg": [0, 100, 240]}, "planet 2 .* does not assemble"),
    ({"n_planets": 6}, "neighbouring planets collide"),
    ({"sun.shift": -0.6, "ring.shift": -0.2}, "undercuts the 20-tooth gear"),
    ({"planet.shift": 1.5, "ring.shift": 3.2}, "ring.shift = 3.2"),
    ({"sun.shift": 1.2, "ring.shift": 1.6}, "pointed tooth"),
], ids=["assembly", "centre-distance", "unequal-angles", "planet-gap", "undercut", "shift-range",
        "pointed"])
def test_each_assembly_rule_refuses_a_design_that_breaks_only_it(changes, message):
    with pytest.raises(DesignError, match=message):
        parse_design(demo(**changes))


def test_contact_ratio_rule():
    """A long-addendum-free, low-tooth stage: tip shortened until the contact ratio < 1."""
    from hubvib.reducer import assembly

    design = parse_design(demo())
    # the rule itself: the demo's ratios are > 1, so it passes; a forged ratio below 1 fails
    ratios = assembly.summary(design)
    assert ratios["contact_ratio_sun_planet"] > 1 and ratios["contact_ratio_ring_planet"] > 1
    from hubvib.fem import mesh_cycle

    class Short:
        def __init__(self, first, second):
            self.contact_ratio = 0.95

    assert assembly.GearPair is mesh_cycle.GearPair  # the rule uses the FE stage's pair
    original = assembly.GearPair
    assembly.GearPair = Short
    try:
        with pytest.raises(DesignError, match="contact ratio 0.9500; allowed >= 1"):
            assembly.check_assembly(design)
    finally:
        assembly.GearPair = original


def test_unequal_angles_that_assemble_are_accepted_and_proposed():
    with pytest.raises(DesignError, match=r"planet_angles_deg = \[0.000000, 91.764706, "
                                          r"180.000000, 268.235294\]"):
        parse_design(demo(n_planets=4))
    design = parse_design(demo(n_planets=4, planet_angles_deg=[0, 91.76470588235294, 180,
                                                               268.2352941176471]))
    assert not design.equally_spaced
    assert len(lumped_parameters(design.__class__(**{**design.__dict__, "lumped": {
        "c_ru": 1e6, "c_r": 1e8, "c_su": 1e6, "c_cu": 1e6, "c_p": 1e8, "c_c": 1e8}})).theta) == 4


@pytest.mark.parametrize("changes, message", [
    ({"module": -1e-3}, r"design.module = -0.001; allowed: a number in \(0, 0.05\]"),
    ({"module": float("nan")}, "design.module = nan"),
    ({"module": "2.5"}, "design.module = '2.5'"),
    ({"n_planets": 2.5}, "design.n_planets = 2.5; allowed: an integer in 1..12"),
    ({"n_planets": True}, "design.n_planets = True"),
    ({"face_width": None}, "missing required key.*design.face_width"),
    ({"colour": "red"}, "unknown key.*design.colour"),
    ({"sun.teeth": 0}, "design.sun.teeth = 0"),
    ({"sun.spin": 1}, "design.sun.spin"),
    ({"ring.mass": 3.0}, "exactly one of rim_thickness"),
    ({"material.nu": 0.5}, "design.material.nu = 0.5"),
    ({"load.sun_torque": 0}, "design.load.sun_torque = 0"),
    ({"supports.count": -1}, "design.supports.count = -1"),
    ({"lumped": {"c_xx": 1.0}}, "unknown key design.lumped.c_xx"),
    ({"lumped": {"c_ru": -1.0}}, "design.lumped.c_ru = -1.0"),
    ({"sun": 5}, "design.sun = 5; allowed: a table"),
])
def test_bad_keys_name_the_key_and_the_range(changes, message):
    with pytest.raises(DesignError, match=message):
        parse_design(demo(**changes))


def test_design_check_command_accepts_the_example_and_refuses_four_planets(tmp_path, capsys):
    good = tmp_path / "demo.toml"
    good.write_text(DEMO_TOML)
    assert main(["design", "check", str(good), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["contact_ratio_sun_planet"] > 1.2 and info["lumped_missing"]
    bad = tmp_path / "demo4.toml"
    bad.write_text(DEMO_TOML.replace("n_planets = 3", "n_planets = 4"))
    assert main(["design", "check", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "(z_s + z_r) / N an integer" in err
    for text in ("not toml [", "[other]\nx = 1\n", "\xff\xfe"):
        bad.write_bytes(text.encode("latin-1"))
        assert main(["design", "check", str(bad)]) == 2
        assert str(bad) in capsys.readouterr().err
    assert main(["design", "check", str(tmp_path / "missing.toml")]) == 2
    assert main(["design", "check", str(tmp_path)]) == 2


def test_spectrum_from_a_design_needs_the_mountings(tmp_path, capsys):
    good = tmp_path / "demo.toml"
    good.write_text(DEMO_TOML)
    assert main(["spectrum", "--design", str(good)]) == 2
    assert "lumped.c_ru" in capsys.readouterr().err
    good.write_text(DEMO_TOML + "[design.lumped]\nc_ru = 1e7\nc_r = 1e8\nc_su = 1e7\n"
                    "c_cu = 1e7\nc_p = 1e9\nc_c = 1e9\n")
    assert main(["spectrum", "--design", str(good), "--json"]) == 0
    modes = json.loads(capsys.readouterr().out)["modes"]
    assert len(modes) == 18 and all(m["omega_rad_s"] > 0 for m in modes)


def test_hub4_preset_is_the_lumped_preset_and_has_four_planets():
    from hubvib.reducer import lumped_preset
    from hubvib.lumped import natural_modes

    params = lumped_preset("hub4")
    assert len(params.theta) == 4
    spectrum = natural_modes(params)
    # Lin & Parker: N = 4 equally spaced planets give N - 3 = 1 planet mode per group
    assert "planet" in spectrum.kind


def test_scene_contradicting_its_design_is_refused():
    from hubvib.studies.scene import SceneError, parse_scene

    crack = "[crack]\ndepths = [0.0, 0.003]\n"
    with pytest.raises(SceneError, match="5 planets, but the design 'raba118' has "
                                         "n_planets = 3"):
        parse_scene("[reducer]\npreset = \"raba118\"\n[reducer.parameters]\nn_planets = 5\n"
                    + crack, "x")
    with pytest.raises(SceneError, match="d_r = 0.2, but the design 'raba118' gives d_r = "
                                         "0.195456"):
        parse_scene("[reducer]\npreset = \"raba118\"\n[reducer.parameters]\nd_r = 0.2\n"
                    + crack, "x")
    with pytest.raises(SceneError, match="either \\[reducer\\] preset or \\[design\\]"):
        parse_scene("[reducer]\npreset = \"raba118\"\n[design]\npreset = \"hub4\"\n", "x")
    scene = parse_scene("[design]\npreset = \"hub4\"\n" + crack, "x")
    assert scene.crack.design.name == "hub4" and len(scene.params.theta) == 4


def test_scene_design_file_is_relative_to_the_scene(tmp_path):
    from hubvib.studies.scene import load_scene

    (tmp_path / "demo.toml").write_text(DEMO_TOML + "[design.lumped]\nc_ru = 1e7\nc_r = 1e8\n"
                                        "c_su = 1e7\nc_cu = 1e7\nc_p = 1e9\nc_c = 1e9\n")
    (tmp_path / "scene.toml").write_text("[design]\nfile = \"demo.toml\"\n[crack]\n"
                                         "depths = [0.0, 0.002]\n")
    scene = load_scene(tmp_path / "scene.toml")
    assert scene.design.name == "demo" and scene.crack.design.ring.teeth == 82


@pytest.mark.parametrize("depth", ["-0.005", "nan", "inf"])
def test_stiffness_refuses_a_crack_depth_that_is_not_a_depth(depth, capsys):
    """It used to exit 0 with the intact ring only."""
    assert main(["stiffness", f"--crack-depth={depth}"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--crack-depth" in err and "allowed" in err


def test_scene_refusals_name_the_file_or_the_key(tmp_path, capsys):
    """A non-UTF-8 scene names its file; 5000 depths and a crack
    scene's ignored [study] values are refused before any FE work."""
    bad = tmp_path / "latin.toml"
    bad.write_bytes("# Zürich\n[crack]\ndepths = [0.0]\n".encode("latin-1"))
    assert main(["run", str(bad), "--out", str(tmp_path / "o1")]) == 2
    assert str(bad) in capsys.readouterr().err
    many = tmp_path / "many.toml"
    many.write_text("[crack]\ndepths = [" + ", ".join(f"{i * 1e-5:g}" for i in range(5000))
                    + "]\n")
    assert main(["run", str(many), "--out", str(tmp_path / "o2")]) == 2
    assert "allowed at most 64" in capsys.readouterr().err
    ignored = tmp_path / "ignored.toml"
    ignored.write_text("[crack]\ndepths = [0.0, 0.003]\n[study]\nparameter = \"c_ru\"\n"
                       "values = [1e5]\n")
    assert main(["run", str(ignored), "--out", str(tmp_path / "o3")]) == 2
    assert "[study] parameter and values are for a lumped sweep" in capsys.readouterr().err
    assert not any((tmp_path / name).exists() for name in ("o1", "o2", "o3"))
