"""Identification uncertainty: Au's law, the Cramer-Rao bound of the shipped Bayesian-FFT
identifier, and a Monte Carlo of identified simulated records against both."""
import math

import numpy as np
import pytest
from scipy.signal import welch
from scipy.stats import chi2

from hubvib.identification.bfft import identify_mode
from hubvib.identification.law import au_sigma_hz, fisher_sigma_hz
from hubvib.identification.montecarlo import identified
from hubvib.identification.records import mode_psd, simulate


def _std_band(n: int, level: float = 0.99) -> tuple[float, float]:
    """Range of sample std / true std for n normal draws at ``level`` (chi-squared)."""
    a = (1 - level) / 2
    return math.sqrt(chi2.ppf(a, n - 1) / (n - 1)), math.sqrt(chi2.ppf(1 - a, n - 1) / (n - 1))


def test_au_law_is_the_closed_form():
    # Au (2014), MSSP 48: c.o.v. of f = sqrt(zeta / (2 pi N_c)), N_c = f T
    assert au_sigma_hz(4548.0, 0.02, 10.0) == pytest.approx(
        4548.0 * math.sqrt(0.02 / (2 * math.pi * 4548.0 * 10.0)), rel=1e-14)


@pytest.mark.parametrize("f, zeta, T", [(4548.0, 0.02, 10.0), (50.0, 0.01, 200.0)])
def test_cramer_rao_bound_tends_to_au_law_for_a_wide_band_and_high_snr(f, zeta, T):
    wide = fisher_sigma_hz(f, zeta, T, math.inf, kappa=40.0)
    assert wide == pytest.approx(au_sigma_hz(f, zeta, T), rel=0.03), \
        "Au (2014): B_f(kappa) -> 1 for a wide band, within 3 %"
    narrow = fisher_sigma_hz(f, zeta, T, math.inf, kappa=2.0)
    noisy = fisher_sigma_hz(f, zeta, T, 10.0)
    assert narrow > 1.1 * wide and noisy > fisher_sigma_hz(f, zeta, T, 1e4), \
        "a narrower band and more noise leave more uncertainty"


def test_simulated_record_has_the_exact_psd_of_its_mode():
    # independent check of the exact discretisation: Welch PSD of a long record vs the
    # two-sided PSD of the discrete process (one-sided Welch = 2 x two-sided)
    rng = np.random.default_rng(3)
    record = simulate(50.0, 0.05, 400.0, 250.0, math.inf, rng)
    f, p = welch(record.values, fs=record.sample_rate, nperseg=4096)
    at = (f > 40) & (f < 60)
    exact = 2 * mode_psd(50.0, 0.05, 250.0, f[at])
    assert p[at].sum() == pytest.approx(exact.sum(), rel=0.05), \
        "power within 40-60 Hz: Welch estimate (about 50 averages x 150 lines) vs exact PSD"
    assert np.corrcoef(p[at], exact)[0, 1] > 0.95, "same shape"


@pytest.mark.slow
def test_identified_frequencies_scatter_as_the_bound_predicts():
    # Monte Carlo of 80 simulated records identified by the shipped method
    f, zeta, T, snr = 50.0, 0.02, 60.0, 100.0
    est = identified(f, zeta, T, snr, records=80, seed=1)
    low, high = _std_band(est.size)
    ratio = est.std(ddof=1) / fisher_sigma_hz(f, zeta, T, snr)
    assert 0.9 * low <= ratio <= 1.1 * high, \
        f"MC std / Cramer-Rao bound = {ratio:.3f}; chi-squared 99 % band {low:.2f}..{high:.2f}"
    assert abs(est.mean() - f) < 4 * est.std(ddof=1) / math.sqrt(est.size), "unbiased"


@pytest.mark.slow
@pytest.mark.parametrize("zeta", [0.01, 0.02, 0.05])
def test_issue_case_mode_13_from_10_s_records(zeta):
    # the reference case: 4548 Hz, 10 s; scatter vs the bound the diagnosis uses
    est = identified(4548.0, zeta, 10.0, 100.0, records=150, seed=2)
    low, high = _std_band(est.size)
    ratio = est.std(ddof=1) / fisher_sigma_hz(4548.0, zeta, 10.0, 100.0)
    assert 0.9 * low <= ratio <= 1.15 * high, f"zeta {zeta}: MC / bound = {ratio:.3f}"


