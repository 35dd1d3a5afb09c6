"""Off-screen renders of lumped and FE mode shapes and of the loaded FE ring: real images,
distinct per mode, repeatable."""

from dataclasses import replace

import numpy as np
import pytest

pv = pytest.importorskip("pyvista")
imageio = pytest.importorskip("imageio")

from hubvib.render.modes import render_mode  # noqa: E402
from hubvib.reducer import lumped_preset  # noqa: E402
from hubvib.lumped import natural_modes  # noqa: E402

PARAMS = lumped_preset("raba118")
SPECTRUM = natural_modes(PARAMS)


def _image(path):
    return np.asarray(imageio.v3.imread(path), dtype=float)


@pytest.mark.slow
def test_mode_renders_are_real_distinct_and_repeatable(tmp_path):
    first = render_mode(PARAMS, SPECTRUM, 0, tmp_path / "a")[0]
    other = render_mode(PARAMS, SPECTRUM, 4, tmp_path / "a")[0]
    again = render_mode(PARAMS, SPECTRUM, 0, tmp_path / "b")[0]
    a, b, c = _image(first), _image(again), _image(other)
    assert a.shape[:2] == (900, 900)
    assert a.std() > 20  # not blank: bodies on a white background
    # sign-fixed modes: the same picture twice, and nothing of mode 5 (actors, camera)
    # left on the plotter drawn again
    np.testing.assert_array_equal(a, b)
    assert np.abs(a - c).mean() > 1.0  # a rotational and a translational mode differ


@pytest.mark.slow
def test_gif_and_multiblock_on_request(tmp_path):
    files = render_mode(PARAMS, SPECTRUM, 2, tmp_path, gif=True, vtm=True)
    assert [f.suffix for f in files] == [".png", ".gif", ".vtm"]
    frames = imageio.v3.imread(files[1], index=None)
    assert len(frames) == 24 and np.abs(frames[0] - frames[6]).mean() > 0.1  # it moves
    blocks = pv.read(files[2])
    assert {"sun", "ring", "carrier", "planet 1"} <= set(blocks.keys())
    # the ring is translated by the mode (translational mode 3): its centre moved
    assert np.hypot(*blocks["ring"].center[:2]) > 1e-4


@pytest.fixture(scope="module")
def cracked_ring_fields():
    pytest.importorskip("gmsh")
    pytest.importorskip("skfem")
    from hubvib.render.fe import ring_fields
    from hubvib.meshing.levels import scaled_options
    from hubvib.reducer import raba118
    from hubvib.meshing.crack import Crack

    # scale 8 (was 4): every property checked below still shows with margin (near-tip
    # stress 21x the intact ring's at 8, 33x at 4; softer; lower first mode)
    return ring_fields(raba118.design(), Crack(0, 0.012), scaled_options(8.0), modes=2)


@pytest.mark.slow
def test_fe_renders_are_real_distinct_and_repeatable(tmp_path, cracked_ring_fields,
                                                     monkeypatch):
    import hubvib.render.fe as fe_render
    from hubvib.render.fe import render_fe
    from hubvib.render.modes import plotter_for

    fields = cracked_ring_fields
    files = render_fe(fields, tmp_path / "a", vtu=True)
    assert [f.name for f in files] == ["fe_ring_loaded.png", "fe_crack_tip.png",
                                       "fe_ring_mode_01_clamped.png",
                                       "fe_ring_mode_02_clamped.png", "fe_ring.vtu"]
    loaded, tip, mode1, mode2 = (_image(f) for f in files[:4])
    for image in (loaded, tip, mode1, mode2):
        assert image.shape[:2] == (900, 900) and image.std() > 20
    assert np.abs(mode1 - mode2).mean() > 1.0 and np.abs(loaded - mode1).mean() > 1.0
    # one plotter draws them all: each picture must be the one a plotter of its own draws
    # (no camera, colour bar, label or length bar of the picture before may stay)
    reused = fe_render._picture

    def _picture_of_its_own(plotter, path, draw, centre=None):
        with plotter_for() as own:
            return reused(own, path, draw, centre)

    monkeypatch.setattr(fe_render, "_picture", _picture_of_its_own)
    alone = render_fe(fields, tmp_path / "b")
    for shared, own in zip(files[:4], alone):
        np.testing.assert_array_equal(_image(own), _image(shared), err_msg=shared.name)
    # The close-up's title sits on a light box (it was black on dark
    # navy: 0 % light pixels there) and a labelled length bar sits at the lower left
    light, dark = tip[..., :3].min(axis=2) > 200, tip[..., :3].max(axis=2) < 60
    assert light[:22, :470].mean() > 0.4 and dark[:22, :470].mean() > 0.03, \
        "crack-tip title: light box with dark text expected in the upper-left strip"
    assert light[785:840, 60:250].mean() > 0.03 and dark[785:840, 60:250].mean() > 0.01, \
        "crack-tip length scale: white bar and labelled box expected at the lower left"
    grid = pv.read(files[-1])
    np.testing.assert_allclose(grid.point_data["von Mises [Pa]"], fields.von_mises)
    assert grid.point_data["displacement [m]"].shape == (len(fields.points), 3)


