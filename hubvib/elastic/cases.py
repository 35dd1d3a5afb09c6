"""One crack depth of the elastic ring as a cacheable case: the coupled spectra with
planet 1 away from and on the cracked tooth, and the reduced ring's operators (SI)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .model import elastic_ring, elastic_spectrum, lowest_ring_mode, out_of_contact_tooth
from .options import ElasticScene


@dataclass(frozen=True, eq=False)
class ElasticCase:
    """One crack depth on the elastic ring: the spectra with planet 1 away from and on the
    cracked tooth (their ``ring`` dropped: light to pickle).

    ``operators``: the reduced ring (``lumped.elastic_ring.RingOperators``, dense, M = I);
    ``foundation_K``: the mounting's part of its reduced stiffness [N/m] (zeros unless on
    a foundation), so that the mounting can be varied apart from the ring body;
    ``params``: the lumped model the ring is coupled to; ``validity``: for the intact
    ring, the rigid-ring model's band (``validity.validity_band``, planet 1 away from the
    tooth) from the same ring; ``pitch``: the spectra over one planet pitch from the
    cracked tooth (``loaded.PitchSpectra``: the ring as built at every position and, when
    cracked, the crack as the working load leaves it for every load variant; None on a
    free ring).
    """

    depth: float
    away: object
    on: object
    k_rest: float
    foundation: tuple | None
    ring_dofs: int
    ring_mass: float
    lowest_ring_mode: tuple | None = None  # (Hz, nodal diameters) of the mounted ring alone
    operators: object = None
    foundation_K: np.ndarray | None = None
    params: object = None
    validity: object = None
    pitch: object = None


def carrier_positions(design, tooth: int) -> tuple[int, int]:
    """Planet 1's ring tooth away from (half a planet pitch) and on the cracked tooth."""
    from hubvib.reducer.stages import ring_gear

    z = ring_gear(design).teeth
    return (tooth + out_of_contact_tooth(z, design.n_planets)) % z, tooth


def reduced_foundation(er) -> np.ndarray:
    """The foundation's part of the reduced ring stiffness ``V^T F V`` [N/m] (zeros when
    the ring is not on a foundation)."""
    size = er.basis.size
    if er.foundation is None:
        return np.zeros((size, size))
    from hubvib.fem.ring_body import support_springs

    body = er.body
    normal, tangential = support_springs(body.model)
    F = body.expand.T @ ((er.foundation.k_n * normal + er.foundation.k_t * tangential)
                         @ body.expand)
    V = er.basis.V
    reduced = V.T @ (F @ V)
    return 0.5 * (reduced + reduced.T)


def elastic_case(design, crack, scene: ElasticScene, k_rest: float,
                 torque_fractions=None, closure_gaps=None) -> ElasticCase:
    """The coupled spectra of one crack (``crack`` None or of depth 0: intact), faces open;
    on a mounted ring also over the pitch, about the working load's crack states for
    ``torque_fractions`` (of the design's sun torque) x ``closure_gaps`` [m] (default
    ``loaded.TORQUE_FRACTIONS`` x ``loaded.CLOSURE_GAPS``)."""
    from .loaded import CLOSURE_GAPS, TORQUE_FRACTIONS

    from dataclasses import replace

    from hubvib.reducer.stages import mesh_force

    from .crack_state import pitch_teeth
    from .loaded import pitch_spectra

    tooth = 0 if crack is None else crack.tooth
    away, on = carrier_positions(design, tooth)
    intact = crack is None or crack.depth == 0
    mounted = scene.options.mounting != "free"
    pitch_positions = pitch_teeth(_teeth(design), design.n_planets, tooth) if mounted else ()
    # a crack through the rim has no tip: its faces are left free (nothing to pair)
    paired = mounted and not intact and not crack.is_through(_ring(design))
    er = elastic_ring(design, None if intact else crack, False, scene.options, (away, on),
                      k_rest=k_rest, more_positions=pitch_positions, crack_faces=paired)
    pitch = pitch_spectra(
        er, tooth, away, design.sun_torque, mesh_force(design),
        TORQUE_FRACTIONS if torque_fractions is None else tuple(torque_fractions),
        CLOSURE_GAPS if closure_gaps is None else tuple(closure_gaps)) if mounted else None
    validity = None
    if intact and scene.options.mounting != "free":
        from .validity import validity_band

        validity = validity_band(design, scene.options, carrier_tooth=away, er=er)
    return ElasticCase(
        0.0 if crack is None else float(crack.depth),
        replace(elastic_spectrum(er, away), ring=None),
        replace(elastic_spectrum(er, on), ring=None), er.k_rest,
        None if er.foundation is None else (er.foundation.k_n, er.foundation.k_t),
        er.body.ndofs, float(er.body.rigid_mass()[0, 0]), lowest_ring_mode(er),
        er.operators, reduced_foundation(er), er.params, validity, pitch)


def _ring(design):
    from hubvib.reducer.stages import ring_gear

    return ring_gear(design)


def _teeth(design) -> int:
    return _ring(design).teeth


def cached_case(design, crack, scene: ElasticScene, k_rest: float) -> ElasticCase:
    """``elastic_case`` through the result cache (inputs and this computation's source)."""
    from hubvib.runtime.result_cache import cached_result

    inputs = (design.fingerprint(), crack, scene.options, float(k_rest))
    return cached_result("elastic-case", inputs, (__name__,),
                         lambda: elastic_case(design, crack, scene, k_rest), ElasticCase)
