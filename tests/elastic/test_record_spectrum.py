"""The spectrum of a record whose stiffness switches as the planets pass, against a direct
time integration of the switching system and exact identities.

The simulations integrate an SDOF (and a 2-DOF) whose stiffness is piecewise constant
over each planet pass, driven by white-noise forces, EXACTLY: per sample the state
transition ``expm(A dt)`` and the exact discrete noise covariance (Van Loan), each state
held for a whole number of samples.  Damping is modal with the same ratio in every state,
as :func:`record_spectrum` assumes.  The velocity record's Welch PSD is identified by a
least-squares fit of damped-mode velocity PSDs to its logarithm; tolerances are stated
against Au's Cramer-Rao scale ``sqrt(zeta f / (2 pi T))`` of a record of ``T`` seconds.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.linalg import eigh, expm
from scipy.optimize import least_squares
from scipy.signal import find_peaks, welch

from hubvib.elastic.record_spectrum import (RecordSpectrumError, SIDEBAND_ORDERS,
                                            record_spectrum)
from hubvib.foundation.errors import InputError

ZETA = 0.02
FS = 240.0          # sample rate [Hz]: 4.8 samples per cycle at 50 Hz, exact integration
SEGMENT_S = 10.0    # Welch segment [s]: bins of 0.1 Hz, 60 decay times


# --- the direct time integration ------------------------------------------------------

def _discrete_state(mass, stiffness, zeta, dt):
    """Exact one-sample transition and a square root of the exact noise covariance of
    ``M x'' + C x' + K x = f``, ``f`` unit white noise on every DOF, ``C`` modal with
    ratio ``zeta`` on every mode (Van Loan 1978)."""
    n = len(mass)
    M = np.diag(np.asarray(mass, float))
    Mi = np.linalg.inv(M)
    lam, phi = eigh(stiffness, M)
    C = M @ phi @ np.diag(2 * zeta * np.sqrt(lam)) @ phi.T @ M
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Mi @ stiffness, -Mi @ C]])
    B = np.vstack([np.zeros((n, n)), Mi])
    m = 2 * n
    big = expm(np.block([[-A, B @ B.T], [np.zeros((m, m)), A.T]]) * dt)
    Phi = big[m:, m:].T
    Q = Phi @ big[:m, m:]
    val, vec = np.linalg.eigh(0.5 * (Q + Q.T))
    return Phi, vec * np.sqrt(np.clip(val, 0, None))


def simulate(mass, stiffnesses, counts, passes, seed, zeta=ZETA):
    """State ``[x, v]`` at every sample of ``passes`` passes; state ``j`` holds
    ``counts[j]`` samples per pass.  All passes are integrated at once from rest, then
    each pass's start is propagated through the pass transition (linearity)."""
    rng = np.random.default_rng(seed)
    m = 2 * len(mass)
    per = sum(counts)
    particular = np.empty((passes, per, m))
    from_start = np.empty((per, m, m))
    x = np.zeros((passes, m))
    transition = np.eye(m)
    i = 0
    for K, count in zip(stiffnesses, counts):
        Phi, L = _discrete_state(mass, K, zeta, 1 / FS)
        noise = rng.standard_normal((passes, count, m)) @ L.T
        for c in range(count):
            x = x @ Phi.T + noise[:, c]
            transition = Phi @ transition
            particular[:, i] = x
            from_start[i] = transition
            i += 1
    start = np.zeros((passes, m))
    s = np.zeros(m)
    for k in range(passes):
        start[k] = s
        s = transition @ s + x[k]
    return particular + np.einsum("pij,kj->kpi", from_start, start)


def sdof_velocity(freqs_hz, dwell, pass_hz, record_s, seed):
    per = FS / pass_hz
    counts = [int(round(w * per)) for w in dwell]
    assert all(abs(c - w * per) < 1e-9 for c, w in zip(counts, dwell)), "whole samples"
    K = [np.array([[(2 * math.pi * f) ** 2]]) for f in freqs_hz]
    x = simulate([1.0], K, counts, int(round(record_s * pass_hz)), seed)
    return x[:, :, 1].ravel()


