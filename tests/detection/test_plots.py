"""Figures: every curve named, at most eight per panel, the depth floor marked."""
from types import SimpleNamespace

import numpy as np
import pytest

from hubvib.detection.plots import MARGIN, PER_PANEL, relative_shift_figure


def test_frequency_figure_has_at_most_eight_named_curves_per_panel():
    depths = np.linspace(0, 0.024, 9)
    omega = 1000.0 * (1 + np.arange(18))[None, :] * (1 - 1e-3 * np.outer(depths / 0.024,
                                                                           np.arange(1, 19)))
    fig = relative_shift_figure("t", depths, omega, ("rotational",) * 18)
    modes = []
    for ax in fig.axes:
        labels = [line.get_label() for line in ax.get_lines()]
        curves = [label for label in labels if not label.startswith("shallowest")]
        assert len(curves) <= PER_PANEL and all(not c.startswith("_") for c in curves)
        assert any(label.startswith("shallowest crack computed 3 mm") for label in labels)
        styles = {(line.get_color(), line.get_marker()) for line in ax.get_lines()[:-1]}
        assert len(styles) == len(curves), "distinct styles within a panel"
        modes += curves
    assert len(modes) == 18 and len(fig.axes) == 3


def test_frequency_figure_tells_apart_modes_moving_by_ppm_to_per_cent():
    """The modes move by parts per million to per cent: on a linear axis all but the
    largest lay on zero.  On the log axis each curve's end lies apart from the others',
    each panel's legend below it (off the data)."""
    from tests.helpers.figure_checks import covered_by_legends, overlapping_texts

    depths = np.linspace(0, 0.024, 9)
    drop = 1e-8 * 10 ** (np.arange(18) / 3)  # 1e-8 .. 5e-3, a third of a decade apart
    omega = 1000.0 * (1 + np.arange(18)) * (1 - np.outer(depths / 0.024, drop))
    fig = relative_shift_figure("t", depths, omega, ("translational",) * 18)
    for ax in fig.axes:
        assert ax.get_yscale() == "log"
        curves = [line for line in ax.get_lines() if "Hz" in line.get_label()]
        ends = np.sort([ax.transData.transform((24.0, line.get_ydata()[-1]))[1]
                        for line in curves])
        assert np.diff(ends).min() > 8, f"curve ends {np.diff(ends)} pixels apart"
        assert not _intersects(ax.get_legend(), ax), "legend below its panel"
    assert covered_by_legends(fig) == [] and overlapping_texts(fig) == []


def test_map_figure_where_no_mounting_detects_anything():
    """The 3D crack-growth study's short cracks: every depth of the map is NaN (nothing
    detectable at any mounting); the log-scaled mounting axis still gets its limits (it
    raised 'Data cannot be log-scaled' and ended `hubvib run raba118_crack_3d`)."""
    from types import SimpleNamespace

    import numpy as np

    from hubvib.detection.plots import map_figure

    mounts = np.geomspace(1e6, 1e12, 5)
    nothing = np.full((5, 18), np.nan)
    dmap = SimpleNamespace(
        mounts=mounts, depth={"c_ru_mount": nothing, "c_r_mount": nothing},
        carried_by={"c_ru_mount": np.full((5, 18), "c_rp"), "c_r_mount": np.full((5, 18), "c_rp")},
        fixed={"c_ru_mount": np.inf, "c_r_mount": np.inf},
        smallest=lambda swept: np.full(5, np.nan))
    fig = map_figure("none", dmap, deepest=0.009, shallowest=0.003)
    fig.canvas.draw()
    low, high = fig.axes[0].get_xlim()
    assert low < 1e6 and high > 1e12 and high / 1e12 == pytest.approx(MARGIN), \
        "the swept range 1e6..1e12 N/m and a margin for the end markers"
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert not any(label.startswith("signal in") or label == "any mode" for label in labels), \
        f"nothing detectable: no curve, so no curve in the legend; got {labels}"
    assert "nothing of the sweep detectable" in labels


def _map(carriers: dict):
    """A map over 13 mountings where, per swept name, the modes of ``carriers`` (mode ->
    (carrier, first detecting mounting index)) detect from that mounting on, deeper cracks
    needed at softer mountings."""
    mounts = np.geomspace(1e6, 1e12, 13)
    depth, carried = {}, {}
    for swept in ("c_ru_mount", "c_r_mount"):
        d = np.full((13, 18), np.nan)
        c = np.full((13, 18), "none", dtype=object)
        for mode, (carrier, first) in carriers.items():
            d[first:, mode] = np.linspace(0.021, 0.003, 13 - first)
            c[:, mode] = carrier
        depth[swept], carried[swept] = d, c

    def smallest(swept):
        d = depth[swept]
        return np.where(np.isnan(d).all(axis=1), np.nan,
                        np.nanmin(np.where(np.isnan(d), np.inf, d), axis=1))

    return SimpleNamespace(mounts=mounts, depth=depth, carried_by=carried,
                           fixed={"c_ru_mount": 1e8, "c_r_mount": 1e6}, smallest=smallest)


