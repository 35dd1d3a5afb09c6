"""The lumped mode picture: arrows for the motion (straight from each moving body's centre
along its translation, curved around it for its turn), text of at least 12 pt at the saved
size, the bodies at rest as dashed outlines."""
import math

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from hubvib.lumped import natural_modes  # noqa: E402
from hubvib.reducer import lumped_preset  # noqa: E402
from hubvib.render.mode_figure import (ARROW, DPI, HEAD_PT, SIZE_IN, SMALLEST,  # noqa: E402
                                       TEXT_PT, arrow_colour, mode_figure,
                                       save_mode_figure)
from hubvib.render.lumped_geometry import motion as _motion  # noqa: E402

PARAMS = lumped_preset("raba118")
SPECTRUM = natural_modes(PARAMS)


def _arrows(fig):
    from matplotlib.patches import FancyArrowPatch

    return [p for p in fig.axes[0].patches if isinstance(p, FancyArrowPatch)]


def _first(kind: str) -> int:
    return next(i for i, k in enumerate(SPECTRUM.kind) if k == kind)


def _motions(index):
    r_c = PARAMS.d_s / 2 + PARAMS.d_p / 2
    names = ["sun", "ring", "carrier"] + [f"planet {i + 1}" for i in range(PARAMS.n_planets)]
    return {n: _motion(PARAMS, SPECTRUM.shapes[:, index], n, r_c) for n in names}, r_c


@pytest.mark.parametrize("kind", ["rotational", "translational"])
def test_every_moving_body_gets_its_arrows(kind):
    """Count the arrows from the mode itself: one straight arrow per body translating by
    at least SMALLEST of the largest motion, one curved per body turning so; a straight
    arrow points along its body's translation."""
    index = _first(kind)
    fig = mode_figure(PARAMS, SPECTRUM.shapes[:, index], "t")
    motions, r_c = _motions(index)
    radius = {"sun": PARAMS.d_s / 2, "ring": PARAMS.d_r / 2, "carrier": r_c}
    sizes = {n: (math.hypot(dx, dy), abs(a) * radius.get(n, PARAMS.d_p / 2))
             for n, (dx, dy, a) in motions.items()}
    largest = max(max(v) for v in sizes.values())
    straight = sum(t >= SMALLEST * largest for t, _ in sizes.values())
    curved = sum(r >= SMALLEST * largest for _, r in sizes.values())
    arrows = _arrows(fig)
    shapes = [len(a.get_path().vertices) for a in arrows]
    assert len(arrows) == straight + curved and straight + curved > 0
    assert sum(n > 6 for n in shapes) >= curved, "a curved arrow per turning body"
    gids = {a.get_gid() for a in arrows}
    assert gids == ({f"translation {n}" for n, (t, _) in sizes.items() if t >= SMALLEST * largest}
                    | {f"turn {n}" for n, (_, r) in sizes.items() if r >= SMALLEST * largest})
    if kind == "rotational":
        assert curved >= 3, "sun, carrier and ring turn in a rotational mode"
    else:
        dx, dy, _ = motions["sun"]
        (sun,) = [a for a in arrows if a.get_gid() == "translation sun"]
        start, tip = np.asarray(sun._posA_posB)  # matplotlib keeps the two ends there
        expected = ARROW * PARAMS.d_r / 2 / largest * np.array([dx, dy])
        np.testing.assert_allclose(start, 0.0, atol=1e-15)
        np.testing.assert_allclose(tip, expected, rtol=1e-9,
                                   err_msg="the sun's arrow is its translation at the "
                                   "arrow scale")