def two_dof(open_share):
    """Two unit masses on ground springs at 40 and 60 Hz, coupled by a spring of 10 % of
    the first; the crack takes 12 % off the second ground spring while open."""
    w1, w2 = 2 * math.pi * 40, 2 * math.pi * 60
    kc = 0.1 * w1**2
    return [np.array([[w1**2 + kc, -kc], [-kc, w2**2 * (1 - share) + kc]])
            for share in open_share]


# --- identification of the simulated record ------------------------------------------

def velocity_psd(f, fn, zeta):
    return f**2 / ((fn**2 - f**2) ** 2 + (2 * zeta * fn * f) ** 2)


def band_psd(v, lo, hi):
    f, p = welch(v, FS, nperseg=int(round(SEGMENT_S * FS)))
    inside = (f >= lo) & (f <= hi)
    return f[inside], p[inside]


def fitted_modes(f, p, guesses):
    """Least-squares fit of a sum of damped-mode velocity PSDs to ``log p``: the fitted
    curve (callable) and the fitted natural frequencies [Hz]."""
    n = len(guesses)

    def model(q, ff):
        return sum(np.exp(q[3 * i + 2]) * velocity_psd(ff, q[3 * i], q[3 * i + 1])
                   for i in range(n))

    q0 = []
    for g in guesses:
        q0 += [g, ZETA, math.log(np.interp(g, f, p) / velocity_psd(g, g, ZETA))]
    q = least_squares(lambda q: np.log(model(q, f)) - np.log(p), q0).x
    return (lambda ff: model(q, ff)), q[0::3]


def curve_peaks(fun, lo, hi):
    """Local maxima of a smooth curve (the same 5 % prominence rule as the module)."""
    g = np.linspace(lo, hi, 20001)
    y = fun(g)
    index, _ = find_peaks(y, prominence=0.05 * y.max())
    return g[index]


def au_sigma(f, record_s):
    """Au's Cramer-Rao scale of an identified frequency from one record [Hz]."""
    return math.sqrt(ZETA * f / (2 * math.pi * record_s))


# --- the time-integration checks -------------------------------------------------------

def test_swing_inside_bandwidth_peaks_at_the_mean():
    """(a) Two states 0.4 Hz apart (a fifth of the 2 Hz bandwidth), dwell 0.35 / 0.65,
    each lasting over 60 decay times: the identified frequency is the predicted one (the
    dwell-weighted mean to first order) within 0.05 Hz, while min and max are more than
    2.5 x that away.  The tolerance is about 3.5 standard deviations of the fitted
    frequency over seeds for a 4000 s record (twice Au's bound: a Welch-PSD fit is not an
    efficient estimator) plus the O(1 / adiabatic ratio) bias of the states' finite
    duration."""
    freqs, dwell, pass_hz, record_s = (49.8, 50.2), (0.35, 0.65), 0.05, 4000.0
    r = record_spectrum(np.array(freqs)[:, None], dwell, ZETA, pass_hz)
    assert r.regime == ("averaged",)
    assert r.adiabatic_ratio[0] > 10
    assert abs(r.frequency_hz[0] - r.mean_hz[0]) < r.resolution_hz[0]
    v = sdof_velocity(freqs, dwell, pass_hz, record_s, seed=1)
    f, p = band_psd(v, r.mean_hz[0] - 1.5, r.mean_hz[0] + 1.5)
    _, (identified,) = fitted_modes(f, p, [r.mean_hz[0]])
    tol = 0.05
    assert abs(identified - r.frequency_hz[0]) < tol, (
        f"identified {identified:.4f} Hz vs predicted {r.frequency_hz[0]:.4f} Hz, "
        f"tolerance {tol} Hz")
    for edge in (r.instantaneous_min_hz[0], r.instantaneous_max_hz[0]):
        assert abs(edge - r.frequency_hz[0]) > 2.5 * tol, "the case must tell mean from edge"


