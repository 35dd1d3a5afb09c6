"""Each report figure shows what its caption says: every series named in a legend, told
apart by colour, not hidden under another, on a scale where it can be read; no text
clipped or lying on another; axis labels on their own panel; units as the text states."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from tests.helpers.figure_checks import (clipped_texts, covered_by_legends, hidden_series,  # noqa: E402
                           misplaced_axis_labels, overlapping_texts, series, shared_colours,
                           squashed_series, unnamed_series)
from hubvib.render.captions import caption  # noqa: E402


def assert_readable(fig):
    """What every line figure must pass."""
    assert clipped_texts(fig) == [], "text outside the figure"
    assert overlapping_texts(fig) == [], "texts drawn over each other"
    assert misplaced_axis_labels(fig) == []
    assert unnamed_series(fig) == [], "series without a legend entry"
    assert covered_by_legends(fig) == [], "a legend drawn over the data"


def small_signal_study():
    """A small signal study on synthetic mesh curves (no FE): three depths, two seeds."""
    from hubvib.design import preset_design
    import hubvib.signal.signature_study as signal_study
    from hubvib.signal.mesh_curves import synthetic_curves
    from hubvib.studies.scene import parse_scene

    scene = parse_scene('[reducer]\npreset = "raba118"\n[crack]\ndepths = [0.0, 0.006, 0.012]\n'
                        'accuracy = "fast"\n[signal]\nsun_speed_rpm = 6000.0\nnoise_seeds = 2\n'
                        'roc_records = 0\nrevolutions = 2\n', "figures")
    p, design = scene.params, preset_design("raba118")
    curves = [synthetic_curves(design, crack_factor=1 + 40 * d, depth=d).to_preset(p.c_sp,
                                                                                 p.c_rp)
              for d in scene.crack.depths]
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(signal_study, "_checks", lambda *args: {})  # the figures need none
        return signal_study.run_signal_study(scene, curves)


@pytest.fixture(scope="module")
def signal_study():
    return small_signal_study()


@pytest.mark.slow
def test_indicators_each_on_a_scale_of_its_own(signal_study):
    from hubvib.signal.indicators import INDICATORS
    from hubvib.signal.report import _indicator_figure

    fig = _indicator_figure(signal_study)
    assert_readable(fig)
    curves = [line for line in series(fig) if line.get_label() in INDICATORS]
    assert sorted(line.get_label() for line in curves) == sorted(INDICATORS)
    assert shared_colours(curves) == [], "one colour per indicator"
    assert len({line.get_marker() for line in curves}) > 1
    # M8A grows a thousandfold where RMS grows a few per cent: one common axis flattens
    # all but the largest into a line
    assert squashed_series(fig, curves) == []
    assert "divided by its intact mean" in caption("indicators.png")


def test_order_spectrum_panels_have_their_own_labels(signal_study):
    from hubvib.signal.report import _spectrum_figure

    fig = _spectrum_figure(signal_study)
    assert_readable(fig)
    overview, zoom = fig.axes[:2]
    assert "carrier order" in overview.get_xlabel() and "carrier order" in zoom.get_xlabel()
    assert "zoom" in zoom.get_title() and "z_r" in caption("order_spectrum.png")
    assert shared_colours(series(fig)) == []


@pytest.mark.slow
def test_tsa_shows_both_traces_and_their_difference(signal_study):
    from hubvib.signal.report import _tsa_figure

    fig = _tsa_figure(signal_study)
    assert_readable(fig)
    assert hidden_series(fig) == [], "a trace hidden under another"
    labels = [line.get_label() for line in series(fig)]
    assert any(label.startswith("0 mm") for label in labels)
    assert any(label.startswith("12 mm") for label in labels)
    assert any("−" in label for label in labels), "the difference of the two traces"
    assert "difference" in caption("tsa.png")


def _pod(depths, shift_hz, watched, threshold_hz):
    modes = shift_hz.shape[1]
    frequency = np.broadcast_to(500.0 * (1 + np.arange(modes)), shift_hz.shape)
    return SimpleNamespace(
        depths=depths, kind=("translational",) * modes, watched=np.asarray(watched),
        nominal=SimpleNamespace(shift_hz=shift_hz, frequency_hz=frequency + shift_hz),
        sigma_hz=np.full(modes, 0.5), threshold_hz=np.asarray(threshold_hz, dtype=float))


def test_shift_vs_depth_draws_the_threshold_its_caption_describes():
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D

    from hubvib.detection.plots import shift_threshold_figure

    depths = np.linspace(0.0, 0.024, 9)
    shift = -np.outer(np.sqrt(depths / 0.024), [0.01, 0.03, 0.5, 1.2, 1.6, 0.3])
    thresholds = np.linspace(4.0, 8.0, shift.shape[1])
    fig = shift_threshold_figure("test", _pod(depths, shift, [3, 4], thresholds))
    assert_readable(fig)
    assert shared_colours(series(fig)) == []
    (legend,) = fig.legends  # below the panel
    ax = fig.axes[0]
    box, panel = legend.get_window_extent(), ax.get_window_extent()
    assert box.y1 <= panel.y0, "the legend lies below the panel, off the data"
    assert box.width <= fig.get_window_extent().width, "the legend within the figure"
    # the log axis spans the data and the thresholds with a margin: no tick label sits on
    # the panel's top edge, under the title
    low, high = ax.get_ylim()
    drops = -shift[1:][shift[1:] < 0]
    assert low < drops.min() / 2 and high > thresholds[[3, 4]].max() * 2
    assert high < 100 * thresholds.max() and low > drops.min() / 10, "sized to the data"
    (entry,) = [(handle, text.get_text()) for handle, text in
                zip(legend.legend_handles, legend.get_texts()) if "alarm" in text.get_text()]
    handle, _ = entry
    text = caption("shift_vs_depth.png")
    if isinstance(handle, Line2D):
        drawn = "black line" if to_rgba(handle.get_color())[:3] == (0, 0, 0) else "line"
    else:
        grey = np.ptp(to_rgba(handle.get_facecolor())[:3]) < 1e-9
        drawn = "grey band" if grey else "band"
    assert drawn in text, f"the figure draws the thresholds as a {drawn}; caption: {text}"


def _carrier(modes=12, engaged=0.14):
    """A carrier study as ``carrier_study`` builds it: a rectangle per mode, several
    modes moving by a few parts per million, a few by up to 1 %."""
    pitch = 2 * math.pi / 64
    angle = np.linspace(-0.5 * pitch, engaged + 0.5 * pitch, 97)
    inside = (angle >= 0) & (angle <= engaged)
    out = 2 * math.pi * np.linspace(50.0, 7000.0, modes)
    drop = np.geomspace(5e-8, 5e-3, modes)[np.random.default_rng(1).permutation(modes)]
    drop[-1] = 2e-3  # the highest mode moves a lot: its row is the lowest, at the right
    omega_in, omega_min = out * (1 - drop), out * (1 - 1.9 * drop)
    return SimpleNamespace(
        omega_out=np.vstack([out, out]), omega_in=np.vstack([out, omega_in]), angle=angle,
        omega_angle=np.where(inside[:, None], omega_in, out),
        omega_angle_min=np.where(inside[:, None], omega_min, out),
        timing=SimpleNamespace(pass_angle=engaged, pass_seconds=0.00885,
                               engaged_fraction=0.137))


@pytest.mark.slow
def test_carrier_position_shows_every_moving_mode_and_its_minimum():
    from hubvib.detection.plots import carrier_figure

    modes = 12
    fig = carrier_figure("test", _carrier(modes), ["rotational"] * modes)
    assert_readable(fig)
    assert hidden_series(fig) == [], "a series hidden under another"
    assert shared_colours(series(fig)) == []
    rows = fig.axes[0]
    named = [t.get_text() for t in rows.get_yticklabels() if t.get_text()]
    assert len(named) == modes and all(" Hz " in t for t in named), named
    for line in series(fig):
        assert line.get_linestyle() == "None" or line.get_linewidth() >= 1.0, \
            f"{line.get_label()!r} drawn faint"
    assert {"minimum", "mean"} <= {w for line in series(fig) for w in
                                   line.get_label().split()}
    text = caption("carrier_position.png")
    assert "minimum" in text and "mean" in text and "log" in text


def test_crack_path_axes_in_the_units_of_its_text(tmp_path):
    """The title and the report give steps and depths in mm; so do the axes."""
    from hubvib.design import preset_design
    import hubvib.render.path_figure as path_picture
    from hubvib.studies.lefm_path import cracked_tooth, loaded_ring

    ring = loaded_ring(preset_design("raba118"))
    tooth = cracked_tooth(ring)
    mouth, _ = ring.load_point(tooth)
    path = mouth + np.outer(np.arange(4) * 0.5e-3, [1.0, -0.05])
    figures = []
    with pytest.MonkeyPatch.context() as patch:  # keep the figure open to look at it
        patch.setattr(path_picture, "save_figure", lambda fig, out: figures.append(fig))
        path_picture.render_path(ring, tooth, path, tmp_path / "crack_path.png",
                                 "raba118: crack heads for the rim (3 steps of 0.5 mm)")
    (fig,) = figures
    assert_readable(fig)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "x [mm]" and ax.get_ylabel() == "y [mm]"
    (crack,) = [line for line in ax.get_lines() if line.get_label() == "crack path"]
    np.testing.assert_allclose(crack.get_xydata(), 1e3 * path)
