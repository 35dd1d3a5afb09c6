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
    assert fig.axes[0].get_xlim() == (1e6, 1e12)