def test_swing_beyond_bandwidth_splits_with_unequal_dwell():
    """(b) Two states 3 Hz apart (1.5 bandwidths), dwell 0.4 / 0.6, each lasting over 50
    decay times: the simulated PSD has exactly the two predicted peaks (the fitted PSD's
    local maxima), each within 0.1 Hz (a tenth of the half-bandwidth: the peaks of a
    two-mode fit scatter by ~0.03 Hz over 2000 s, and the states' finite duration pulls
    the smaller peak towards the larger by O(1 / adiabatic ratio)), and its value at the
    dwell-weighted mean lies in the dip, below both peaks."""
    freqs, dwell, pass_hz, record_s = (48.5, 51.5), (0.4, 0.6), 0.05, 2000.0
    r = record_spectrum(np.array(freqs)[:, None], dwell, ZETA, pass_hz)
    assert r.regime == ("split",)
    predicted = np.array(r.peaks_hz[0])
    assert predicted.size == 2
    assert r.frequency_hz[0] == pytest.approx(predicted[1]), "the longer state's peak"
    v = sdof_velocity(freqs, dwell, pass_hz, record_s, seed=2)
    f, p = band_psd(v, 46.0, 54.0)
    fun, _ = fitted_modes(f, p, list(freqs))
    found = curve_peaks(fun, 46.5, 53.5)
    assert found.size == 2, f"simulated peaks {found}, predicted {predicted}"
    assert np.all(np.abs(found - predicted) < 0.1), (
        f"simulated {np.round(found, 3)} vs predicted {np.round(predicted, 3)} Hz, tol 0.1")
    assert fun(r.mean_hz[0]) < fun(found).min(), "the mean lies in the dip"


def test_fast_modulation_is_the_averaged_mode_with_sidebands():
    """(c) States 47 / 53 Hz (3 bandwidths apart: quasi-static they would split) switching
    at 8 Hz, each state lasting 0.06 s, well under the 0.16 s decay time: one peak at the
    averaged frequency (within 4 x Au's scale, 0.05 Hz for 1000 s), nothing at 47 or
    53 Hz, and planet-pass sidebands at mean +- 8 Hz (within 0.25 Hz, an eighth of the
    bandwidth), standing at least twice above the central line's tail."""
    freqs, dwell, pass_hz, record_s = (47.0, 53.0), (0.5, 0.5), 8.0, 1000.0
    r = record_spectrum(np.array(freqs)[:, None], dwell, ZETA, pass_hz)
    assert r.regime == ("averaged",) and r.adiabatic_ratio[0] < 1
    assert r.frequency_hz[0] == r.mean_hz[0] == 50.0
    v = sdof_velocity(freqs, dwell, pass_hz, record_s, seed=3)
    f, p = band_psd(v, 30.0, 70.0)
    near = (f > 48.5) & (f < 51.5)
    _, (identified,) = fitted_modes(f[near], p[near], [50.0])
    tol = 4 * au_sigma(50.0, record_s)
    assert abs(identified - r.frequency_hz[0]) < tol, (
        f"central line {identified:.4f} Hz vs predicted {r.frequency_hz[0]} Hz, tol {tol:.3f}")
    centre = np.interp(50.0, f, p)
    for state in freqs:
        assert np.interp(state, f, p) < 0.5 * centre, "no quasi-static peak at a state"
    tail = velocity_psd(f, r.mean_hz[0], ZETA)
    tail *= np.median((p / tail)[near])
    excess = p - tail
    for k, sideband in zip(SIDEBAND_ORDERS, r.sidebands_hz[0]):
        if abs(k) != 1:
            continue
        window = (f > sideband - 3) & (f < sideband + 3)
        i = np.argmax(excess[window])
        ff, ee = f[window], excess[window]
        fit = np.polyfit(ff[i - 5:i + 6] - ff[i], ee[i - 5:i + 6], 2)
        found = ff[i] - fit[1] / (2 * fit[0])
        assert abs(found - sideband) < 0.25, f"sideband {found:.3f} vs {sideband} Hz"
        assert ee[i] > 2 * np.interp(sideband, f, tail), "sideband above the tail"


