"""The elastic ring beside the plane crack study: its crack cases begun behind the FE
cases (in the pool, or taken back into this process), its detection answer with the
rigid-ring model's validity band, the depths it adds to resolve where the POD crosses the
required probability, and the elastic map (depths in metres)."""
from __future__ import annotations

from concurrent.futures import Future

from hubvib.cases.sweep import crack_of
from hubvib.reducer.stages import ring_gear
from hubvib.runtime.claims import Claims
from hubvib.runtime.engines import EngineError, Execution, run_cases
from hubvib.studies.kind_registry import Scene

__all__ = ["begin_elastic", "elastic_depths", "elastic_load_sensitivity", "elastic_map_of",
           "elastic_pad_variant", "finish_elastic", "refine_elastic", "THROUGH_RIM",
           "left_out_depths"]

#: why the elastic ring leaves a depth out
THROUGH_RIM = ("through the rim: the ring is opened, its modes no longer continue the intact "
               "ones")


def _elastic_scene(scene: Scene):
    table = scene.elastic
    return table if table.elastic and scene.crack.model == "plane" else None


def begin_elastic(scene: Scene, pool):
    """The elastic ring's crack cases as futures, or their arguments to compute in this
    process (no pool); None when the scene runs the rigid ring only.

    With a pool every case is queued there, behind what is queued already, and this
    process computes, the deepest first, every case no worker has begun (each claimed by
    whoever begins it first, ``runtime.claims``; the executor's call queue included), as a
    worker would (one BLAS thread): while the workers run the FE cases and renders ahead,
    it would only wait for them.  The intact case brings the rigid-ring model's validity
    band, computed from its own ring."""
    elastic = _elastic_scene(scene)
    if elastic is None:
        return None
    from hubvib.detection.elastic_model import cached_case, case_arguments

    sweep = scene.crack
    depths = elastic_depths(sweep)
    arguments = case_arguments(sweep.reducer, depths, lambda d: crack_of(sweep, d), elastic)
    if pool is None:
        return arguments
    work = [(cached_case, a, f"elastic ring at {1e3 * d:g} mm")
            for a, d in zip(arguments, depths)]
    with Claims() as claims:
        futures = [claims.submit(pool, str(k), function, *a)
                   for k, (function, a, _) in enumerate(work)]
        for k in reversed(range(len(futures))):
            if claims.claim(str(k)):  # no worker has begun it (queued, or in the call queue)
                futures[k] = _computed_here(*work[k])
    return futures


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


def finish_elastic(scene: Scene, begun, refine: bool = True, pool=None) -> tuple:
    """The elastic ring's detection answer (``detection.result.DetectionResult``) from the
    cases ``begun_elastic`` began, with the depths :func:`refine_elastic` adds (``refine``),
    the rigid-ring model's validity band its intact case computed (planet 1 where the
    detection's statistic has it, half a planet pitch from the cracked tooth), and the
    ``ElasticCase`` of every depth of the answer (the first intact); with a worker
    ``pool`` the refinement computes the depths it will ask for next there."""
    from hubvib.detection.elastic_model import cached_case, elastic_result
    from hubvib.detection.elastic_refinement import refined_elastic
    from hubvib.detection.options import detection_options

    cases = [b.result() if hasattr(b, "result") else cached_case(*b) for b in begun]
    sweep = scene.crack
    es, options = _elastic_scene(scene), detection_options(scene)
    depths = elastic_depths(sweep)
    result = elastic_result(sweep.reducer, depths, lambda d: crack_of(sweep, d), es, options,
                            cases, left_out=left_out_depths(sweep))
    if refine:
        result, cases = refined_elastic(sweep.reducer, lambda d: crack_of(sweep, d), es,
                                        options, result, cases, pool=pool)
    return result, cases[0].validity, cases


