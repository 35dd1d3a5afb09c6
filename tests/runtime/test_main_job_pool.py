"""The main job's shared worker pool: the FE cases and then the renders on the same warm
workers.  The numbers and pictures are the same as in one process (exact), a cached
rerun submits nothing (counted, not timed), and the benchmark's per-stage seconds add up."""
import json
import shutil
from dataclasses import replace

import pytest

from hubvib.benchmarks.main_job import STAGES, stage_breakdown
from hubvib.render.cache import cached_render
from hubvib.runtime import stage_seconds
from hubvib.runtime.process_pool import worker_pool
from hubvib.render import schedule
from hubvib.studies import elastic_stage
from hubvib.studies.scene import load_scene


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    return tmp_path


class _CountingPool:
    """Stands in for a ``worker_pool``: counts what is submitted, runs nothing."""

    def __init__(self):
        self.submitted = []

    def submit(self, function, *args):
        from hubvib.runtime.claims import claimed_call

        # a claimed task (``runtime.claims``): the work it wraps
        self.submitted.append((args[2] if function is claimed_call else function).__name__)
        return None


def _fill_render_cache(kind, inputs, tmp_path):
    """A complete, checked render cache entry for ``inputs`` (a stand-in picture)."""
    def render(target):
        target.mkdir(parents=True, exist_ok=True)
        (target / "picture.png").write_bytes(b"png")
        return [target / "picture.png"]

    cached_render(kind, inputs, tmp_path / "first", render,
                  schedule.FE_SOURCE if kind == "fe-ring" else schedule.MODES_SOURCE)


def test_renders_are_submitted_only_when_the_render_cache_lacks_them(cache):
    """Counter, not time: the default scene submits the FE ring's render and the modes'
    render once each on an empty render cache, and nothing once the cache holds them (a
    cached rerun computes no picture and starts no worker)."""
    from hubvib.reducer import lumped_preset
    from hubvib.lumped import natural_modes

    scene = load_scene(None)
    spectrum = natural_modes(lumped_preset("raba118"), scene.method)
    pool, begun = _CountingPool(), {}
    schedule.begin_renders(scene, cache / "out", pool, begun)
    schedule.begin_renders(scene, cache / "out", pool, begun)  # queued, then FE done
    schedule.begin_renders(scene, cache / "out", pool, begun, spectrum)
    assert pool.submitted == ["render_fe_ring", "render_mode_shapes"], \
        f"an empty render cache: both renders go to the pool once, got {pool.submitted}"
    assert set(begun) == {"fe", "modes"}
    _fill_render_cache("fe-ring", schedule._fe_render_case(scene.crack, scene.vtm)[2],
                       cache)
    _fill_render_cache("modes", schedule._mode_render_inputs(
        scene.params, spectrum, scene.gif, scene.vtm), cache)
    pool, begun = _CountingPool(), {}
    schedule.begin_renders(scene, cache / "out", pool, begun)
    schedule.begin_renders(scene, cache / "out", pool, begun, spectrum)
    assert pool.submitted == [] and begun == {}, \
        f"the render cache holds both: nothing may be submitted, got {pool.submitted}"


class _StartedPool(_CountingPool):
    """A ``_CountingPool`` whose workers have begun the first ``started`` cases it is given
    (claimed them, ``runtime.claims``; their futures cannot be cancelled) and moved the next
    ``queued`` to the executor's call queue (cannot be cancelled either, not begun), the
    rest still queued; it records the BLAS environment of each submit (what a worker
    spawned there would get)."""

    def __init__(self, started, queued=0):
        super().__init__()
        self.started, self.queued, self.environments = started, queued, []

    def submit(self, function, *args):
        import os
        from concurrent.futures import Future

        from hubvib.runtime.engines import SINGLE_THREADED

        self.environments.append({key: os.environ.get(key) for key in SINGLE_THREADED})
        super().submit(function, *args)
        from hubvib.runtime.claims import _claim

        future = Future()
        if len(self.submitted) <= self.started + self.queued:
            future.set_running_or_notify_cancel()
        if len(self.submitted) <= self.started:
            assert _claim(args[0], args[1]), "a worker claims a case no one has"
        return future