def test_two_modes_each_in_its_regime():
    """2-DOF, the crack softening one ground spring while open (dwell 0.4): the 40 Hz mode
    barely moves (regime averaged), the 60 Hz mode swings 1.5 bandwidths (split).  The
    simulated record's first mode within 4 x Au's scale of its prediction, the second's
    two peaks within 0.1 Hz of theirs (as in the SDOF split case)."""
    dwell, pass_hz, record_s = (0.4, 0.6), 0.05, 2000.0
    states = two_dof((0.12, 0.0))
    freqs = np.array([np.sqrt(eigh(K, eigvals_only=True)) / (2 * math.pi) for K in states])
    r = record_spectrum(freqs, dwell, ZETA, pass_hz)
    assert r.regime == ("averaged", "split")
    counts = [int(round(w * FS / pass_hz)) for w in dwell]
    x = simulate([1.0, 1.0], states, counts, int(round(record_s * pass_hz)), seed=4)
    v = (x[:, :, 2] + x[:, :, 3]).ravel()
    f, p = band_psd(v, r.mean_hz[0] - 1.5, r.mean_hz[0] + 1.5)
    _, (first,) = fitted_modes(f, p, [r.mean_hz[0]])
    tol = 4 * au_sigma(r.mean_hz[0], record_s)
    assert abs(first - r.frequency_hz[0]) < tol, (
        f"mode 1 {first:.4f} vs {r.frequency_hz[0]:.4f} Hz, tol {tol:.3f}")
    lo, hi = r.instantaneous_min_hz[1], r.instantaneous_max_hz[1]
    f, p = band_psd(v, lo - 2.5, hi + 2.5)
    fun, _ = fitted_modes(f, p, [lo, hi])
    found = curve_peaks(fun, lo - 2, hi + 2)
    predicted = np.array(r.peaks_hz[1])
    assert found.size == 2 and np.all(np.abs(found - predicted) < 0.1), (
        f"mode 2 simulated {np.round(found, 3)} vs predicted {np.round(predicted, 3)} Hz")


# --- exact identities ---------------------------------------------------------------

def _floquet_hz(freqs, dwell, pass_hz, near_hz):
    """Frequency of the switching SDOF's Floquet multiplier (monodromy matrix over one
    pass), on the branch nearest ``near_hz`` [Hz]."""
    period = 1 / pass_hz
    monodromy = np.eye(2)
    for f, w in zip(freqs, dwell):
        omega = 2 * math.pi * f
        A = np.array([[0.0, 1.0], [-omega**2, -2 * ZETA * omega]])
        monodromy = expm(A * w * period) @ monodromy
    mu = np.linalg.eigvals(monodromy)
    base = abs(np.angle(mu[0])) / (2 * math.pi * period)
    return base + round((near_hz - base) * pass_hz) / pass_hz


@pytest.mark.parametrize("freqs,dwell", [((45.0, 55.0), (0.5, 0.5)),
                                         ((40.0, 60.0), (0.5, 0.5)),
                                         ((46.0, 50.0, 56.0), (0.3, 0.3, 0.4))])
def test_fast_regime_frequency_is_the_phase_average(freqs, dwell):
    """With f_pp << f and away from parametric resonance (f_pp = 8 Hz, 2 f / f_pp = 12.5),
    the Floquet frequency of the exactly integrated switching oscillator is the
    dwell-weighted mean of the frequencies (within 15 % of the gap), not the eigenvalue
    average sqrt(sum w f^2) of :mod:`hubvib.detection.carrier` (second order higher)."""
    r = record_spectrum(np.array(freqs)[:, None], dwell, ZETA, 8.0)
    eigen_mean = math.sqrt(np.dot(dwell, np.square(freqs)))
    floquet = _floquet_hz(freqs, dwell, 8.0, r.mean_hz[0])
    assert abs(floquet - r.mean_hz[0]) < 0.15 * (eigen_mean - r.mean_hz[0]), (
        f"Floquet {floquet:.4f}, phase average {r.mean_hz[0]:.4f}, eigenvalue average "
        f"{eigen_mean:.4f} Hz")


