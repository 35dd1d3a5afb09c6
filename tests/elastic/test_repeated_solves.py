"""Work a refined sweep asks for again is done once: a depth's Monte Carlo draws are
solved once per set of draws, and each carrier position's spectrum is ordered as the
intact reference once, whichever load variants share it; the answers are those of a
fresh solve."""
from dataclasses import replace

import numpy as np
from tests.elastic.test_elastic_diagnose import OPTIONS, _synthetic_cases

from hubvib.detection.elastic_model import (batched_hz, depth_operators, draw_elastic,
                                            elastic_spectrum_model)
from hubvib.elastic.loaded import PitchSpectra, StoredSpectrum, ordered_frequencies
from hubvib.elastic.tracking import track_descriptors


def test_a_depths_draws_are_solved_once_and_equal_a_fresh_solve():
    """The sweep's model grown by one depth draws the same reducers (same seed): its grid
    frequencies equal, bit for bit, those of operators built anew (no stored solve); the
    same draws give back the stored array, other draws other frequencies."""
    cases = _synthetic_cases()
    depths = [c.depth for c in cases]
    small = elastic_spectrum_model(depths[:3], cases[:3])
    model = elastic_spectrum_model(depths, cases)
    assert all(a is b for a, b in zip(small.operators, model.operators[:3])), \
        "the depths both sweeps hold share their operators"
    assert depth_operators(cases[2], cases[0], cases[0].ring_mass) is model.operators[2]
    drawn = draw_elastic(model, OPTIONS, 50, np.random.default_rng(7))
    again = draw_elastic(model, OPTIONS, 50, np.random.default_rng(7))
    values = model.grid_hz(drawn)
    fresh = replace(model, operators=tuple(replace(op) for op in model.operators))
    assert np.array_equal(fresh.grid_hz(again), values), \
        "stored solves equal a fresh batched solve of the same draws exactly"
    op = model.operators[3]
    assert batched_hz(op, again, model.masks) is batched_hz(op, drawn, model.masks)
    other = draw_elastic(model, OPTIONS, 50, np.random.default_rng(8))
    assert not np.allclose(model.grid_hz(other), values, rtol=1e-6, atol=0), \
        "other draws are solved, not taken from the store"


def _stored(rng, features: int, f_hz) -> StoredSpectrum:
    return StoredSpectrum(np.asarray(f_hz, dtype=float),
                          rng.standard_normal((features, len(f_hz))).astype(np.float32))


def _direct(intact: PitchSpectra, case: PitchSpectra, index) -> np.ndarray:
    """Each position's spectrum tracked to the intact one there, then to the reference
    by order: the rule of ``ordered_frequencies``, written out."""
    ref = intact.spectra[intact.base_index[intact.reference]].frequency_hz
    out = np.full((len(index), ref.size), np.nan)
    for p, i in enumerate(index):
        here, s = intact.spectra[intact.base_index[p]], case.spectra[i]
        to_here = track_descriptors(here.descriptors, here.frequency_hz, s.descriptors,
                                    s.frequency_hz).reference
        for j, r in enumerate(to_here):
            if 0 <= r < ref.size:
                out[p, r] = s.frequency_hz[j]
    return out


def test_positions_shared_by_load_variants_are_ordered_once_and_as_tracked():
    """Two load variants sharing some positions' spectra: each variant's table equals the
    tracking written out; the second asks nothing new for the shared positions."""
    rng = np.random.default_rng(5)
    features, positions = 12, 4
    intact_spectra = tuple(_stored(rng, features, np.linspace(1000, 5000, 6) + 10 * p)
                           for p in range(positions))
    intact = PitchSpectra(tuple(range(positions)), 2, intact_spectra, tuple(range(positions)),
                          (), 1000.0, 8000.0, 3, {})
    cracked = tuple(_stored(rng, features, np.linspace(990, 4950, 6 - (k % 2)) + 7 * k)
                    for k in range(8))
    case = PitchSpectra(tuple(range(positions)), 2, cracked, (0, 1, 2, 3), (), 1000.0,
                        8000.0, 3, {})
    first, second = (0, 4, 5, 3), (0, 6, 5, 7)
    for index in (first, second, first):
        assert np.array_equal(ordered_frequencies(intact, case, index),
                              _direct(intact, case, index), equal_nan=True), index
    from hubvib.elastic.loaded import _ordered_rows

    assert set(_ordered_rows(intact, case)) == {(0, 0), (1, 4), (2, 5), (3, 3), (1, 6),
                                                (3, 7)}, "one ordering per position and spectrum"