def refine_elastic(scene: Scene, result, cases: list, most: int | None = None):
    """``result`` (the elastic ring's ``DetectionResult`` over ``cases``) with depths added
    until, for records of 10, 60 and 600 s, the family POD's crossing of the detection
    probability is resolved (:func:`hubvib.detection.elastic_refinement.refined_elastic`,
    the function the diagnosis refines its elastic model with)."""
    from hubvib.detection.elastic_refinement import refined_elastic
    from hubvib.detection.options import detection_options

    sweep = scene.crack
    refined, _ = refined_elastic(sweep.reducer, lambda d: crack_of(sweep, d),
                                 _elastic_scene(scene), detection_options(scene), result,
                                 cases, most)
    return refined


def elastic_load_sensitivity(scene: Scene, elastic, cases: list) -> tuple:
    """The elastic ring's answer per closure gap and torque fraction
    (``detection.load_sensitivity``) on the depths of ``elastic`` (the refined sweep) and
    their ``cases``, or () when the cases carry no loaded crack."""
    from hubvib.detection.load_sensitivity import load_sensitivity
    from hubvib.detection.options import detection_options

    if cases[0].pitch is None:
        return ()
    sweep = scene.crack
    return load_sensitivity(sweep.reducer, elastic.depths, lambda d: crack_of(sweep, d),
                            _elastic_scene(scene), detection_options(scene), cases)


def elastic_pad_variant(scene: Scene, elastic) -> tuple:
    """``(variant, reason)``: the elastic ring's answer with the crack on a support pad and
    between pads (``detection.pad_variant.PadVariant``) on the sweep's depths, beside
    ``elastic`` (the refined answer); ``(None, why not)`` when the scene
    does not ask for it (``[elastic] pad_variant``) or the ring has no pads to move the
    crack against."""
    from hubvib.meshing.crack import Crack

    es = _elastic_scene(scene)
    if es is None or elastic is None:
        return None, "the elastic ring did not run"
    if not es.pad_variant:
        return None, "the scene's [elastic] pad_variant is false"
    sweep = scene.crack
    ring = ring_gear(sweep.reducer)
    if ring.supports.count == 0:
        return None, "the ring is held all round its outer surface: it has no pads"
    if es.options.mounting == "free":
        return None, "the elastic ring is free ([elastic] mounting): no pad holds it"
    depths = elastic_depths(sweep)
    if len(depths) < 2 or depths[0] != 0:
        return None, "the sweep has no crack depth the elastic ring is solved at"
    if not isinstance(crack_of(sweep, depths[-1]), Crack):
        return None, "the sweep's crack follows a predicted path, computed for its own tooth"
    from hubvib.detection.options import detection_options
    from hubvib.detection.pad_variant import pad_variant

    return pad_variant(sweep.reducer, lambda d: crack_of(sweep, d), es,
                       detection_options(scene), elastic, depths, ring), ""


def elastic_map_of(scene: Scene, elastic):
    """The elastic ring's detectability against the foundation scale when ``[elastic]
    map`` asks (else None), a ``detection.mounting_map.MountingMap`` (its rings through
    the result cache) over the depths of ``elastic`` (the elastic ring's refined answer:
    the sweep's depths the ring is solved at and those added to resolve its crossing)."""
    es = _elastic_scene(scene)
    if not es.map:
        return None
    from hubvib.detection.mounting_map import ElasticMounting
    from hubvib.detection.options import detection_options
    from hubvib.detection.pod import family_pod

    sweep = scene.crack
    mounting = ElasticMounting(sweep.reducer, tuple(elastic.depths),
                               lambda d: crack_of(sweep, d), es, pod=family_pod,
                               k_rest=elastic.detail.k_rest)
    return mounting.mounting_map(detection_options(scene))


def elastic_depths(sweep) -> tuple:
    """The sweep's depths the elastic ring is solved at: all but a crack through the rim
    (it opens the ring; its modes no longer continue the intact ring's)."""
    ring = ring_gear(sweep.reducer)
    return tuple(d for d in sweep.depths if d == 0 or not crack_of(sweep, d).is_through(ring))


def left_out_depths(sweep) -> tuple:
    """The sweep's depths the elastic ring leaves out, each with the reason [m]."""
    kept = set(elastic_depths(sweep))
    return tuple((float(d), THROUGH_RIM) for d in sweep.depths if d not in kept)