@pytest.mark.slow
def test_fe_ring_fields_physics(cracked_ring_fields):
    from hubvib.render.fe import ring_fields
    from hubvib.meshing.levels import scaled_options
    from hubvib.reducer import raba118

    fields = cracked_ring_fields
    intact = ring_fields(raba118.design(), None, scaled_options(8.0), modes=1)
    # LEFM: the stress is singular at the crack tip; intact, the rim there is barely loaded
    near = lambda f: f.von_mises[np.hypot(*(f.points - fields.crack_tip).T) < 3e-3].max()
    assert near(fields) > 5 * near(intact)
    # an open crack: the ring is softer, the same torque turns it further
    assert np.abs(fields.displacement).max() > np.abs(intact.displacement).max()
    assert fields.mode_hz[0] < intact.mode_hz[0]
    assert np.isfinite(fields.von_mises).all() and fields.von_mises.min() >= 0
    assert np.all(np.diff(fields.mode_hz) > 0) and fields.mode_hz[0] > 1e3


def test_fe_modes_sign_fixed():
    """Two solves of the same model return the same shapes, largest entry positive."""
    pytest.importorskip("skfem")
    from hubvib.fem.elasticity import plane_model
    from hubvib.fem.modal import lowest_modes
    from hubvib.meshing.annulus import annulus_mesh

    model = plane_model(annulus_mesh(0.08, 0.1, 8e-3, 2), thickness=0.01)
    a, b = (lowest_modes(model, 3, ["inner"]) for _ in range(2))
    np.testing.assert_array_equal(a.shapes, b.shapes)
    for shape in a.shapes.T:
        assert shape[np.argmax(np.abs(shape))] > 0


@pytest.mark.slow
def test_fe_colour_bar_text_is_readable_and_clear_of_the_ticks(tmp_path, cracked_ring_fields,
                                                               monkeypatch):
    """Title and tick labels of every FE picture's colour bar: contrast of at least 4.5
    (WCAG) against whatever is drawn behind them (the crack-tip close-up puts the bar over
    dark blue mesh), and the title clear of the top tick label."""
    from dataclasses import replace

    import hubvib.render.fe as fe_render
    from tests.helpers.figure_checks import bar_title_over_labels, scalar_bar_texts, unreadable_bar_text

    fields = replace(cracked_ring_fields, mode_shapes=cracked_ring_fields.mode_shapes[:1],
                     mode_hz=cracked_ring_fields.mode_hz[:1])
    bars = []
    save = fe_render.save_picture

    def checked(plotter, path):
        bars.append(scalar_bar_texts(plotter))
        save(plotter, path)

    monkeypatch.setattr(fe_render, "save_picture", checked)
    files = fe_render.render_fe(fields, tmp_path)
    assert [f.name for f in files] == ["fe_ring_loaded.png", "fe_crack_tip.png",
                                       "fe_ring_mode_01_clamped.png"]
    assert [len(found) for found in bars] == [1, 1, 1], "one colour bar per picture"
    wrong = [f"{path.name}: {problem}" for path, found in zip(files, bars)
             for problem in unreadable_bar_text(found) + bar_title_over_labels(found)]
    assert not wrong, "\n".join(wrong)


