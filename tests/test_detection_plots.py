"""Figures: every curve named, at most eight per panel, the depth floor marked."""
import numpy as np

from hubvib.detection.plots import PER_PANEL, relative_shift_figure


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