def test_constant_stiffness_is_one_averaged_peak():
    for pass_hz in (0.1, 22.0, 5000.0):
        r = record_spectrum(np.full((25, 3), [150.0, 4700.0, 9000.0]), np.ones(25), ZETA,
                            pass_hz)
        expected = np.array([150.0, 4700.0, 9000.0])
        for name in ("frequency_hz", "mean_hz", "instantaneous_min_hz",
                     "instantaneous_max_hz"):
            np.testing.assert_allclose(getattr(r, name), expected, rtol=1e-12,
                                       err_msg=f"{name}, constant stiffness")
        assert r.regime == ("averaged",) * 3
        assert all(len(p) == 1 for p in r.peaks_hz)
        np.testing.assert_allclose(r.swing_hz, 0.0)
        np.testing.assert_allclose(r.bandwidth_hz, 2 * ZETA * expected)
        np.testing.assert_allclose(r.sidebands_hz,
                                   expected[:, None] + pass_hz * np.array(SIDEBAND_ORDERS))


def test_mixture_peak_second_order_correction():
    """Swing well inside the bandwidth: the numerically found peak minus the dwell-weighted
    mean matches the docstring's second-order expansion ``-2 mu3 / gamma^2 - 5 sigma^2 /
    (2 fbar)`` to within 5 % (the next order is smaller by ``swing / gamma``)."""
    fbar0, gamma = 1000.0, ZETA * 1000.0
    d = np.array([-0.1, 0.0, 0.05]) * gamma
    dwell = np.array([0.2, 0.3, 0.5])
    freqs = fbar0 + d
    r = record_spectrum(freqs[:, None], dwell, ZETA, 1e-3)
    dev = freqs - r.mean_hz[0]
    mu3, sigma2 = np.dot(dwell, dev**3), np.dot(dwell, dev**2)
    g = ZETA * r.mean_hz[0]
    expected = -2 * mu3 / g**2 - 2.5 * sigma2 / r.mean_hz[0]
    shift = r.frequency_hz[0] - r.mean_hz[0]
    assert shift == pytest.approx(expected, rel=0.05), f"shift {shift} vs {expected} Hz"


def test_permutation_of_positions_changes_nothing():
    rng = np.random.default_rng(7)
    freqs = 4700.0 * (1 + np.where(rng.random((25, 6)) < 0.64, -0.01, 0.004)
                      * np.arange(1, 7))
    dwell = rng.uniform(0.5, 1.5, 25)
    a = record_spectrum(freqs, dwell, ZETA, 22.0)
    order = rng.permutation(25)
    b = record_spectrum(freqs[order], dwell[order], ZETA, 22.0)
    for name in ("frequency_hz", "mean_hz", "adiabatic_ratio", "modulation_index",
                 "swing_hz"):
        np.testing.assert_allclose(getattr(a, name), getattr(b, name), rtol=1e-12,
                                   err_msg=name)
    assert a.regime == b.regime
    for pa, pb in zip(a.peaks_hz, b.peaks_hz):
        np.testing.assert_allclose(pa, pb, rtol=1e-12)


def test_untracked_positions_are_left_out():
    freqs = np.array([[100.0, np.nan], [100.0, np.nan], [104.0, np.nan], [np.nan, np.nan]])
    with_nan = record_spectrum(freqs, [1.0, 1.0, 2.0, 5.0], ZETA, 0.1)
    without = record_spectrum(freqs[:3, :1], [1.0, 1.0, 2.0], ZETA, 0.1)
    assert with_nan.frequency_hz[0] == pytest.approx(without.frequency_hz[0], rel=1e-14)
    assert with_nan.mean_hz[0] == pytest.approx(102.0)
    assert with_nan.regime == (without.regime[0], "untracked")
    assert np.isnan(with_nan.frequency_hz[1]) and np.isnan(with_nan.mean_hz[1])
    assert np.all(np.isnan(with_nan.sidebands_hz[1])) and with_nan.peaks_hz[1] == ()
    rows = with_nan.rows()
    json.dumps(rows, allow_nan=False)
    assert rows[1]["frequency_hz"] is None and rows[1]["regime"] == "untracked"
    assert rows[0]["peaks_hz"] == [pytest.approx(p) for p in with_nan.peaks_hz[0]]


