"""The elastic ring beside the plane crack study: its crack cases begun behind the FE
cases (in the pool, or taken back into this process), its detection answer, the rigid-ring
model's validity band and the elastic map (depths in metres)."""
from __future__ import annotations

from concurrent.futures import Future

from hubvib.cases.sweep import crack_of
from hubvib.reducer.stages import ring_gear
from hubvib.runtime.engines import EngineError, Execution, run_cases, submit
from hubvib.studies.kind_registry import Scene

__all__ = ["begin_elastic", "elastic_band_and_map", "elastic_depths", "finish_elastic"]


def _elastic_scene(scene: Scene):
    table = scene.tables.get("elastic")
    return table if table is not None and table.elastic and scene.crack.model == "plane" \
        else None


def begin_elastic(scene: Scene, pool):
    """The elastic ring's crack cases as futures, or their arguments to compute in this
    process (no pool); None when the scene runs the rigid ring only.

    With a pool every case is queued there, behind what is queued already, and this
    process takes back the cases no worker has started, the deepest first, and computes
    them here (as a worker would: one BLAS thread) until the workers reach the rest: while
    they run the FE cases ahead, it would only wait for them.  The validity band
    (``elastic_band_and_map``) goes first the same way, into the result cache, where the
    band's own call then finds it."""
    elastic = _elastic_scene(scene)
    if elastic is None:
        return None
    from hubvib.detection.elastic import cached_case, case_arguments
    from hubvib.elastic.validity import cached_validity_band

    sweep = scene.crack
    depths = elastic_depths(sweep)
    arguments = case_arguments(sweep.reducer, depths, lambda d: crack_of(sweep, d), elastic)
    if pool is None:
        return arguments
    work = [(cached_case, a, f"elastic ring at {1e3 * d:g} mm")
            for a, d in zip(arguments, depths)]
    work.append((cached_validity_band, _validity_band_arguments(scene),
                 "the rigid-ring model's validity band"))
    futures = [submit(pool, function, *a) for function, a, _ in work]
    for k in reversed(range(len(futures))):
        if not futures[k].cancel():  # a worker has it: the earlier ones are theirs too
            break
        futures[k] = _computed_here(*work[k])
    return futures[:len(arguments)]  # the band's result stays in the result cache


def _computed_here(function, arguments: tuple, label: str) -> Future:
    """``function(*arguments)`` run in this process as on a pool worker
    (``runtime.engines.run_cases`` with one worker), as a finished future (its failure as
    the future's ``EngineError``)."""
    done = Future()
    try:
        run_cases(lambda _: function(*arguments), [label],
                  lambda _, result: done.set_result(result), Execution(), 1)
    except EngineError as error:
        done.set_exception(error)
    return done


def finish_elastic(scene: Scene, begun):
    """The elastic ring's detection answer from the cases ``begin_elastic`` began."""
    from hubvib.detection.elastic import cached_case, elastic_detection
    from hubvib.detection.options import detection_options

    cases = [b.result() if hasattr(b, "result") else cached_case(*b) for b in begun]
    sweep = scene.crack
    return elastic_detection(sweep.reducer, elastic_depths(sweep),
                             lambda d: crack_of(sweep, d), _elastic_scene(scene),
                             detection_options(scene), cases)


def elastic_band_and_map(scene: Scene, elastic) -> tuple:
    """The rigid-ring model's computed validity band on the scene's mounting (planet 1 where
    the detection's statistic has it) and, when ``[elastic] map`` asks, the elastic ring's
    detectability against the foundation scale; both through the result cache."""
    from hubvib.elastic.validity import cached_validity_band

    es = _elastic_scene(scene)
    sweep = scene.crack
    band = cached_validity_band(*_validity_band_arguments(scene))
    if not es.map:
        return band, None
    from hubvib.detection.elastic import family_pod
    from hubvib.detection.elastic_map import elastic_map
    from hubvib.detection.options import detection_options

    emap = elastic_map(sweep.reducer, elastic_depths(sweep), lambda d: crack_of(sweep, d), es,
                       detection_options(scene), pod=family_pod, k_rest=elastic.k_rest)
    return band, emap


def _validity_band_arguments(scene: Scene) -> tuple:
    """The arguments of ``cached_validity_band`` for the scene: its design and elastic
    options, planet 1 away from the cracked tooth."""
    from hubvib.elastic.cases import carrier_positions

    sweep = scene.crack
    away = carrier_positions(sweep.reducer, crack_of(sweep, sweep.depths[-1]).tooth)[0]
    return sweep.reducer, _elastic_scene(scene).options, away


def elastic_depths(sweep) -> tuple:
    """The sweep's depths the elastic ring is solved at: all but a crack through the rim
    (it opens the ring; its modes no longer continue the intact ring's)."""
    ring = ring_gear(sweep.reducer)
    return tuple(d for d in sweep.depths if d == 0 or not crack_of(sweep, d).is_through(ring))

