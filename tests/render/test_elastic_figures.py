"""The elastic ring's figures: both ring models side by side, the crack's open /
record-averaged / closed states, the open length over a carrier revolution.  Each is
written as a PNG and checked for what a reader must tell apart: every curve its own style,
each panel on a scale of its own, legends off the data, the values drawn those given."""
import numpy as np
import pytest

pytest.importorskip("matplotlib")

from hubvib.foundation.output import save_figure  # noqa: E402
from hubvib.render.captions import caption  # noqa: E402
from hubvib.render.elastic_figures import (ELASTIC_OPEN, ELASTIC_RECORD,  # noqa: E402
                                           RIGID_RECORD, both_models_figure,
                                           crack_states_figure, open_length_figure)
from tests.helpers.figure_checks import (clipped_texts, covered_by_legends,  # noqa: E402
                                         hidden_series, overlapping_texts, series,
                                         squashed_series, unnamed_series)

DEPTHS = np.array([0.0, 0.003, 0.006, 0.009, 0.012, 0.015, 0.018, 0.021])


def _readable(fig):
    assert clipped_texts(fig) == [], "text outside the figure"
    assert overlapping_texts(fig) == [], "texts drawn over each other"
    assert unnamed_series(fig) == [], "series without a legend entry"
    assert covered_by_legends(fig) == [], "a legend drawn over the data"


def _styles(lines) -> set:
    return {(line.get_color(), line.get_marker(), str(line.get_linestyle())) for line in lines}


def _written(fig, path) -> np.ndarray:
    import matplotlib.image

    image = np.asarray(matplotlib.image.imread(save_figure(fig, path)), dtype=float)
    assert image.std() > 0.05, "a blank picture"
    return image


@pytest.mark.slow
def test_both_models_each_curve_told_apart_on_its_own_scale(tmp_path):
    """The rigid ring moves its modes by about 1 Hz, the elastic ring by hundreds: one
    panel each, every curve with its own colour, marker and line style."""
    rigid = -np.outer(np.sqrt(DEPTHS / DEPTHS[-1]), [1.65, 1.38, 1.2, 0.34])
    elastic = -np.outer(DEPTHS / DEPTHS[-1], [660.0, 460.0, 580.0, 310.0])
    elastic[6:, 2] = np.nan  # a mode no longer tracked
    fig = both_models_figure("t", DEPTHS, rigid, [f"rigid {k}" for k in range(4)], DEPTHS,
                             elastic, [f"elastic {k}" for k in range(4)])
    _readable(fig)
    left, right = fig.axes[:2]
    for ax, labels in ((left, "rigid"), (right, "elastic")):
        lines = [line for line in ax.get_lines() if line.get_label().startswith(labels)]
        assert len(lines) == 4 and len(_styles(lines)) == 4
        assert len({line.get_linestyle() for line in lines}) == 4, "four line styles"
        assert not ax.get_legend() or not _overlaps(ax.get_legend(), ax), "legend below"
    np.testing.assert_allclose(left.get_lines()[0].get_ydata(), rigid[:, 0])
    assert squashed_series(fig, series(fig)) == [], "each panel on a scale of its own"
    _written(fig, tmp_path / "frequency_both_models.png")
    assert "rigid" in caption("frequency_both_models.png")
    assert ELASTIC_OPEN in right.get_title() and RIGID_RECORD in left.get_title()
    loaded = both_models_figure("t", DEPTHS, rigid, ["r"] * 4, DEPTHS, elastic, ["e"] * 4,
                                ELASTIC_RECORD)
    assert ELASTIC_RECORD in loaded.axes[1].get_title(), "the panel says what its change is"
    # the caption leaves it to the titles: it once called the record's change "crack open"
    assert "crack open" not in caption("frequency_both_models.png")


def _overlaps(legend, ax) -> bool:
    renderer = ax.figure.canvas.get_renderer()
    a, b = legend.get_window_extent(renderer), ax.get_window_extent(renderer)
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


