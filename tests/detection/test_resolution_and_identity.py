"""The POD crossing's bracket and the depth the sweep adds next (one rule for both ring
models), the mode map between the two models by shape, and which model's answer leads."""
from types import SimpleNamespace

import numpy as np
import pytest

from hubvib.detection.mode_map import mode_map
from hubvib.detection.resolution import FLOOR, RESOLUTION, bracket, next_depth
from hubvib.detection.mode_names import rigid_label
from hubvib.detection.result import DetectionResult
from hubvib.lumped import natural_modes
from hubvib.reports.answer import answer_line, lead, lead_lines


def test_bracket_words_and_the_next_depth():
    """Exact cases: the crossing between two computed depths, under the shallowest one,
    outside the sweep; bisection halves the bracket and never goes below 0.5 mm."""
    depths = [0.0, 0.003, 0.006, 0.009]
    b = bracket(depths, [0.01, 0.5, 0.95, 1.0], 0.9)
    assert (b.low, b.high, b.words()) == (0.003, 0.006, "between 3 and 6 mm")
    assert next_depth(b) == pytest.approx(0.0045) and not b.resolved
    below = bracket(depths, [0.01, 1.0, 1.0, 1.0], 0.9)
    assert below.words() == "below 3 mm" and next_depth(below) == pytest.approx(0.0015)
    none = bracket(depths, [0.01, 0.2, 0.3, 0.5], 0.9)
    assert none.high is None and none.resolved and next_depth(none) is None
    assert none.words() == "not within the sweep (up to 9 mm)"
    floor = bracket([0.0, 0.00075, 0.003], [0.01, 1.0, 1.0], 0.9)
    assert next_depth(floor) == FLOOR  # half of 0.75 mm is below the floor
    at_floor = bracket([0.0, FLOOR, 0.003], [0.01, 0.95, 1.0], 0.9)
    assert at_floor.resolved and at_floor.words() == "below 0.5 mm"
    narrow = bracket([0.0, 0.001, 0.0015], [0.01, 0.5, 0.95], 0.9)
    assert narrow.high - narrow.low <= RESOLUTION and narrow.resolved
    assert narrow.words() == "between 1 and 1.5 mm"
    with pytest.raises(ValueError, match="one POD per depth"):
        bracket(depths, [0.1, 0.2], 0.9)


def _rigid():
    from hubvib.design.presets import preset_design
    from hubvib.reducer.stages import lumped_parameters

    return natural_modes(lumped_parameters(preset_design("raba118")))


def test_the_rigid_models_own_shapes_map_to_themselves_with_mac_one():
    """Identity: the rigid model's own mode shapes (without the ring's x_r, y_r, u_r) as
    the "elastic" modes map each to its own mode, a repeated pair to the pair, MAC 1."""
    spectrum = _rigid()
    keep = np.array([i for i in range(spectrum.shapes.shape[0]) if i not in (4, 5, 8)])
    f = spectrum.omega / (2 * np.pi)
    labels = [rigid_label(i, k, f[i]) for i, k in enumerate(spectrum.kind)]
    own = SimpleNamespace(lumped=spectrum.shapes[keep], lumped_mass=spectrum.mass[keep],
                          frequency_hz=f)
    pairs = mode_map(spectrum, labels, own, [f"own {i + 1}" for i in range(f.size)])
    for i, pair in enumerate(pairs[1:], start=1):  # mode 1: the rigid-body rotation
        assert pair.mac == pytest.approx(1.0, abs=1e-9), (pair, "MAC of a shape with itself")
        assert str(i + 1) in pair.rigid.split()[1].split("/"), pair
        assert pair.rigid_hz == pytest.approx(f[i], rel=1e-6)


def _result(ring, watched_hz, pod_at_3mm):
    f = np.array([[*watched_hz], [*watched_hz]], dtype=float)
    pod = {10.0: np.array([0.01, pod_at_3mm])}
    return DetectionResult(ring, (0.0, 0.003), f, tuple(f"{ring} {x:.0f} Hz" for x in f[0]),
                           {10.0: np.ones(f.shape[1])}, tuple(range(f.shape[1])), pod, pod,
                           0.9, 0.01, 10.0)


def test_the_model_whose_band_covers_the_watched_modes_leads():
    """The rigid ring holds below 884 Hz: with watched modes at 4.5-6.9 kHz the elastic
    ring leads and the rigid ring is the comparison row, with the reason; with a band
    covering them the rigid ring would lead."""
    rigid = _result("rigid", (4548.5, 6900.9), 0.2)
    elastic = _result("elastic", (2831.2, 4715.6), 1.0)
    band = SimpleNamespace(band_top_hz=884.2, compared_to_hz=10e3,
                           holds_for=lambda f: f < 884.2)
    which = lead(rigid, elastic, band)
    assert which.leader is elastic and which.other is rigid
    assert which.reason == "rigid ring: holds below 884 Hz; watched modes 4.5-6.9 kHz"
    text = "\n".join(lead_lines(which))
    assert text.startswith("**On the elastic ring, the model that holds at the watched "
                           "modes, the depth from which a crack is detected")
    assert "10 s: below 3 mm.**" in text and "not within the sweep (up to 3 mm)" in text
    assert answer_line(which).startswith("elastic ring: crack detected")
    wide = SimpleNamespace(band_top_hz=20e3, compared_to_hz=10e3, holds_for=lambda f: True)
    assert lead(rigid, elastic, wide).leader is rigid
    assert lead(rigid, None, band).leader is rigid and lead(rigid, None, band).other is None