@pytest.mark.parametrize("kwargs,word", [
    ({"dwell": [1.0, -0.5]}, "dwell"),
    ({"dwell": [0.0, 0.0]}, "dwell"),
    ({"dwell": [1.0, np.nan]}, "dwell"),
    ({"dwell": [1.0, 1.0, 1.0]}, "dwell"),
    ({"damping_ratio": 0.0}, "damping_ratio"),
    ({"damping_ratio": 1.0}, "damping_ratio"),
    ({"pass_hz": 0.0}, "pass_hz"),
    ({"pass_hz": math.inf}, "pass_hz"),
    ({"instantaneous_hz": [[100.0], [-1.0]]}, "instantaneous_hz"),
    ({"instantaneous_hz": np.ones((2, 2, 2))}, "instantaneous_hz"),
    ({"resolution_hz": 0.0}, "resolution_hz"),
])
def test_bad_input_names_the_argument(kwargs, word):
    args = {"instantaneous_hz": [[100.0], [101.0]], "dwell": [1.0, 1.0],
            "damping_ratio": ZETA, "pass_hz": 22.0}
    args.update(kwargs)
    with pytest.raises(RecordSpectrumError) as info:
        record_spectrum(**args)
    assert isinstance(info.value, InputError) and isinstance(info.value, ValueError)
    message = str(info.value)
    assert message.startswith(word) and "\n" not in message, message


def test_regimes_follow_the_stated_rules():
    """Quasi-static two states: equal dwell at 0.2 bandwidths apart is one peak at the
    mean; 1.5 bandwidths apart splits (equal Lorentzians split beyond 2 gamma / sqrt(3));
    0.4 / 0.6 dwell at half a bandwidth is one peak pulled off the mean (mixture)."""
    f0, B = 1000.0, 2 * ZETA * 1000.0
    cases = {"averaged": ((f0 - 0.1 * B, f0 + 0.1 * B), (0.5, 0.5)),
             "split": ((f0 - 0.75 * B, f0 + 0.75 * B), (0.5, 0.5)),
             "mixture": ((f0 - 0.25 * B, f0 + 0.25 * B), (0.4, 0.6))}
    for regime, (freqs, dwell) in cases.items():
        r = record_spectrum(np.array(freqs)[:, None], dwell, ZETA, 0.01)
        assert r.regime == (regime,), (regime, r.peaks_hz)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [11, 12, 13])
def test_long_records_mixture(seed):
    """Mixture (states 49.3 / 50.7 Hz, dwell 0.3 / 0.7, 0.7 bandwidths apart, 8000 s
    records, three seeds): one peak, within 0.06 Hz of the predicted 50.62 Hz (a peak of
    a two-mode fit to one hump is poorly conditioned), more than 0.3 Hz from the
    dwell-weighted mean 50.28 Hz."""
    freqs, dwell, pass_hz, record_s = (49.3, 50.7), (0.3, 0.7), 0.05, 8000.0
    r = record_spectrum(np.array(freqs)[:, None], dwell, ZETA, pass_hz)
    assert r.regime == ("mixture",)
    assert abs(r.frequency_hz[0] - r.mean_hz[0]) > 0.3
    v = sdof_velocity(freqs, dwell, pass_hz, record_s, seed)
    f, p = band_psd(v, 47.0, 53.0)
    fun, _ = fitted_modes(f, p, list(freqs))
    found = curve_peaks(fun, 47.5, 52.5)
    assert found.size == 1 and abs(found[0] - r.frequency_hz[0]) < 0.06, (
        f"simulated {found} vs predicted {r.frequency_hz[0]:.4f} Hz (mean {r.mean_hz[0]})")


def test_one_dimensional_input_is_one_mode():
    one = record_spectrum([100.0, 104.0, 101.0], [1.0, 2.0, 1.0], ZETA, 0.1)
    two = record_spectrum([[100.0], [104.0], [101.0]], [1.0, 2.0, 1.0], ZETA, 0.1)
    assert one.regime == two.regime and one.frequency_hz.shape == (1,)
    assert one.frequency_hz[0] == two.frequency_hz[0]
    assert one.mean_hz[0] == pytest.approx((100.0 + 2 * 104.0 + 101.0) / 4, rel=1e-15)
