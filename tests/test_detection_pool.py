"""The detection stage on a process pool (the main job's): the scene's POD, each point of
the detectability map and the other c_rp method's POD run there, seeded as in one process,
so every number is the same exactly (not only to round-off), and the result cache holds
the same entry whichever way it was computed."""
import pickle
import re
from dataclasses import replace

import numpy as np
import pytest
from test_detection_helpers import TIMING, synthetic_model

from hubvib.detection.mesh_stiffness import compare_methods
from hubvib.detection.study import (begin_compare_methods, begin_detection_study,
                                    cached_compare_methods, cached_detection_study,
                                    detection_study)
from hubvib.detection.options import DetectionOptions
from hubvib.runtime.process_pool import worker_pool
from hubvib.runtime.result_cache import cache_folder

OPTIONS = DetectionOptions(samples=100, map_samples=20, mount_points=2, mount_min=1e7,
                           mount_max=1e11)


@pytest.fixture(scope="module")
def pool():
    with worker_pool(2) as workers:
        yield workers


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    return tmp_path


def _same(a, b, what: str) -> None:
    """Every array and number of two results equal exactly (their pickles, field by field)."""
    for name in a.__dataclass_fields__:
        x, y = getattr(a, name), getattr(b, name)
        if hasattr(x, "__dataclass_fields__"):
            _same(x, y, f"{what}.{name}")
        elif isinstance(x, np.ndarray):
            np.testing.assert_array_equal(x, y, err_msg=f"{what}.{name}: pool vs one process")
        elif isinstance(x, dict):
            assert x.keys() == y.keys(), f"{what}.{name}"
            for key in x:
                np.testing.assert_array_equal(x[key], y[key],
                                              err_msg=f"{what}.{name}[{key!r}]")
        else:
            assert pickle.dumps(x) == pickle.dumps(y), f"{what}.{name}: {x!r} vs {y!r}"


def test_the_detection_study_on_a_pool_is_the_one_of_one_process(cache, pool):
    model = synthetic_model("series")
    here = detection_study(model, OPTIONS, TIMING)
    pooled = begin_detection_study(model, OPTIONS, TIMING, pool).result()
    _same(pooled, here, "DetectionStudy")
    entries = sorted(cache_folder().glob("detection-*.pickle"))
    assert len(entries) == 1, f"the pool run stores one detection entry, got {entries}"
    # the entry is read back by the in-process route (same key: same inputs)
    _same(cached_detection_study(model, OPTIONS, TIMING), here, "cached DetectionStudy")


def test_the_method_comparison_on_a_pool_is_the_one_of_one_process(cache, pool):
    model = synthetic_model("series")
    here = compare_methods(model, TIMING, OPTIONS.record_length, OPTIONS)
    pooled = begin_compare_methods(model, TIMING, OPTIONS.record_length, OPTIONS,
                                   pool).result()
    _same(pooled, here, "MethodComparison")
    entries = sorted(cache_folder().glob("c_rp_methods-*.pickle"))
    assert len(entries) == 1, f"the pool run stores one entry, got {entries}"
    _same(cached_compare_methods(model, TIMING, OPTIONS.record_length, OPTIONS), here,
          "cached MethodComparison")


def test_a_cached_study_submits_nothing(cache):
    """Counted: with the entry on disk the pool gets no work."""
    model = synthetic_model("series")

    class Counting:
        submitted = 0

        def submit(self, function, *args):
            Counting.submitted += 1
            raise AssertionError("a cached study must not queue work")

    cached_detection_study(model, OPTIONS, TIMING)
    begin_detection_study(model, OPTIONS, TIMING, Counting()).result()
    assert Counting.submitted == 0


@pytest.mark.slow
def test_the_crack_study_with_its_detection_in_the_pool_writes_the_same_files(
        cache, pool, tmp_path, monkeypatch):
    """``crack_study_from_fe`` with the pool (the main job's route: POD runs in the pool,
    the frequency plot drawn meanwhile by ``while_detecting``) against the same study in
    this process: every table, the JSON and the report byte for byte (date aside), and the
    callback saw the spectra before the detection study was there."""
    from test_crack_study import _synthetic_scene
    from test_detection_helpers import synthetic_fe_rows

    from hubvib.studies.crack_study import (crack_study_from_fe, spectrum_plots,
                                            write_crack_study)

    scene = replace(_synthetic_scene("series"), plots=True)
    rows = synthetic_fe_rows(scene.crack.depths)
    here = crack_study_from_fe(scene, rows, timing=TIMING)
    write_crack_study(here, tmp_path / "here")
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "second-cache"))  # all computed again
    seen, begun = [], {}

    def while_detecting(partial):
        seen.append(partial.detection)
        begun["spectrum_plots"] = spectrum_plots(scene, partial, tmp_path / "pooled")

    pooled = crack_study_from_fe(scene, rows, timing=TIMING, pool=pool,
                                 while_detecting=while_detecting)
    write_crack_study(pooled, tmp_path / "pooled", begun)
    assert seen == [None], "while_detecting runs before the detection study is assembled"
    written = sorted(p.name for p in (tmp_path / "here").iterdir())
    assert written == sorted(p.name for p in (tmp_path / "pooled").iterdir())
    for name in written:
        a, b = ((tmp_path / side / name).read_bytes() for side in ("here", "pooled"))
        if name in ("report.md", "results.json"):  # the run's date is in them
            a, b = (re.sub(rb"\d{4}-\d\d-\d\d \d\d:\d\d UTC", b"DATE", x) for x in (a, b))
        assert a == b, f"{name}: pool route vs one process"