@pytest.mark.slow
@pytest.mark.parametrize("averaged", [True, False])
def test_crack_states_open_averaged_closed(tmp_path, averaged):
    """Per watched mode a panel with the open, (when given) record-averaged and closed
    crack; closed is the intact frequency at every depth; no averaged line without data."""
    intact = np.array([4715.6, 2831.2, 8567.8])
    opened = intact - np.outer(DEPTHS / DEPTHS[-1], [660.0, 460.0, 580.0])
    mean = 0.5 * (opened + intact) if averaged else None
    fig = crack_states_figure("t", DEPTHS, intact, opened, ["a", "b", "c"], mean)
    _readable(fig)
    panels = [ax for ax in fig.axes if ax.get_visible()]
    assert len(panels) == 3
    expected = 3 if averaged else 2
    for j, ax in enumerate(panels):
        lines = ax.get_lines()
        assert len(lines) == expected and len(_styles(lines)) == expected
        closed = [line for line in lines if "closed" in line.get_label()][0]
        np.testing.assert_array_equal(closed.get_ydata(), np.full(DEPTHS.size, intact[j]))
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any("record-averaged" in label for label in labels) == averaged, labels
    assert hidden_series(fig) == [], "a state hidden under another"
    _written(fig, tmp_path / "elastic_states.png")


def test_open_length_over_a_revolution_from_synthetic_states(tmp_path):
    """Synthetic crack states: the open length drawn (in mm, in carrier order) is the one
    given for each depth; a mismatch of arrays is refused by name."""
    rng = np.random.default_rng(3)
    teeth = rng.permutation(np.arange(0, 76, 2))  # out of order: the figure sorts them
    depths = DEPTHS[1:]
    states = [(teeth, d * 0.5 * (1 + np.cos(2 * np.pi * 3 * teeth / 76))) for d in depths]
    fig = open_length_figure("t", depths, states, ring_teeth=76)
    _readable(fig)
    lines = fig.axes[0].get_lines()
    assert len(lines) == depths.size and len(_styles(lines)) == depths.size
    order = np.argsort(teeth)
    for line, (tooth, length) in zip(lines, states):
        np.testing.assert_array_equal(line.get_xdata(), tooth[order])
        np.testing.assert_allclose(line.get_ydata(), 1e3 * length[order])
    assert fig.axes[0].get_xlim() == (0.0, 76.0)
    assert not _overlaps(fig.legends[0], fig.axes[0])
    _written(fig, tmp_path / "crack_state.png")
    with pytest.raises(ValueError, match="3 mm has 38 carrier positions but 2 open"):
        open_length_figure("t", depths[:1], [(teeth, np.zeros(2))])
    with pytest.raises(ValueError, match="1 states for 2 depths"):
        open_length_figure("t", depths[:2], states[:1])


def test_the_report_draws_each_models_watched_modes():
    """``both_models_arguments`` hands the figure the rigid study's watched modes
    (record-averaged change) and the elastic ring's, labelled with frequency, class and
    nodal diameters."""
    from types import SimpleNamespace

    from hubvib.reports.crack_figures import both_models_arguments

    shift = -np.outer(DEPTHS, np.arange(1.0, 19.0))
    pod = SimpleNamespace(depths=DEPTHS, kind=("translational",) * 18,
                          nominal=SimpleNamespace(shift_hz=shift, frequency_hz=np.broadcast_to(
                              100.0 * np.arange(1, 19), shift.shape)))
    study = SimpleNamespace(pod=pod, watched_modes=lambda: np.array([12, 15]))
    opened = 1000.0 - np.outer(DEPTHS, [10.0, 20.0, 30.0])
    elastic = SimpleNamespace(depths=tuple(DEPTHS), watched=(2, 0),
                              intact_hz=np.array([1000.0, 1000.0, 1000.0]),
                              shift_hz=opened - 1000.0,
                              labels=("elastic n=2 (ring, 1000.0 Hz)",
                                      "elastic n=3 (mixed, 1000.0 Hz)",
                                      "elastic n=4 (rotational, 1000.0 Hz)"))
    args = both_models_arguments("t", SimpleNamespace(elastic=elastic), study)
    (name, rigid_depths, rigid, rigid_labels, elastic_depths, change, labels, elastic_is,
     rigid_is) = args
    assert elastic_is == ELASTIC_OPEN and rigid_is == RIGID_RECORD, \
        "without the load cycle the elastic change is the open crack's"
    track = SimpleNamespace()
    elastic.detail = SimpleNamespace(open_hz=opened, tracks=(None, track, track))
    assert both_models_arguments("t", SimpleNamespace(elastic=elastic), study)[7] == \
        ELASTIC_RECORD, "with the load cycle it is a record's change"
    np.testing.assert_array_equal(rigid, shift[:, [12, 15]])
    np.testing.assert_array_equal(change, (opened - 1000.0)[:, [2, 0]])
    assert labels == ["elastic n=4 (rotational, 1000.0 Hz)", "elastic n=2 (ring, 1000.0 Hz)"], \
        "each elastic mode by its one identity (class, nodal diameters, frequency)"
    assert "1300.0 Hz translational" in rigid_labels[0]