@pytest.mark.slow
def test_fe_ring_modes_on_the_foundation_are_the_elastic_rings(tmp_path, monkeypatch):
    """On the report's mounting (a foundation sized to the preset's c_r, c_ru) the FE ring's
    pictured modes are its own lowest: the n = 2 pair and the n = 3 pair the pads split,
    as docs/elastic_ring.md measured them (1232.4, 2685.9 / 2874.3 Hz on the default mesh;
    a coarser mesh here, 1 %); clamped, its first is 8051.6 Hz (1 %).  Each picture has
    one colour bar and its file names the mounting, which its caption reads back."""
    pytest.importorskip("gmsh")
    pytest.importorskip("skfem")
    import hubvib.render.fe as fe_render
    from hubvib.meshing.levels import scaled_options
    from hubvib.reducer import raba118
    from hubvib.render.captions import caption

    on = fe_render.ring_fields(raba118.design(), None, scaled_options(4.0), modes=4,
                               mounting="foundation")
    np.testing.assert_allclose(on.mode_hz, [1232.4, 1232.4, 2685.9, 2874.3], rtol=0.01,
                               err_msg="vs docs/elastic_ring.md, ring on the mounting")
    assert on.mode_diameters == (2, 2, 3, 3)
    assert "Winkler foundation" in on.mounting_words
    clamped = fe_render.ring_fields(raba118.design(), None, scaled_options(4.0), modes=1)
    assert clamped.mode_hz[0] == pytest.approx(8051.6, rel=0.01), \
        "first ring mode clamped on the six pads, docs/elastic_ring.md"
    bars = []
    save = fe_render.save_picture

    def counted(plotter, path):
        bars.append([b.GetTitle() for b in plotter.scalar_bars.values()])
        save(plotter, path)

    monkeypatch.setattr(fe_render, "save_picture", counted)
    files = fe_render.render_fe(replace(on, mode_shapes=on.mode_shapes[:1],
                                        mode_hz=on.mode_hz[:1]), tmp_path)
    assert [f.name for f in files] == ["fe_ring_loaded.png", "fe_ring_mode_01_foundation.png"]
    assert bars[1] == ["displacement / largest"]
    assert "Winkler foundation" in caption(files[1].name)
    assert "clamped" in caption("fe_ring_mode_01_clamped.png")


def _text_of(actor) -> str:
    """The text a pyvista text actor shows (a corner annotation's four corners, or a text
    actor's input); empty for other actors."""
    if hasattr(actor, "GetInput") and isinstance(actor.GetInput(), str):
        return actor.GetInput()
    if actor.IsA("vtkCornerAnnotation"):
        return "\n".join(actor.GetText(i) or "" for i in range(4))
    return ""


@pytest.mark.slow
def test_watched_coupled_modes_have_a_colour_bar_and_a_caption_naming_them(tmp_path,
                                                                           monkeypatch):
    """The elastic ring's watched modes: one picture each with one colour bar (0..1 of the
    ring's largest displacement), the title naming class, nodal diameters, frequency and
    mounting, and a file name the caption reads back to the same facts."""
    pytest.importorskip("gmsh")
    import hubvib.render.coupled as coupled
    from hubvib.design import preset_design
    from hubvib.elastic.model import elastic_ring, elastic_spectrum
    from hubvib.elastic.options import ElasticOptions, study_mesh
    from hubvib.render.captions import caption

    er = elastic_ring(preset_design("hub4"),
                      options=ElasticOptions(mesh=study_mesh(), rest="beam", band_hz=3e3))
    spectrum = elastic_spectrum(er)
    ring = max(range(spectrum.frequency_hz.size),
               key=lambda j: spectrum.content[j].ring_share)
    watched = [ring, 0]
    seen = []
    save = coupled.save_picture

    def checked(plotter, path):
        bars = list(plotter.scalar_bars.values())
        texts = [_text_of(a) for a in plotter.renderer.actors.values()]
        seen.append(([b.GetTitle() for b in bars],
                     [tuple(b.GetLookupTable().GetRange()) for b in bars], texts))
        save(plotter, path)

    monkeypatch.setattr(coupled, "save_picture", checked)
    files = coupled.render_watched_modes(er, spectrum, watched, tmp_path)
    assert len(files) == 2 and all(f.suffix == ".png" for f in files)
    for rank, (j, path, (titles, ranges, texts)) in enumerate(zip(watched, files, seen)):
        content = spectrum.content[j]
        assert titles == [coupled.BAR_TITLE] and ranges == [(0.0, 1.0)]
        title = "\n".join(texts)
        for fact in (f"{spectrum.frequency_hz[j]:.1f} Hz", content.kind,
                     f"n = {content.nodal_diameter}", "Winkler foundation",
                     f"coupled mode {j + 1}"):
            assert fact in title, f"{fact!r} missing from the picture's title {title!r}"
        words = caption(path.name)
        assert path.name.startswith(f"elastic_mode_{rank + 1:02d}_{content.kind}_")
        for fact in (f"{content.kind} mode at {spectrum.frequency_hz[j]:.0f} Hz",
                     f"elastic n={content.nodal_diameter}", "Winkler foundation",
                     f"ranked {rank + 1} (best first)"):
            assert fact in words, f"{fact!r} missing from the caption {words!r}"
        label = (f"elastic n={content.nodal_diameter} ({content.kind}, "
                 f"{spectrum.frequency_hz[j]:.1f} Hz)")
        assert label in title, f"the picture names the mode as reports do: {title!r}"
        image = _image(path)
        assert image.std() > 20
