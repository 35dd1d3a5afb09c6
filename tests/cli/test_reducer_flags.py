"""A command is told its reducer once: ``--preset`` with ``--design`` is refused naming both,
and what the outputs say about the reducer comes from the input actually used (the design's
sun torque, the design's or scene's c_ru)."""
import contextlib
from types import SimpleNamespace

import numpy as np
import pytest

from hubvib.cli import main

from tests.helpers.design_demo import DEMO_TOML


@pytest.fixture
def design_file(tmp_path):
    path = tmp_path / "demo.toml"
    path.write_text(DEMO_TOML + "[design.lumped]\nc_ru = 1e6\nc_r = 1e8\nc_su = 1e6\n"
                    "c_cu = 1e6\nc_p = 1e9\nc_c = 1e9\n")
    return path


@pytest.mark.parametrize("argv", [
    ["spectrum"], ["shift", "--to", "c_ru", "1e5"], ["stiffness"],
    ["mesh", "ring", "--out", "OUT"], ["crack-path", "--steps", "1", "--out", "OUT"]],
    ids=["spectrum", "shift", "stiffness", "mesh", "crack-path"])
def test_preset_with_design_is_refused_naming_both(argv, design_file, tmp_path, capsys):
    out = tmp_path / "out"
    argv = [str(out) if a == "OUT" else a for a in argv]
    assert main([*argv, "--preset", "raba118", "--design", str(design_file)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("hubvib: error: "), err
    assert "--preset raba118" in err and f"--design {design_file}" in err, err
    assert not out.exists(), "nothing written"


def test_either_flag_alone_still_names_the_reducer(design_file, capsys):
    assert main(["spectrum", "--design", str(design_file), "--json"]) == 0
    assert main(["spectrum", "--preset", "hub4", "--json"]) == 0
    assert main(["spectrum", "--json"]) == 0
    capsys.readouterr()


def test_fe_picture_names_the_design_sun_torque_not_an_assumption(monkeypatch, tmp_path):
    """The loaded ring's caption says where its torque comes from (every design's own sun
    torque) and claims no ASSUMED value the design did not assume."""
    pytest.importorskip("pyvista")
    from hubvib.render import fe

    texts = []
    monkeypatch.setattr(fe, "_label", lambda plotter, text: texts.append(text))
    monkeypatch.setattr(fe, "plotter_for", lambda: contextlib.nullcontext(
        SimpleNamespace(add_mesh=lambda *a, **k: None)))
    monkeypatch.setattr(fe, "_picture", lambda plotter, path, draw, centre=None:
                        (draw(plotter), path)[1])
    points = np.array([[0.1, 0.0], [0.0, 0.1], [-0.1, 0.0]])
    fields = fe.RingFields(points, np.array([[0, 1, 2]]), 1e-6 * points, np.ones(3),
                           np.zeros((0, 3, 2)), np.zeros(0), None, 2400.0, "demo ring, intact")
    fe.render_fe(fields, tmp_path)
    [title] = texts
    assert "ring torque 2400 N m (from the design's sun torque)" in title, title
    assert "ASSUMED" not in title, title


def _scene(text):
    from hubvib.studies.scene import parse_scene

    return parse_scene(text + "\n[crack]\ndepths = [0.0]\n", "x")


@pytest.mark.parametrize("text, c_ru, c_r", [
    ('[design]\npreset = "hub4"', "the lumped table of design 'hub4'",
     "the lumped table of design 'hub4'"),
    ('[reducer]\npreset = "raba118"', "the raba118 preset's table", "the raba118 preset's table"),
    ('[reducer]\npreset = "raba118"\n[reducer.parameters]\nc_ru = 2e6',
     "the scene's [reducer.parameters]", "the raba118 preset's table"),
], ids=["design", "preset", "override"])
def test_ring_support_sentence_names_where_c_ru_comes_from(text, c_ru, c_r):
    from hubvib.reports.detection_sections import mounting_sentence

    scene = _scene(text)
    sources = {key: scene.lumped_source(key) for key in ("c_ru", "c_r")}
    assert sources == {"c_ru": c_ru, "c_r": c_r}
    p = scene.params
    model = SimpleNamespace(apply="series", params=p, c_ru=[p.c_ru], c_r=[p.c_r],
                            c_ru_mount=10 * p.c_ru, c_r_mount=10 * p.c_r)
    sentence = mounting_sentence(model, sources)
    assert f"c_ru = {p.c_ru:.4g} N/m ({c_ru})" in sentence, sentence
    assert "preset's c_ru" not in sentence and "preset's c_r" not in sentence, sentence


def test_scene_keys_do_not_call_a_design_value_the_presets():
    from hubvib.studies.crack_table import SCHEMA

    docs = " ".join(str(field.doc) for field in SCHEMA.fields)
    assert "preset's c_ru" not in docs, docs


def test_preset_that_contradicts_the_params_file_is_refused(tmp_path, capsys):
    params = tmp_path / "p.toml"
    params.write_text('preset = "hub4"\nc_ru = 2e6\n')
    assert main(["spectrum", "--preset", "raba118", "--params", str(params)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--preset raba118" in err and str(params) in err, err
    assert "'hub4'" in err, err
    assert main(["spectrum", "--preset", "hub4", "--params", str(params), "--json"]) == 0
    capsys.readouterr()


def test_a_design_name_prints_as_given():
    """A design named in lower case (or any case) keeps its spelling in the report's source
    sentence: no capitalisation, no doubled quote before a possessive."""
    scene = _scene('[design]\npreset = "hub4"\n[reducer.parameters]\nc_su = 1e8')
    text = scene.lumped_source("c_ru")
    assert "'hub4'" in text and "Hub4" not in text and "''" not in text, text
