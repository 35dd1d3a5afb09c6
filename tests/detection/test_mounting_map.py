"""One detectability map for both ring models: the rigid ring's and the elastic ring's
maps as one ``MountingMap``, the same numbers as each model's own map, one figure and one
section writer for both."""
import math

import numpy as np
import pytest
from tests.detection.test_plots import _image, _intersects
from tests.elastic.test_elastic_map import _synthetic_map
from tests.helpers.synthetic_rows import TIMING, synthetic_model

from hubvib.detection.detectability import detectability_map
from hubvib.detection.mounting_map import (ElasticMounting, Mounting, MountingMap,
                                           RigidMounting, as_mounting_map,
                                           elastic_mounting_map)
from hubvib.detection.options import DetectionOptions
from hubvib.detection.plots import map_figure
from hubvib.detection.spectrum_model import as_spectrum_model
from hubvib.reports import detection_sections, elastic_map_sections
from hubvib.reports.mounting_map_sections import map_section, map_summary, map_table

OPTIONS = DetectionOptions(map_samples=60, mount_points=3, mount_min=1e6, mount_max=1e12)


@pytest.fixture(scope="module")
def rigid():
    model = synthetic_model("series", c_rp_drop=0.0)
    return model, as_spectrum_model(model).mounting().mounting_map(OPTIONS, TIMING)


def test_the_rigid_models_mounting_map_is_its_detectability_map_digit_for_digit(rigid):
    """Through the protocol (``RigidSpectrum.mounting()``) the same seeded Monte Carlo POD
    per mounting as ``detectability_map`` itself: every depth, carrier and row identical,
    the line over all modes the smallest over the modes."""
    model, mmap = rigid
    own = detectability_map(model, OPTIONS, TIMING)
    assert isinstance(RigidMounting(model), Mounting)
    assert mmap.ring == "rigid" and mmap.line_label == "any mode"
    assert [p.axis_name for p in mmap.panels] == ["c_ru_mount", "c_r_mount"]
    assert mmap.depths == tuple(model.depths) and mmap.record_length == OPTIONS.record_length
    for panel in mmap.panels:
        np.testing.assert_array_equal(panel.axis_values, own.mounts)
        np.testing.assert_array_equal(panel.depth, own.depth[panel.axis_name],
                                      err_msg=f"{panel.axis_name}: protocol vs own map")
        assert (panel.carried_by == own.carried_by[panel.axis_name]).all()
        smallest = np.array([np.nanmin(row) if np.isfinite(row).any() else np.nan
                             for row in own.depth[panel.axis_name]])
        np.testing.assert_array_equal(panel.any_mode, smallest)
    assert mmap.rows() == own.rows()
    assert map_table(mmap) == detection_sections.map_table(own)
    assert map_summary(mmap) == detection_sections.map_summary(own)
    assert map_table(mmap)[0].startswith("| mounting [N/m] | c_ru_mount swept: via c_ru [mm]")
    assert map_section(mmap)[0] == "## Detectability against the ring mounting"


def test_the_elastic_map_as_a_mounting_map_keeps_its_numbers_and_words():
    """The elastic map's one panel over the foundation scale: its family depth is the line
    over all modes, its followed modes the columns; the section writer gives the elastic
    map's table and section (headings the report and its tests read) for either type."""
    emap = _synthetic_map()
    mmap = elastic_mounting_map(emap)
    (panel,) = mmap.panels
    assert mmap.ring == "elastic" and as_mounting_map(emap).ring == "elastic"
    assert as_mounting_map(mmap) is mmap
    np.testing.assert_array_equal(panel.axis_values, emap.scales)
    np.testing.assert_array_equal(panel.any_mode, emap.family_depth)
    np.testing.assert_array_equal(panel.depth, emap.mode_depth)
    assert panel.carried_by is None and panel.mode_names[0] == "elastic 4716 Hz at s = 1"
    assert list(panel.detectable) == [True, True, False]
    assert mmap.shallowest == 0.003 and mmap.deepest == 0.006
    assert mmap.rows() == emap.rows()
    assert map_table(mmap) == map_table(emap) == elastic_map_sections.map_table(emap)
    assert map_section(mmap)[0] == "## Elastic ring against its mounting"
    assert map_table(mmap)[0].startswith("| s | k_n [N/m^2] | k_t [N/m^2] |")
    assert isinstance(ElasticMounting(None, (0.0,), None, None), Mounting)


@pytest.mark.slow
def test_the_elastic_map_figure_is_the_rigid_maps_function(tmp_path):
    """The elastic map through ``plots.map_figure``: one panel over the foundation scale,
    the family line drawn over the modes alone, the scale where nothing is detectable
    (s = 10) shaded, the clamped ring one step past the stiffest scale, the legend below
    the panel naming only what is drawn."""
    from hubvib.foundation.output import save_figure
    from tests.helpers.figure_checks import covered_by_legends, hidden_series

    emap = _synthetic_map()
    emap = type(emap)(**{**emap.__dict__,
                         "scales": np.array([0.1, 1.0, math.inf]),
                         "family_depth": np.array([0.006, np.nan, 0.006])})
    fig = elastic_map_sections.map_figure("t", emap)
    (ax,) = fig.axes
    drawn = {line.get_label(): line for line in ax.get_lines()}
    family = drawn["family (watched anew per scale)"]
    alone = [line for label, line in drawn.items() if label.endswith(", alone")]
    assert len(alone) == 2 and all(family.get_zorder() > a.get_zorder() for a in alone)
    assert np.asarray(family.get_xdata())[-1] == pytest.approx(3.0), \
        "the clamped ring drawn at 3 x the stiffest finite scale (s = 1 here)"
    shaded = [p for p in ax.patches if p.get_label() == "nothing of the sweep detectable"]
    assert len(shaded) == 1
    x0, x1 = shaded[0].get_x(), shaded[0].get_x() + shaded[0].get_width()
    assert x0 < 1.0 < x1, "s = 1 (nothing detectable there) lies in the shaded span"
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "family (watched anew per scale)" in labels and "any mode" not in labels
    assert not any(label.startswith("signal in") for label in labels), labels
    assert ax.get_xlabel() == "foundation scale s [-]"
    # the modes detectable at the shallowest crack lie on its reference line, as they should
    hidden = [h for h in hidden_series(fig) if not h.startswith("'shallowest")]
    assert hidden == [] and covered_by_legends(fig) == []
    assert not _intersects(fig.legends[0], ax)
    assert _image(save_figure(fig, tmp_path / "elastic_map.png")).std() > 10


def test_the_rigid_figure_from_the_mounting_map_equals_the_one_from_its_map(rigid):
    """``map_figure`` of the rigid ``MountingMap`` and of its ``DetectabilityMap`` (as the
    report calls it) draw the same lines and limits."""
    model, mmap = rigid
    deepest, shallowest = max(model.depths), min(d for d in model.depths if d > 0)
    one = map_figure("t", mmap)
    other = map_figure("t", mmap.detail, deepest, shallowest)
    for a, b in zip(one.axes, other.axes):
        assert a.get_xlim() == b.get_xlim() and a.get_ylim() == b.get_ylim()
        assert [line.get_label() for line in a.get_lines()] == \
            [line.get_label() for line in b.get_lines()]
        for p, q in zip(a.get_lines(), b.get_lines()):
            np.testing.assert_array_equal(np.asarray(p.get_xydata(), float),
                                          np.asarray(q.get_xydata(), float))
    assert isinstance(mmap, MountingMap)
