"""Off-screen renders of lumped mode shapes: real images, distinct per mode, repeatable."""
import numpy as np
import pytest

pv = pytest.importorskip("pyvista")
imageio = pytest.importorskip("imageio")

from hubvib.render import render_mode  # noqa: E402
from lumped import natural_modes  # noqa: E402
from lumped.presets import raba118  # noqa: E402

PARAMS = raba118()
SPECTRUM = natural_modes(PARAMS)


def _image(path):
    return np.asarray(imageio.v3.imread(path), dtype=float)


def test_mode_renders_are_real_distinct_and_repeatable(tmp_path):
    first = render_mode(PARAMS, SPECTRUM, 0, tmp_path / "a")[0]
    again = render_mode(PARAMS, SPECTRUM, 0, tmp_path / "b")[0]
    other = render_mode(PARAMS, SPECTRUM, 4, tmp_path / "a")[0]
    a, b, c = _image(first), _image(again), _image(other)
    assert a.shape[:2] == (900, 900)
    assert a.std() > 20  # not blank: bodies on a white background
    np.testing.assert_array_equal(a, b)  # sign-fixed modes: the same picture twice
    assert np.abs(a - c).mean() > 1.0  # a rotational and a translational mode differ


def test_gif_and_multiblock_on_request(tmp_path):
    files = render_mode(PARAMS, SPECTRUM, 2, tmp_path, gif=True, vtm=True)
    assert [f.suffix for f in files] == [".png", ".gif", ".vtm"]
    frames = imageio.v3.imread(files[1], index=None)
    assert len(frames) == 24 and np.abs(frames[0] - frames[6]).mean() > 0.1  # it moves
    blocks = pv.read(files[2])
    assert {"sun", "ring", "carrier", "planet 1"} <= set(blocks.keys())
    # the ring is translated by the mode (translational mode 3): its centre moved
    assert np.hypot(*blocks["ring"].center[:2]) > 1e-4