@pytest.mark.parametrize("started,queued", [(99, 0), (5, 0), (2, 3)])
def test_elastic_cases_the_workers_have_not_started_are_computed_here(cache, monkeypatch,
                                                                      started, queued):
    """Counter, not time: the default scene queues one elastic case per depth (the crack
    through the rim left out), each submitted with one BLAS thread in the environment
    (``runtime.engines.SINGLE_THREADED``), as the FE cases; what no worker has begun is
    computed in this process, the deepest cases first, with one BLAS thread as on a worker
    (the same digits), also a case the executor has moved to its call queue (its future
    cannot be cancelled, and the workers may be busy with a render for seconds); the
    cases come back as finished futures in depth order."""
    from hubvib.detection import elastic_model as detection_elastic
    from hubvib.elastic import rest
    from hubvib.foundation.blas import blas_thread_counts
    from hubvib.runtime.engines import SINGLE_THREADED

    monkeypatch.setattr(rest, "rest_stiffness", lambda design, method="fe": 2e9)
    here = []

    def case_here(design, crack, scene, k_rest):
        here.append((0.0 if crack is None else crack.depth, set(blas_thread_counts())))
        return ("case", here[-1][0])

    monkeypatch.setattr(detection_elastic, "cached_case", case_here)
    scene = load_scene(None)
    depths = elastic_stage.elastic_depths(scene.crack)
    assert len(depths) == len(scene.crack.depths) - 1
    pool = _StartedPool(started, queued)
    begun = elastic_stage.begin_elastic(scene, pool)
    assert pool.submitted == ["case_here"] * len(depths)
    assert pool.environments == [SINGLE_THREADED] * len(depths), pool.environments
    taken = max(len(depths) - started, 0)
    assert [d for d, _ in here] == list(depths[::-1][:taken]), "the deepest cases first"
    assert len(begun) == len(depths)
    assert all(threads == {1} for _, threads in here), f"one BLAS thread, as a worker: {here}"
    for k, future in enumerate(begun):
        if k < len(depths) - taken:
            assert future.running(), "a case a worker has begun stays the worker's"
        else:
            assert future.result(timeout=0) == ("case", depths[k])


def test_no_renders_no_pool_work(cache):
    """A scene without renders (or without a pool) submits nothing."""
    scene = replace(load_scene(None), renders=False)
    pool, begun = _CountingPool(), {}
    schedule.begin_renders(scene, cache / "out", pool, begun)
    schedule.begin_renders(load_scene(None), cache / "out", None, begun)
    assert pool.submitted == [] and begun == {}


def test_stage_breakdown_adds_up_to_the_wall_time():
    """The disjoint stages of ``main_job_stage_seconds`` sum to the measured total (the
    nested ``write`` holds ``plots`` and ``render``)."""
    parts = {"fe": 20.0, "lumped": 0.5, "detection": 8.0, "write": 12.0, "plots": 4.0,
             "render": 6.0}
    out = stage_breakdown(parts, total=45.0)
    assert tuple(out) == STAGES
    assert out["write"] == 2.0 and out["other"] == 4.5, out
    assert sum(out.values()) == pytest.approx(45.0, abs=1e-9), \
        "stages must add up to the run's wall time (exact arithmetic, rounding to 0.01 s)"


def test_timed_parts_are_written_on_request(tmp_path, monkeypatch):
    """``timed`` adds up per part; ``write_requested`` writes them to the file the
    environment names (what ``hubvib benchmark`` reads), and nothing without it."""
    monkeypatch.setattr(stage_seconds, "_SECONDS", {})
    with stage_seconds.timed("fe"):
        pass
    with stage_seconds.timed("fe"):
        pass
    assert set(stage_seconds.stage_seconds()) == {"fe"}
    assert stage_seconds.stage_seconds()["fe"] >= 0.0
    monkeypatch.delenv(stage_seconds.ENV, raising=False)
    stage_seconds.write_requested()
    assert list(tmp_path.iterdir()) == []
    path = tmp_path / "stages.json"
    monkeypatch.setenv(stage_seconds.ENV, str(path))
    stage_seconds.write_requested()
    assert json.loads(path.read_text()) == stage_seconds.stage_seconds()