def test_a_record_of_two_known_modes_is_identified_within_its_uncertainty():
    rng = np.random.default_rng(7)
    modes, zeta = (40.0, 55.0), 0.02
    record = simulate(modes, zeta, 120.0, 250.0, 100.0, rng)
    for f in modes:
        found = identify_mode(record.values, record.sample_rate, f * 1.01, zeta)
        assert abs(found.frequency_hz - f) < 4 * found.sigma_hz, \
            f"mode {f} Hz identified at {found.frequency_hz:.4f} +- {found.sigma_hz:.4f} Hz"
        assert found.sigma_hz == pytest.approx(fisher_sigma_hz(f, zeta, 120.0, 100.0), rel=0.5)


def test_bad_bands_are_refused():
    values = np.zeros(1000)
    with pytest.raises(ValueError, match="Nyquist"):
        identify_mode(values, 100.0, 49.0, 0.05)
    with pytest.raises(ValueError, match="frequency lines"):
        identify_mode(values, 100.0, 10.0, 0.001)
    with pytest.raises(ValueError, match="all must be > 0"):
        fisher_sigma_hz(100.0, 0.0, 10.0)


@pytest.mark.parametrize("power", [0, 4])
def test_cramer_rao_bound_matches_a_finite_difference_fisher_matrix(power):
    # independent: the Fisher matrix of the Whittle likelihood from central differences
    from hubvib.identification.law import response_shape

    f0, zeta, T, snr, kappa = 100.0, 0.02, 100.0, 50.0, 6.0
    k = np.arange(math.ceil(f0 * (1 - kappa * zeta) * T), math.floor(f0 * (1 + kappa * zeta)
                                                                     * T) + 1)
    f = k / T
    theta = np.array([f0, zeta, 1.0, 1.0 / (4 * zeta * zeta * snr)])

    def D(t):
        return t[2] * response_shape(f, t[0], t[1], power) + t[3]

    grads = []
    for i in range(4):
        step = np.zeros(4)
        step[i] = 1e-6 * theta[i]
        grads.append((D(theta + step) - D(theta - step)) / (2 * step[i]))
    G = np.array(grads) / D(theta)
    expected = math.sqrt(np.linalg.inv(G @ G.T)[0, 0])
    assert fisher_sigma_hz(f0, zeta, T, snr, kappa, power) == pytest.approx(expected, rel=1e-6)


@pytest.mark.parametrize("power", [0, 4])
@pytest.mark.parametrize("snr", [50.0, math.inf])
def test_cramer_rao_bound_in_place_has_the_digits_of_the_plain_formulas(power, snr):
    # the bound is evaluated in place (bands of ~1e6 ordinates); the plain expressions of
    # its Fisher information (Yuen, Katafygiotis & Beck 2002), written out here, must give
    # the same float to the last digit (the same operations in the same order)
    from hubvib.identification.law import _fisher_sigma_hz

    f0, zeta, T, kappa = 1234.5, 0.02, 60.0, 6.0
    df = 1.0 / T
    f = np.arange(math.ceil(f0 * (1 - kappa * zeta) / df),
                  math.floor(f0 * (1 + kappa * zeta) / df) + 1) * df
    S, Se = 1.0, (0.0 if math.isinf(snr) else 1.0 / (4 * zeta * zeta * snr))
    b = f / f0
    g = (1 - b * b) ** 2 + (2 * zeta * b) ** 2
    dg_db = -4 * b * (1 - b * b) + 8 * zeta * zeta * b
    if power == 0:
        h2 = 1 / g
        d_f0 = S * (dg_db * b / g ** 2) / f0
        d_zeta = S * (-(8 * zeta * b * b) / g ** 2)
    else:
        bp = b ** power
        h2 = bp / g
        d_f0 = S * (bp * dg_db * b / g ** 2 - power * h2) / f0
        d_zeta = S * bp * (-(8 * zeta * b * b) / g ** 2)
    D = S * h2 + Se
    grads = [d_f0, d_zeta, h2] + ([np.ones_like(f)] if Se > 0 else [])
    G = np.array(grads) / D
    expected = float(math.sqrt(np.linalg.inv(G @ G.T)[0, 0]))
    got = _fisher_sigma_hz.__wrapped__(f0, zeta, T, snr, kappa, power)
    assert got == expected, f"in-place {got!r} vs plain formulas {expected!r} (exact)"
