"""Two close modes fitted together in one band (:mod:`hubvib.identification.multimode`)
against simulated records of known modes (exact sampled oscillators, :mod:`.records`)."""
from __future__ import annotations

import numpy as np
import pytest

from hubvib.identification.multimode import identify_band
from hubvib.identification.records import simulate

MODES = np.array([1000.0, 1030.0])  # 0.75 half-power bandwidth apart at 2 %
ZETA = 0.02


@pytest.mark.slow
def test_close_modes_within_their_bounds_over_records():
    """20 records of 60 s: each mode's frequency scatters about the truth as its Cramer-Rao
    bound says (mean error within 3 standard errors; sample deviation within a factor 1.6
    of the mean bound: the 20-record 95 % band of a deviation is about 0.7..1.3)."""
    rng = np.random.default_rng(7)
    fs = 4400.0
    found, bounds = [], []
    for _ in range(20):
        rec = simulate(MODES, ZETA, 60.0, fs, 100.0, rng)
        fit = identify_band(rec.values, fs, MODES * np.array([0.995, 1.004]), ZETA,
                            MODES.min() * (1 - 4 * ZETA), MODES.max() * (1 + 4 * ZETA),
                            lines=False, acceleration=False)
        found.append(fit.frequency_hz)
        bounds.append(fit.sigma_hz)
    found, bounds = np.array(found), np.array(bounds)
    for j, f in enumerate(MODES):
        error = found[:, j].mean() - f
        spread, bound = found[:, j].std(ddof=1), bounds[:, j].mean()
        assert abs(error) < 3 * bound / np.sqrt(20), (
            f"mode at {f:g} Hz: mean error {error:.3g} Hz, bound {bound:.3g} Hz")
        assert bound / 1.6 < spread < 1.6 * bound, (
            f"mode at {f:g} Hz: scatter {spread:.3g} Hz vs Cramer-Rao bound {bound:.3g} Hz")


def test_warm_start_is_blind_to_the_sensor_gain():
    """A record fitted from another record's fit of the same band: the same record at ten
    times the gain (PSD levels times 100, rescaled by the median ordinates) starts at the
    first fit's optimum and returns its frequencies and damping (to the optimiser's
    tolerance: a gain carries no information on a frequency)."""
    rng = np.random.default_rng(11)
    fs = 4400.0
    rec = simulate(MODES, ZETA, 20.0, fs, 100.0, rng)
    band = (MODES.min() * (1 - 4 * ZETA), MODES.max() * (1 + 4 * ZETA))
    first = identify_band(rec.values, fs, MODES, ZETA, *band, lines=False,
                          acceleration=False)
    again = identify_band(10.0 * rec.values, fs, MODES * 1.01, ZETA, *band, lines=False,
                          acceleration=False, start=first)
    assert np.allclose(again.frequency_hz, first.frequency_hz, rtol=0, atol=1e-3 * first.sigma_hz.min()), (
        f"{again.frequency_hz} vs {first.frequency_hz} Hz (bounds {first.sigma_hz} Hz)")
    assert np.allclose(again.damping_ratio, first.damping_ratio, rtol=1e-3), (
        f"{again.damping_ratio} vs {first.damping_ratio}")
