"""The crack of the Raba ring as the working load leaves it: Signorini's conditions
checked on the full FE ring, the load's size and sign, and the modes about the loaded
state against the tied-faces and the open-faces rings (``hubvib.elastic.crack_state``,
``hubvib.elastic.loaded``)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from hubvib.design.presets import preset_design
from hubvib.elastic.crack_state import crack_state, pitch_teeth
from hubvib.elastic.loaded import CARRIER_SPEED, DAMPING_RATIO, loaded_modes
from hubvib.elastic.model import elastic_ring, elastic_spectrum
from hubvib.elastic.options import ElasticScene
from hubvib.meshing.crack import Crack

DEPTH = 0.006
AWAY, ON = 11, 0  # Raba: z = 64, N = 3; half a pitch is round(64 / 6) = 11 teeth


def test_record_constants_are_the_detection_defaults():
    from hubvib.detection.options import DetectionOptions

    o = DetectionOptions()
    assert DAMPING_RATIO == o.damping_ratio and CARRIER_SPEED == pytest.approx(
        o.carrier_speed, rel=1e-15), "the record's damping and carrier speed are the " \
        "detection's defaults (one source per fact, the layer below cannot import them)"


@pytest.fixture(scope="module")
def rings():
    design = preset_design("raba118")
    options = ElasticScene().options
    crack = Crack(depth=DEPTH)
    full = elastic_ring(design, crack, False, options, (AWAY, ON),
                        more_positions=pitch_teeth(64, 3, 0), crack_faces=True)
    plain = elastic_ring(design, crack, False, options, (AWAY, ON), k_rest=full.k_rest)
    tied = elastic_ring(design, crack, True, options, (AWAY, ON), k_rest=full.k_rest)
    from hubvib.reducer.stages import mesh_force

    return design, full, plain, tied, mesh_force(design)


def _engaged(er, position):
    from hubvib.lumped.elastic_ring import engagement

    return engagement(er.params, er.operators, position).teeth


@pytest.mark.slow
def test_signorini_on_the_full_ring(rings):
    """At every position of the pitch: force >= 0, no penetration, complementarity, and the
    condensed openings equal a full FE solve with the contact forces applied."""
    from hubvib.fem.solvers import factorise, pick

    _, er, _, _, force = rings
    body, pairs = er.body, er.contact.pairs
    factor = factorise(body.K, pick("auto", body.ndofs, 1))
    try:
        for position in pitch_teeth(64, 3, 0):
            teeth = _engaged(er, position)
            state, solution = crack_state(er.contact, position, teeth, force, 1e-6)
            load = force * np.asarray(body.contact[:, list(teeth)].sum(axis=1)).ravel()
            u = np.asarray(factor.solve(load + pairs.G_n.T @ solution.force)).ravel()
            w = pairs.G_n @ u - 1e-6
            scale = np.abs(force * er.contact.tooth_opening[:, list(teeth)].sum(axis=1)).max()
            assert solution.force.min() >= 0, "contact force >= 0"
            assert w.min() >= -1e-9 * scale, (
                f"tooth {position}: penetration {w.min():.3g} m beyond round-off of the "
                f"opening scale {scale:.3g} m (full FE solve)")
            assert abs(solution.force @ w) <= 1e-9 * scale * solution.force.sum(), (
                "complementarity force . gap = 0 (full FE solve), 1e-9 of the opening scale")
            np.testing.assert_allclose(np.maximum(w, 0), solution.gap, rtol=0,
                                       atol=1e-9 * scale,
                                       err_msg="condensed gaps vs the full FE solve")
            assert state.open_length_m == pytest.approx(
                pairs.length[~solution.pressed].sum(), rel=1e-12)
    finally:
        factor.free()


@pytest.mark.slow
def test_load_size_and_sign(rings):
    """Without a closure gap the state is homogeneous of degree one in the load: the same
    pairs apart at a quarter of the torque and the gaps a quarter; the reversed torque
    changes the state at the cracked tooth."""
    _, er, _, _, force = rings
    for position in pitch_teeth(64, 3, 0):
        teeth = _engaged(er, position)
        full, s_full = crack_state(er.contact, position, teeth, force)
        quarter, s_quarter = crack_state(er.contact, position, teeth, 0.25 * force)
        assert full.open_pairs == quarter.open_pairs, "gap 0: state independent of the torque"
        np.testing.assert_allclose(s_quarter.gap, 0.25 * s_full.gap, rtol=1e-9,
                                   atol=1e-12 * s_full.gap.max(initial=1e-6),
                                   err_msg="gap 0: gaps scale with the torque")
    on, _ = crack_state(er.contact, ON, _engaged(er, ON), force)
    reversed_, _ = crack_state(er.contact, ON, _engaged(er, ON), -force)
    assert on.open_length_m > 0 and reversed_.open_length_m < on.open_length_m, (
        "planet 1 on the cracked tooth opens its crack; the reversed load closes it")


@pytest.mark.slow
def test_modes_about_all_closed_and_all_open(rings):
    """All pairs stuck: the tied-faces ring (closed=True); all open: the open ring; a
    position's ring without the pairs: the ring built for the positions; sliding faces
    (fewer ties) lower every frequency (Rayleigh's interlacing)."""
    _, full, plain, tied, _ = rings
    n = full.contact.pairs.count
    for position in (AWAY, ON):
        stuck = loaded_modes(full, position, np.ones(n, bool), True).frequency_hz
        slip = loaded_modes(full, position, np.ones(n, bool), False).frequency_hz
        opened = loaded_modes(full, position, np.zeros(n, bool)).frequency_hz
        t = elastic_spectrum(tied, position).frequency_hz
        o = elastic_spectrum(plain, position).frequency_hz
        m = min(stuck.size, t.size)
        np.testing.assert_allclose(stuck[:m], t[:m], rtol=3e-5, err_msg=(
            "every pair stuck vs the tied-faces ring: ties exact on the open ring's modes "
            "plus every pair's static response, both Ritz reductions of one FE model; the "
            "stuck ring's reduction error against the full tied FE is up to 1.2e-5 (0.1 Hz "
            "at 8.6 kHz), so rtol 3e-5"))
        m = min(opened.size, o.size)
        np.testing.assert_allclose(opened[:m], o[:m], rtol=1e-5, err_msg=(
            "no pair tied vs the open-faces ring (a larger Ritz basis of one model), 1e-5"))
        m = min(slip.size, stuck.size)
        assert np.all(slip[:m] <= stuck[:m] * (1 + 1e-6)), (
            "sliding faces: fewer constraints, no frequency rises (interlacing; 1e-6: the "
            "rank decisions on nearly dependent ties move the 45 Hz mode by ~1e-7)")
        lead = _without_pairs(full, position).frequency_hz
        np.testing.assert_allclose(lead, o, rtol=1e-6, err_msg=(
            "a position's reduced ring without the pairs (its three engaged teeth) vs "
            "ring_basis's for the six teeth of both positions: Ritz reductions of one "
            "model, rtol 1e-6"))
        assert np.all(lead >= o * (1 - 1e-9)), (
            "the position's basis is a subspace of the six-teeth basis: no frequency lower "
            "(Rayleigh-Ritz; 1e-9: round-off)")
        np.testing.assert_allclose(elastic_spectrum(full, position).frequency_hz, o,
                                   rtol=1e-12, err_msg="asking for the pitch and the pairs "
                                   "leaves the ring's own basis as it was")


def _without_pairs(er, position):
    from hubvib.fem.ring_positions import position_basis
    from hubvib.lumped.elastic_ring import RingOperators, coupled_modes

    pb = position_basis(er.positions, _engaged(er, position), functionals=False)
    o = er.operators
    ops = RingOperators(pb.K, np.eye(pb.K.shape[0]), pb.contact, o.moment_sign,
                        o.patch_angles, o.directions, pb.probe)
    return coupled_modes(er.params, ops, position, er.k_rest, max_hz=er.options.band_hz)


@pytest.mark.slow
def test_record_of_the_intact_ring_against_itself(tmp_path, monkeypatch):
    """The intact case's record against itself: no change; with a 3 mm crack every record
    frequency within the instantaneous range and the faces apart at some positions only."""
    from hubvib.elastic.cases import elastic_case
    from hubvib.elastic.loaded import record_track
    from hubvib.elastic.rest import rest_stiffness

    design = preset_design("raba118")
    scene = ElasticScene()
    k_rest = rest_stiffness(design, scene.options.rest)
    intact = elastic_case(design, None, scene, k_rest)
    same = record_track(intact, intact)
    np.testing.assert_array_equal(same.record_hz, same.intact_record_hz,
                                  err_msg="intact against itself: the same record")
    assert same.open_share == 0.0 and same.states == ()
    case = elastic_case(design, Crack(depth=0.003), scene, k_rest)
    track = record_track(intact, case)
    ok = np.isfinite(track.record_hz)
    assert ok.sum() >= 0.9 * ok.size, "nearly every intact mode tracked at some position"
    assert np.all(track.instantaneous_min_hz[ok] <= track.record_hz[ok] + 1e-9) and np.all(
        track.record_hz[ok] <= track.instantaneous_max_hz[ok] + 1e-9), (
        "the record frequency lies within the instantaneous range")
    assert 0 < track.open_share < 1, "the crack opens and closes over the pitch"


@pytest.mark.slow
def test_pitch_spectra_are_the_coupled_modes(rings):
    """The pitch's stored spectra (the coupled model assembled once per position and
    restricted to the ties' null space, standard eigenproblem below the band) equal
    ``coupled_modes`` of the tied reduced ring at the same state."""
    from hubvib.elastic.loaded import pitch_spectra

    _, er, _, _, force = rings
    pitch = pitch_spectra(er, ON, AWAY, 1000.0, force, (1.0,), (0.0, 1e-6))
    for variant in pitch.loaded:
        for i, position in enumerate(variant.carrier_teeth[::4]):
            i = variant.carrier_teeth.index(position)
            _, solution = crack_state(er.contact, position, _engaged(er, position),
                                      variant.torque_fraction * force, variant.closure_gap_m)
            for stick, index in ((True, variant.stick_index[i]), (False, variant.slip_index[i])):
                expected = loaded_modes(er, position, solution.pressed, stick).frequency_hz
                np.testing.assert_allclose(pitch.spectra[index].frequency_hz, expected,
                                           rtol=1e-7, atol=1e-3, err_msg=(
                                               "pitch spectrum vs coupled_modes of the tied "
                                               "ring, rtol 1e-7; atol 1 mHz: the 45 Hz "
                                               "mode's omega^2 is 1e-7 of the matrix norm, "
                                               "its round-off ~1e-4 Hz"))


@pytest.mark.slow
def test_contact_compliance_from_the_basis_factorisation(rings):
    """The validity band's local contact compliance reads ``b^T K^-1 b`` from the
    factorisation the basis made (``ElasticRing.tooth_compliance``, every tooth of the
    pitch) instead of factorising K again.  Against a fresh sparse LU of K: ``b^T K^-1 b``
    to 1e-8 (the LU's relative residual is about 2e-9: the mounted ring's K is stiff
    against its foundation); the local compliance, ``b^T K^-1 b`` less its rigid-ring part
    (about 300 times smaller on Raba's foundation, so the relative error grows by that
    factor), to 1e-5."""
    import scipy.sparse.linalg as spla

    from hubvib.elastic.validity import local_contact_compliance

    _, full, plain, _, _ = rings
    teeth = _engaged(full, AWAY) + _engaged(full, ON)
    assert set(full.tooth_compliance) == set(range(64)) and not plain.tooth_compliance
    B = full.body.contact[:, list(teeth)].toarray()
    fresh = np.einsum("ij,ij->j", B, spla.splu(full.body.K.tocsc()).solve(B))
    np.testing.assert_allclose([full.tooth_compliance[k] for k in teeth], fresh, rtol=1e-8)
    np.testing.assert_allclose(local_contact_compliance(full, teeth),
                               local_contact_compliance(plain, teeth), rtol=1e-5)
