"""Smallest detectable depth against the mounting stiffness."""
import math

import numpy as np
import pytest
from tests.helpers.synthetic_rows import TIMING, synthetic_model

from hubvib.detection.detectability import detectability_map, series_base
from hubvib.detection.options import DetectionOptions

OPTIONS = DetectionOptions(map_samples=60, mount_points=3, mount_min=1e6, mount_max=1e12)


@pytest.fixture(scope="module")
def dmap():
    # no c_rp change: what is left to detect is carried by the ring support
    return detectability_map(synthetic_model("series", c_rp_drop=0.0), OPTIONS, TIMING)


def test_the_mounting_decides_what_the_support_stiffness_shows(dmap):
    np.testing.assert_allclose(dmap.mounts, [1e6, 1e9, 1e12])
    for swept, carrier in (("c_ru_mount", "c_ru"), ("c_r_mount", "c_r")):
        own = np.where(dmap.carried_by[swept] == carrier, dmap.depth[swept], np.nan)
        assert np.isnan(own[0]).all(), f"{swept} = 1e6 N/m hides the crack"
        assert not np.isnan(own[-1]).all(), f"{swept} = 1e12 N/m (body alone) shows it"
    rows = dmap.rows()
    assert len(rows) == 2 * 3 * 18
    assert {r["signal_in"] for r in rows} <= {"c_ru", "c_r", "c_rp", "none"}
    assert all(r["smallest_detectable_depth_mm"] is None or r["smallest_detectable_depth_mm"] > 0
               for r in rows)


def test_series_base_of_every_apply():
    assert math.isinf(series_base(synthetic_model("direct")).c_ru_mount)
    ratio = series_base(synthetic_model("ratio"))
    assert ratio.apply == "series" and ratio.c_ru[0] == pytest.approx(1e6, rel=1e-12)
    given = synthetic_model("series", c_ru_mount=3e9, c_r_mount=4e9)
    assert series_base(given) is given


def test_the_map_on_threads_gives_the_same_digits(dmap):
    # the mounting values run on two threads at one BLAS thread: each is the same seeded
    # POD as on one thread, so every number must agree exactly, not only to round-off
    threaded = detectability_map(synthetic_model("series", c_rp_drop=0.0), OPTIONS, TIMING,
                                 workers=2)
    for swept in ("c_ru_mount", "c_r_mount"):
        np.testing.assert_array_equal(threaded.depth[swept], dmap.depth[swept],
                                      err_msg=f"{swept}: threaded map vs one thread")
        np.testing.assert_array_equal(threaded.frequency_hz[swept], dmap.frequency_hz[swept],
                                      err_msg=f"{swept}: threaded map vs one thread")
        assert (threaded.carried_by[swept] == dmap.carried_by[swept]).all(), swept
    assert threaded.kind == dmap.kind