@pytest.mark.slow
def test_map_figure_draws_what_its_legend_names_with_any_mode_on_top(tmp_path):
    """Only c_ru carries a signal: no 'signal in c_rp' entry without a mark; the 'any
    mode' line over the markers and visible; the legend off the data; the PNG written."""
    from hubvib.detection.plots import map_figure
    from hubvib.foundation.output import save_figure
    from tests.helpers.figure_checks import covered_by_legends, hidden_series, overlapping_texts

    fig = map_figure("t", _map({3: ("c_ru", 7)}), deepest=0.0247, shallowest=0.003)
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "signal in c_ru" in labels and "any mode" in labels
    assert "signal in c_rp" not in labels and "signal in c_r" not in labels, labels
    for ax in fig.axes:
        drawn = {line.get_label(): line for line in ax.get_lines()}
        marks, line = drawn["signal in c_ru"], drawn["any mode"]
        assert np.isfinite(np.asarray(marks.get_ydata(), float)).sum() == 6, \
            "a mark at each of the 6 detecting mountings"
        assert line.get_zorder() > marks.get_zorder(), "'any mode' drawn over the marks"
    assert hidden_series(fig) == [] and covered_by_legends(fig) == []
    assert overlapping_texts(fig) == []
    for ax in fig.axes:  # the legend below the panels, not over them
        assert not _intersects(fig.legends[0], ax)
    out = save_figure(fig, tmp_path / "map.png")
    assert _image(out).std() > 10


def _intersects(legend, ax) -> bool:
    renderer = ax.figure.canvas.get_renderer()
    a, b = legend.get_window_extent(renderer), ax.get_window_extent(renderer)
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def _image(path):
    import matplotlib.image

    return np.asarray(matplotlib.image.imread(path), dtype=float) * 255


def _pod_study(single):
    """A POD study whose single-mode PODs ``single`` (depths, modes) lie near the false-alarm
    rate and whose family curves reach the required POD."""
    depths = np.linspace(0.0, 0.0247, 9)
    modes = single.shape[1]
    frequency = np.broadcast_to(1000.0 * (1 + np.arange(modes)), (9, modes))
    return SimpleNamespace(
        depths=depths, pod=single, kind=("translational",) * modes,
        nominal=SimpleNamespace(frequency_hz=frequency),
        family_pod={10.0: np.linspace(0.01, 0.05, 9), 60.0: np.linspace(0.01, 0.36, 9),
                    600.0: np.minimum(1.0, np.linspace(0.01, 3.0, 9))},
        detection_probability=0.9, false_alarm_rate=0.01, per_mode_rate=0.00251,
        samples=2000)


def test_pod_single_modes_are_told_apart_on_their_own_log_panel(tmp_path):
    """The four single-mode curves lie between 0.003 and 0.02: on the family's linear axis
    they were one line at 0; on their own log panel each spans a readable height and has
    its own colour, marker and line style."""
    from hubvib.detection.plots import pod_figure
    from hubvib.foundation.output import save_figure
    from tests.helpers.figure_checks import (covered_by_legends, overlapping_texts,
                                             shared_colours, squashed_series)

    single = np.column_stack([np.linspace(0.01, 0.02, 9), np.linspace(0.01, 0.004, 9),
                              np.linspace(0.01, 0.015, 9), np.geomspace(0.01, 0.003, 9)])
    fig = pod_figure("t", _pod_study(single), [0, 1, 2, 3])
    family, alone = fig.axes[:2]
    curves = [line for line in alone.get_lines() if "Hz" in line.get_label()]
    assert len(curves) == 4 and alone.get_yscale() == "log"
    styles = {(line.get_color(), line.get_marker(), str(line.get_linestyle()))
              for line in curves}
    assert len(styles) == 4 and len({line.get_linestyle() for line in curves}) == 4
    assert shared_colours(curves) == []
    assert squashed_series(fig, curves) == [], \
        "each single-mode curve spans at least 5 % of its panel's height"
    ends = sorted(alone.transData.transform([(1e3 * 0.0247, line.get_ydata()[-1])
                                             for line in curves])[:, 1])
    assert np.diff(ends).min() > 10, f"the curves end apart (pixels {np.diff(ends)})"
    assert covered_by_legends(fig) == [] and overlapping_texts(fig) == []
    (legend,) = fig.legends
    for ax in (family, alone):
        assert not _intersects(legend, ax), "the legend below the panels"
    named = [t.get_text() for t in legend.get_texts()]
    assert len(named) == len(set(named)) == 3 + 4 + 4, \
        "three record lengths, four modes, the required POD, two false-alarm rates, the " \
        "shallowest crack: each once"
    # each panel's false-alarm line is the rate its curves start at: the family's 0.01 on
    # the left, each mode's own 0.00251 on the right (the single curves once started
    # below the family's line drawn there)
    rates = {ax: [line.get_ydata()[0] for line in ax.get_lines()
                  if "false-alarm" in line.get_label()] for ax in (family, alone)}
    assert rates[family] == [0.01] and rates[alone] == [0.00251]
    assert alone.get_ylim()[0] < 0.00251, "the per-mode rate inside the log panel"
    out = save_figure(fig, tmp_path / "pod.png")
    assert _image(out).std() > 10


def test_rigid_curves_are_named_by_their_model():
    """Every curve of the rigid ring's crack figures names its model and its mode the way
    the tables do (``detection.mode_names``): ``rigid 2 (split pair 2/3, lower): ...``."""
    from hubvib.detection.mode_names import mode_names

    depths = np.linspace(0, 0.024, 5)
    omega = 1000.0 * np.array([1.0, 2.0, 2.0, 3.0]) * (1 - np.outer(depths, [1, 2, 3, 4]))
    fig = relative_shift_figure("t", depths, omega, ("rotational",) * 4)
    curves = [line.get_label() for ax in fig.axes for line in ax.get_lines()
              if "Hz" in line.get_label()]
    names = mode_names(omega[0])
    assert curves == [f"rigid {n}: {f:.1f} Hz rotational"
                      for n, f in zip(names, omega[0] / (2 * np.pi))]
    assert curves[1].startswith("rigid 2 (split pair 2/3, lower)")
