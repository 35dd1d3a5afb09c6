"""Issue 26 item 13: the carrier-position figure draws each moving mode with its own
solid, full-width style (it used thin dotted lines with repeated colours); the thin dotted
line of the minimum mesh ratio keeps the colour of its mode."""
from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from hubvib.detection.plots import carrier_figure  # noqa: E402


def test_carrier_position_curves_have_distinct_solid_styles():
    modes, angles = 12, 40
    angle = np.linspace(0.0, 0.3, angles)
    out = np.linspace(100.0, 1200.0, modes)[None, :]
    wave = 1e-3 * np.sin(angle)[:, None] * np.arange(1, modes + 1)
    carrier = SimpleNamespace(omega_out=out, omega_angle=out * (1 + wave),
                              omega_angle_min=out * (1 + 1.5 * wave), angle=angle,
                              timing=SimpleNamespace(pass_angle=0.1, pass_seconds=0.004))
    fig = carrier_figure("test", carrier, ["rotational"] * modes)
    lines = fig.axes[0].get_lines()
    main, minimum = lines[0::2], lines[1::2]
    assert len(main) == modes, "one curve per moving mode"
    styles = {(str(l.get_color()), l.get_linestyle(), l.get_marker()) for l in main}
    assert len(styles) == modes, f"repeated styles among {modes} curves: {styles}"
    assert all(l.get_linestyle() != ":" and l.get_linewidth() >= 1.0 for l in main[:10])
    assert all(m.get_color() == l.get_color() and m.get_linestyle() == ":"
               for l, m in zip(main, minimum))
