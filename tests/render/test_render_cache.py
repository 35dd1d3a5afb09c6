"""The render cache: a rerun copies the files instead of rendering, checked first."""
import json

import numpy as np
import pytest

from hubvib.render.cache import array_digest, cache_folder, cached_render

#: the entry module of the stand-in renders below
MODULES = ("hubvib.render.modes",)


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    return tmp_path


class _Render:
    """Writes a PNG-like file and a multiblock (.vtm plus a folder of pieces) as pyvista
    does; counts its calls."""

    def __init__(self, text="mode 1"):
        self.calls, self.text = 0, text

    def __call__(self, target):
        self.calls += 1
        target.mkdir(parents=True, exist_ok=True)
        (target / "mode_01.png").write_text(self.text)
        (target / "mode_01").mkdir(exist_ok=True)
        (target / "mode_01" / "mode_01_0.vtp").write_text("piece")
        (target / "mode_01.vtm").write_text("blocks")
        return [target / "mode_01.png", target / "mode_01.vtm"]


def test_second_render_is_a_copy(cache):
    render = _Render()
    first = cached_render("modes", {"a": 1}, cache / "out1", render, MODULES)
    second = cached_render("modes", {"a": 1}, cache / "out2", render, MODULES)
    assert render.calls == 1
    assert [p.relative_to(cache / "out2") for p in second] == \
        [p.relative_to(cache / "out1") for p in first]
    for folder in ("out1", "out2"):
        assert (cache / folder / "mode_01.png").read_text() == "mode 1"
        assert (cache / folder / "mode_01" / "mode_01_0.vtp").read_text() == "piece"
    cached_render("modes", {"a": 2}, cache / "out3", render, MODULES)  # other inputs: rendered
    assert render.calls == 2


@pytest.mark.parametrize("damage", ["edit", "delete", "manifest", "empty", "list", "escape"])
def test_a_damaged_entry_is_rendered_again(cache, capsys, damage):
    render = _Render()
    cached_render("modes", {"a": 1}, cache / "out1", render, MODULES)
    (entry,) = cache_folder().iterdir()
    if damage == "edit":
        (entry / "mode_01.png").write_text("mode 2")
    elif damage == "delete":
        (entry / "mode_01" / "mode_01_0.vtp").unlink()
    else:
        manifest = {"manifest": {"files": {}, "returned": ["x.png"]},
                    "empty": {"files": {}, "returned": []},
                    "list": {"files": [], "returned": []},
                    "escape": {"files": {"../x.png": "0"}, "returned": ["../x.png"]}}[damage]
        (entry / "manifest.json").write_text(json.dumps(manifest))
    cached_render("modes", {"a": 1}, cache / "out2", render, MODULES)
    assert render.calls == 2
    assert "rendering again" in capsys.readouterr().err
    assert (cache / "out2" / "mode_01.png").read_text() == "mode 1"
    cached_render("modes", {"a": 1}, cache / "out3", render, MODULES)  # repaired
    assert render.calls == 2


def test_a_failed_render_leaves_no_entry(cache):
    def broken(target):
        (target / "half.png").write_text("x")
        raise RuntimeError("no display")

    with pytest.raises(RuntimeError):
        cached_render("modes", {"a": 1}, cache / "out", broken, MODULES)
    assert list(cache_folder().iterdir()) == []


def test_an_unusable_cache_folder_renders_in_place(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("HUBVIB_CACHE", str(blocker))
    render = _Render()
    files = cached_render("modes", {"a": 1}, tmp_path / "out", render, MODULES)
    assert files == [tmp_path / "out" / "mode_01.png", tmp_path / "out" / "mode_01.vtm"]
    assert (tmp_path / "out" / "mode_01.png").read_text() == "mode 1"


def test_array_digest_ignores_eigensolver_round_off():
    shapes = np.random.default_rng(0).standard_normal((18, 18))
    assert array_digest(shapes) == array_digest(shapes * (1 + 1e-14))
    moved = shapes.copy()
    moved[3, 4] *= 1 + 1e-6
    assert array_digest(shapes) != array_digest(moved)
    assert array_digest(shapes) != array_digest(shapes.reshape(9, 36))
    with pytest.raises(ValueError, match="NaN"):
        array_digest([1.0, float("nan")])
