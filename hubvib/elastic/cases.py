"""One crack depth of the elastic ring as a cacheable case: the coupled spectra with
planet 1 away from and on the cracked tooth (SI)."""
from __future__ import annotations

from dataclasses import dataclass

from .model import elastic_ring, elastic_spectrum, out_of_contact_tooth
from .options import ElasticScene


@dataclass(frozen=True, eq=False)
class ElasticCase:
    """One crack depth on the elastic ring: the spectra with planet 1 away from and on the
    cracked tooth (their ``ring`` dropped: light to pickle)."""

    depth: float
    away: object
    on: object
    k_rest: float
    foundation: tuple | None
    ring_dofs: int
    ring_mass: float


def carrier_positions(design, tooth: int) -> tuple[int, int]:
    """Planet 1's ring tooth away from (half a planet pitch) and on the cracked tooth."""
    from hubvib.build.stages import ring_gear

    z = ring_gear(design).teeth
    return (tooth + out_of_contact_tooth(z, design.n_planets)) % z, tooth


def elastic_case(design, crack, scene: ElasticScene, k_rest: float) -> ElasticCase:
    """The coupled spectra of one crack (``crack`` None or of depth 0: intact), faces open."""
    from dataclasses import replace

    tooth = 0 if crack is None else crack.tooth
    away, on = carrier_positions(design, tooth)
    er = elastic_ring(design, crack if crack is not None and crack.depth > 0 else None, False,
                      scene.options, (away, on), k_rest=k_rest)
    return ElasticCase(
        0.0 if crack is None else float(crack.depth),
        replace(elastic_spectrum(er, away), ring=None),
        replace(elastic_spectrum(er, on), ring=None), er.k_rest,
        None if er.foundation is None else (er.foundation.k_n, er.foundation.k_t),
        er.body.ndofs, float(er.body.rigid_mass()[0, 0]))


def cached_case(design, crack, scene: ElasticScene, k_rest: float) -> ElasticCase:
    """``elastic_case`` through the result cache (inputs and this computation's source)."""
    from hubvib.runtime.result_cache import cached_result

    inputs = (design.fingerprint(), crack, scene.options, float(k_rest))
    return cached_result("elastic-case", inputs, (__name__,),
                         lambda: elastic_case(design, crack, scene, k_rest), ElasticCase)
