"""Drift between two records: temperature and load against exact eigen-solves, family-wise
false-alarm rate under drift, and what compensation by a reference mode removes."""
import numpy as np
import pytest

from hubvib.detection.drift import compensate, drift_model, family_pod, references
from hubvib.reducer import lumped_preset
from hubvib.detection.options import DetectionOptions
from hubvib.lumped import natural_modes
from hubvib.lumped.parameters import STIFFNESS_FIELDS

OPTIONS = DetectionOptions(temperature_std=2.0, mesh_load_std=0.01)
SPRINGS = STIFFNESS_FIELDS


@pytest.fixture(scope="module")
def drift():
    params = lumped_preset("raba118")
    f0 = natural_modes(params).omega / (2 * np.pi)
    return params, f0, drift_model(params, f0, OPTIONS)


def _scaled(params, names, factor):
    return params.replace(**{n: getattr(params, n) * factor for n in names
                             if hasattr(params, n) and getattr(params, n) > 0})


def test_temperature_moves_every_mode_by_the_same_relative_amount(drift):
    # independent: every spring of the reducer scaled by 1 + (e_E + alpha) dT, exact solve
    params, f0, model = drift
    dT = 0.5
    factor = 1 + (OPTIONS.modulus_per_K + OPTIONS.expansion_per_K) * dT
    f = natural_modes(_scaled(params, SPRINGS, factor)).omega / (2 * np.pi)
    elastic = f0 > 1.0
    np.testing.assert_allclose((f - f0)[elastic], dT * model.per_kelvin_hz[elastic],
                               rtol=1e-4, err_msg="first order vs exact eigen-solve")
    # the reference figures: 1 K moves mode 13 (4548 Hz) by about -0.6 Hz
    assert model.per_kelvin_hz[12] == pytest.approx(-0.56, abs=0.02)


def test_load_drift_follows_the_mesh_sensitivities(drift):
    params, f0, model = drift
    delta = 1e-4
    f = natural_modes(_scaled(params, ("c_sp", "c_rp"), 1 + delta)).omega / (2 * np.pi)
    moving = np.abs(model.per_load_hz) > 1.0
    np.testing.assert_allclose((f - f0)[moving], delta * model.per_load_hz[moving],
                               rtol=1e-3, err_msg="sensitivity vs exact eigen-solve")


def test_family_false_alarm_rate_holds_under_drift_with_and_without_compensation(drift):
    params, f0, model = drift
    watched = np.array([12, 15, 14, 17])
    sigma = OPTIONS.sigma_hz(f0)
    refs = references(np.zeros(18), sigma, model, f0, watched, 0.12)
    assert (refs >= 0).all() and not np.isin(refs, watched).any()
    rng = np.random.default_rng(0)
    zero = np.zeros((40_000, 2, 18))
    for r in (None, refs):
        rate = family_pod(zero, sigma, f0, watched, 0.01, rng, model, r)[0]
        assert rate == pytest.approx(0.01, abs=4 * np.sqrt(0.01 * 0.99 / 40_000)), \
            "family-wise false-alarm rate on fresh intact draws, 4 binomial sigma"


def test_compensation_removes_a_uniform_shift_exactly(drift):
    params, f0, model = drift
    watched, refs = np.array([12, 15]), np.array([7, 7])
    uniform = 1e-3 * f0
    np.testing.assert_allclose(compensate(uniform, f0, watched, refs), 0.0, atol=1e-9)


def test_a_repeated_pair_gives_its_lower_member_as_reference(drift):
    """The members of a repeated frequency leave the same variance up to the eigensolver's
    round-off, whose sign differs between BLAS builds: the lower mode number is taken
    whichever member round-off favours."""
    params, f0, model = drift
    watched = np.array([12, 15, 14, 17])
    sigma = OPTIONS.sigma_hz(f0)
    refs = references(np.zeros(18), sigma, model, f0, watched, 0.12)
    for nudge in (1 + 1e-13, 1 - 1e-13):
        for r in set(refs.tolist()):
            twin = [j for j in range(18) if j != r and abs(f0[j] / f0[r] - 1) < 1e-9]
            if not twin:
                continue
            assert r < twin[0], f"reference {r + 1} is the upper member of {r + 1}/{twin[0] + 1}"
            pushed = sigma.copy()
            pushed[twin[0]] = sigma[r] * nudge
            np.testing.assert_array_equal(
                references(np.zeros(18), pushed, model, f0, watched, 0.12), refs)