@pytest.mark.slow
def test_fe_cases_in_the_shared_pool_equal_one_process(cache):
    """Two FE cases (Raba ring, fast accuracy) in a shared pool of 2 workers and in this
    process give the same values to round-off (one BLAS thread each: the same arithmetic;
    MKL's PARDISO without conditional numerical reproducibility may still differ in the
    last bits with memory alignment: a CI run saw 2.6e-12 relative in an error estimate,
    a difference of two ratios); only the wall times differ."""
    pytest.importorskip("gmsh")
    from hubvib.cases.runner import cache_folder, run_fe_cases

    sweep = replace(load_scene(None).crack, depths=(0.0, 0.006), accuracy="fast")
    with worker_pool(2) as pool:
        pooled, computed = run_fe_cases(sweep, progress=False, pool=pool)
    assert computed == 2
    for entry in cache_folder().iterdir():  # the cases and the shared intact tooth curves
        shutil.rmtree(entry) if entry.is_dir() else entry.unlink()
    # and this process's own memory of intact curves, which an earlier test in this
    # process may have filled under other settings: "one process" computes from scratch
    from hubvib.fem import tooth_stiffness

    tooth_stiffness._intact_curve.cache_clear()
    tooth_stiffness._OFFERED.clear()
    here, computed = run_fe_cases(replace(sweep, workers=1), progress=False)
    assert computed == 2

    def numbers(row):
        return {k: v for k, v in row.items() if not k.startswith("seconds")}

    for a, b in zip(pooled, here, strict=True):
        a, b = numbers(a), numbers(b)
        assert a.keys() == b.keys()
        for key in a:
            expected = (pytest.approx(b[key], rel=1e-9, abs=1e-12)
                        if isinstance(b[key], float) else b[key])
            assert a[key] == expected, \
                f"{key}: pool and serial FE cases agree to round-off (1e-9 relative)"


@pytest.mark.slow
def test_mode_renders_in_a_worker_equal_this_process(tmp_path, monkeypatch):
    """The lumped mode pictures rendered on a pool worker are byte-identical to those
    rendered here (each from an empty render cache)."""
    pytest.importorskip("pyvista")
    from hubvib.reducer import lumped_preset
    from hubvib.lumped import natural_modes
    from hubvib.runtime.engines import submit

    params = lumped_preset("raba118")
    spectrum = natural_modes(params, "jacobi")
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache-worker"))
    with worker_pool(1) as pool:
        there = submit(pool, schedule.render_mode_shapes, params, spectrum, False, False,
                       tmp_path / "worker").result()
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache-here"))
    here = schedule.render_mode_shapes(params, spectrum, False, False, tmp_path / "here")
    assert [p.name for p in there] == [p.name for p in here] and len(here) >= 10
    for a, b in zip(there, here):
        assert a.read_bytes() == b.read_bytes(), f"{a.name}: worker and here differ"


def test_a_render_whose_worker_died_is_one_engine_error():
    """A render future that raises (its worker killed: BrokenProcessPool) becomes one
    ``EngineError`` line naming the render, as a failed FE case does; the CLI prints it
    without a traceback."""
    from concurrent.futures import Future
    from concurrent.futures.process import BrokenProcessPool

    from hubvib.runtime.engines import EngineError
    from hubvib.render.schedule import _rendered

    done = Future()
    done.set_result(["a.png"])
    assert _rendered(done, "FE ring") == ["a.png"]
    broken = Future()
    broken.set_exception(BrokenProcessPool("a child process terminated abruptly"))
    with pytest.raises(EngineError, match="the FE ring render failed on a pool worker: "
                                          "BrokenProcessPool"):
        _rendered(broken, "FE ring")
