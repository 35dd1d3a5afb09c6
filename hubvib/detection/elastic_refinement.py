"""The elastic ring's sweep refined where its POD crosses the required probability: depths
added by bisection (:mod:`.resolution`) per record length, each new ``ElasticCase`` through
the result cache.  One function for the crack study (``hubvib run``) and the diagnosis
(``hubvib diagnose --ring elastic``), so both see the same depths [m]."""
from __future__ import annotations

from dataclasses import replace

__all__ = ["REFINED", "refined_elastic"]

#: how the elastic ring's sweep resolves the POD crossing, in words
REFINED = ("depths added by bisection below the first detectable one, per record length "
           "(at most {most} each, shared where they coincide), until the POD {p:g} crossing "
           "is bracketed within {width:g} mm or {floor:g} mm is reached")


def refined_elastic(design, crack_of, scene, options, result, cases: list,
                    most: int | None = None, pool=None) -> tuple:
    """``(result, cases)``: ``result`` (the elastic ring's ``DetectionResult`` over
    ``cases``, one ``ElasticCase`` per depth, the first intact) with depths added until, for
    records of 10, 60 and 600 s, the family POD's crossing of the detection probability is
    resolved (bisection, at least ``resolution.FLOOR`` deep, at most ``most`` per record
    length, default ``resolution.MAX_ADDED``; a depth added for one length serves the
    others), and the cases of every depth, added ones in depth order.

    ``crack_of(depth)``: the ``Crack`` of a depth [m]; ``scene``: the ``[elastic]`` table;
    ``options``: the ``DetectionOptions``.  With a worker ``pool``, while this process
    computes the depth one record length asks for next, the depth each later record length
    asks for now is computed on the pool (taken back here when no worker has begun it,
    ``runtime.claims``): the depths added, and so the answer, are those of the sequential
    rule."""
    from hubvib.runtime.claims import Claims

    from . import elastic_model
    from .pod import RECORD_LENGTHS
    from .resolution import FLOOR, MAX_ADDED, RESOLUTION, next_depth

    most = MAX_ADDED if most is None else most
    words = REFINED.format(most=most, p=options.detection_probability,
                           width=1e3 * RESOLUTION, floor=1e3 * FLOOR)
    depths, cases, added = list(result.depths), list(cases), list(result.added_depths)
    k_rest = cases[0].k_rest
    ahead = {}  # depth [m] -> the pool's future of its case

    claims = Claims() if pool is not None else None

    def case_of(depth):
        future = ahead.pop(depth, None)
        if future is not None and not claims.claim(repr(depth)):  # a worker has begun it
            return future.result()
        return elastic_model.cached_case(design, crack_of(depth), scene, k_rest)

    try:
        for n, length in enumerate(RECORD_LENGTHS):
            for _ in range(most):
                depth = next_depth(result.bracket(length))
                if depth is None:
                    break
                if pool is not None:
                    for later in RECORD_LENGTHS[n + 1:]:
                        other = next_depth(result.bracket(later))
                        if other not in (None, depth) and other not in depths \
                                and other not in ahead:
                            ahead[other] = claims.submit(pool, repr(other),
                                                         elastic_model.cached_case, design,
                                                         crack_of(other), scene, k_rest)
                at = next(k for k, d in enumerate(depths + [float("inf")]) if d > depth)
                depths.insert(at, depth)
                cases.insert(at, case_of(depth))
                added.append(depth)
                result = elastic_model.elastic_result(
                    design, depths, crack_of, scene, options, cases, tuple(sorted(added)),
                    words, result.left_out)
    finally:
        if claims is not None:  # asked ahead and not begun: not needed, dropped
            claims.close()
    if not added:
        result = replace(result, refinement=words + "; none was needed")
    return result, cases
