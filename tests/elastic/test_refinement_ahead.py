"""The elastic sweep's refinement with a worker pool computes ahead, on the pool, the depth
each later record length asks for, and adds exactly the depths (and so gives exactly the
answer) of the sequential rule without one."""
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from hubvib.elastic.options import parse_elastic_table


@pytest.mark.slow
def test_the_pool_computes_ahead_and_the_answer_is_the_sequential_one(monkeypatch):
    from tests.elastic.test_elastic_diagnose import _synthetic_cases

    from hubvib.detection import elastic_model
    from hubvib.detection import options as detection_options
    from hubvib.detection.elastic_refinement import refined_elastic
    from hubvib.studies.scene import load_scene

    deepest = 0.05  # a crack weak enough that the record lengths' brackets part
    asked = []  # (depth [m], thread name)

    def case_at(design, crack, scene, k_rest):
        asked.append((crack.depth, threading.current_thread().name))
        return _synthetic_cases((0.0, crack.depth, deepest))[1]

    monkeypatch.setattr(elastic_model, "cached_case", case_at)
    options = replace(detection_options.detection_options(load_scene(None)), samples=100)
    es = parse_elastic_table({"ring": "both"})
    depths = (0.0, 0.004, 0.008, deepest)
    cases = _synthetic_cases(depths)
    first = elastic_model.elastic_result(None, depths, lambda d: None, es, options, cases)

    def crack_of(depth):
        return SimpleNamespace(depth=depth)

    alone, _ = refined_elastic(None, crack_of, es, options, first, cases)
    sequential = [d for d, _ in asked]
    asked.clear()
    with ThreadPoolExecutor(1, thread_name_prefix="pool") as pool:
        ahead, ahead_cases = refined_elastic(None, crack_of, es, options, first, cases,
                                             pool=pool)
    assert ahead.depths == alone.depths and ahead.added_depths == alone.added_depths, \
        "the same depths as the sequential rule"
    for t in alone.lengths:
        assert np.array_equal(ahead.pod[t], alone.pod[t]), t
        assert ahead.bracket(t) == alone.bracket(t), t
    assert len(ahead_cases) == len(ahead.depths)
    on_pool = {d for d, name in asked if name.startswith("pool")}
    assert on_pool, "some depth was computed ahead on the pool"
    assert set(sequential) <= {d for d, _ in asked}, "every depth the rule adds was computed"