def test_text_at_least_12_pt_and_one_dashed_outline_per_body(tmp_path):
    from matplotlib.patches import PathPatch

    index = _first("translational")
    fig = mode_figure(PARAMS, SPECTRUM.shapes[:, index], "mode 4: 303.70 Hz, translational")
    from tests.helpers.figure_checks import drawn_texts, overlapping_texts

    texts = [t for t, _ in drawn_texts(fig)]  # every text the saved picture shows
    assert len(texts) >= 8, "title, scales and the legend's entries"
    small = [(t.get_text(), t.get_fontsize()) for t in texts if t.get_fontsize() < 12]
    assert not small and TEXT_PT >= 12, f"text under 12 pt at the saved size: {small}"
    assert overlapping_texts(fig) == []
    outlines = [p for p in fig.axes[0].patches if isinstance(p, PathPatch)
                and p.get_facecolor()[3] == 0 and p.get_linestyle() != "solid"]
    assert len(outlines) == 3 + PARAMS.n_planets, "sun, ring, carrier and planets at rest"
    out = tmp_path / "mode.png"
    save_mode_figure(PARAMS, SPECTRUM.shapes[:, index], "mode 4", out)
    import matplotlib.image

    image = matplotlib.image.imread(out)
    assert image.shape[:2] == (round(SIZE_IN * DPI),) * 2
    from matplotlib.colors import to_rgb

    drawn = [np.abs(image[..., :3] - to_rgb(arrow_colour(n))).max(axis=2) < 0.06
             for n in ("sun", "planet 1")]
    assert all(d.mean() > 0.0003 for d in drawn), "the sun's and the planets' arrows drawn"


def _luminance(colour) -> float:
    from matplotlib.colors import to_rgb

    return float(np.dot(to_rgb(colour), (0.2126, 0.7152, 0.0722)))


def test_arrows_from_the_centre_told_apart_by_their_bodys_colour():
    """Sun, ring and carrier all translate from the centre: their arrows (once all black,
    one over the other) each in a dark shade of the body's colour, the three different,
    each darker than its body's fill and rimmed in white; a short arrow's head shrinks
    with it (down to HEAD_PT[0]) so its length still shows the motion."""
    from hubvib.render.lumped_geometry import COLOURS, PLANET_COLOUR

    index = next(i for i in range(SPECTRUM.shapes.shape[1])
                 if all(math.hypot(*_motions(i)[0][n][:2]) > 0.1 * max(
                     max(math.hypot(dx, dy), abs(a) * PARAMS.d_p / 2)
                     for dx, dy, a in _motions(i)[0].values())
                        for n in ("sun", "ring", "carrier")))
    arrows = {a.get_gid(): a for a in _arrows(mode_figure(PARAMS, SPECTRUM.shapes[:, index],
                                                          "t"))}
    centre = [arrows[f"translation {n}"] for n in ("sun", "ring", "carrier")]
    colours = {tuple(np.round(a.get_edgecolor(), 3)) for a in centre}
    assert len(colours) == 3, "the sun's, ring's and carrier's arrows in three colours"
    for gid, a in arrows.items():
        body = gid.split(" ", 1)[1]
        fill = COLOURS.get(body, PLANET_COLOUR)
        assert _luminance(a.get_edgecolor()) < 0.6 * _luminance(fill), gid
        assert any(getattr(e, "_gc", {}).get("foreground") == "white"
                   for e in a.get_path_effects()), f"{gid}: white rim"
        assert HEAD_PT[0] <= a.get_mutation_scale() <= HEAD_PT[1]
    heads = sorted(a.get_mutation_scale() for a in arrows.values())
    assert heads[0] < heads[-1], "a shorter arrow, a smaller head"


def test_the_carriers_turn_clear_of_the_suns():
    """In a rotational mode sun and carrier both turn about the centre, the carrier's arc
    over the sun's body: the two arcs lie on opposite sides (they once ran into each other
    on the sun's upper right)."""
    fig = mode_figure(PARAMS, SPECTRUM.shapes[:, _first("rotational")], "t")
    renderer = fig.canvas.get_renderer()
    boxes = {a.get_gid(): a.get_window_extent(renderer) for a in _arrows(fig)}
    sun, carrier = boxes["turn sun"], boxes["turn carrier"]
    assert not sun.overlaps(carrier), (sun, carrier)


def test_every_moved_body_inside_the_picture():
    """The ring translating by the full AMPLITUDE stays inside the axes (its outer edge
    was cut flat at the old limit of 1.25 ring radii)."""
    from matplotlib.patches import PathPatch

    for index in range(SPECTRUM.shapes.shape[1]):
        fig = mode_figure(PARAMS, SPECTRUM.shapes[:, index], "t")
        ax = fig.axes[0]
        low, high = ax.get_xlim()
        for patch in ax.patches:
            if isinstance(patch, PathPatch):
                xy = patch.get_path().vertices
                assert low < xy.min() and xy.max() < high, f"mode {index + 1}: cut off"
        import matplotlib.pyplot as plt

        plt.close(fig)
