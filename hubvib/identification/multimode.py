"""Several close modes from one record in one band: the multi-mode Whittle fit (SI).

The single-mode method (:mod:`.bfft`) needs a band free of other modes.  Close modes seen
by one sensor share a band; with independent modal forces their acceleration PSD adds,

    D_k = sum_j S_j b_jk^4 |h(f_k; f_j, zeta_j)|^2 + S_e,     b_jk = f_k / f_j,

and the FFT ordinates of the band are still independent complex Gaussians of variance
``D_k`` (Yuen, Katafygiotis & Beck 2002), so the frequencies, damping ratios and PSD levels
of all of them maximise the same Whittle likelihood as one mode's (a single-channel
reduction of Au's multi-mode Bayesian FFT, which with one channel cannot use mode shapes:
modes closer than about a half-power bandwidth remain poorly told apart, and their
uncertainty says so).  The uncertainty of each frequency is the Cramer-Rao bound: the
inverse of the Fisher information ``sum_k grad D_k grad D_k^T / D_k^2`` at the estimate.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from .bfft import IdentificationError, line_mask


@dataclass(frozen=True)
class BandFit:
    """The modes of one band.

    Attributes
    ----------
    frequency_hz, damping_ratio, sigma_hz : ndarray
        Per mode: natural frequency [Hz], damping [-], Cramer-Rao bound of the frequency [Hz].
    snr : ndarray
        Modal signal-to-noise ratio ``S_j / (4 zeta_j^2 S_e)`` [-].
    band_hz : tuple
        The band fitted [Hz].
    parameters : ndarray
        The fitted likelihood's parameters (per mode in the guesses' order ``f_j, ln zeta_j,
        ln S_j``, then ``ln S_e``), a start for a fit of another record of the band.
    median_level : float
        The median periodogram ordinate of the band [unit^2/Hz] (a start's levels are
        rescaled by the ratio of two records').
    """

    frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    sigma_hz: np.ndarray
    snr: np.ndarray
    band_hz: tuple
    parameters: np.ndarray = None
    median_level: float = float("nan")


def _psd(params: np.ndarray, f: np.ndarray, k: int, power: int = 4):
    """D_k and its gradient (k modes: f_j, ln zeta_j, ln S_j, then ln S_e); ``power`` 4:
    acceleration, 0: displacement."""
    D = np.full(f.size, math.exp(params[-1]))
    grad = np.zeros((params.size, f.size))
    grad[-1] = D
    for j in range(k):
        f0, zeta, S = params[3 * j], math.exp(params[3 * j + 1]), math.exp(params[3 * j + 2])
        b = f / f0
        g = (1 - b * b) ** 2 + (2 * zeta * b) ** 2
        bp = b ** power
        h2 = bp / g
        term = S * h2
        D = D + term
        dg_db = -4 * b * (1 - b * b) + 8 * zeta * zeta * b
        dh2_db = power * b ** (power - 1) / g - bp * dg_db / g ** 2 if power else \
            -dg_db / g ** 2
        grad[3 * j] = S * dh2_db * (-b / f0)
        grad[3 * j + 1] = S * (-bp / g ** 2) * (8 * zeta * b * b) * zeta
        grad[3 * j + 2] = term
    return D, grad


def identify_band(values, sample_rate: float, guesses_hz, damping_guess: float, low_hz: float,
                  high_hz: float, lines: bool = True, acceleration: bool = True,
                  start: BandFit | None = None) -> BandFit:
    """Fit the modes near ``guesses_hz`` [Hz] together in ``low_hz .. high_hz`` [Hz] of the
    record ``values`` sampled at ``sample_rate`` [Hz] (an acceleration, or with
    ``acceleration`` False a displacement); ``lines``: leave the spectral lines out
    (:func:`.bfft.line_mask`); ``start``: another record's fit of the same band and
    guesses, whose parameters (PSD levels scaled by the two records' median ordinates)
    start this fit, so that a record that differs a little is fitted in the same basin.

    Raises :class:`.bfft.IdentificationError` when a fitted frequency leaves the band or the
    fit carries no information on it."""
    x = np.asarray(values, dtype=float)
    n = x.size
    dt = 1.0 / sample_rate
    T = n * dt
    guesses = np.sort(np.atleast_1d(np.asarray(guesses_hz, dtype=float)))
    kk = np.arange(math.ceil(low_hz * T), math.floor(high_hz * T) + 1)
    P = (dt / n) * np.abs(np.fft.rfft(x - x.mean())[kk]) ** 2
    f = kk / T
    if lines:
        keep = ~line_mask(P)
        P, f = P[keep], f[keep]
    k = guesses.size
    level = float(np.median(P))
    previous = start
    start = []
    for g in guesses:
        near = np.abs(f - g) < damping_guess * g
        peak = float(P[near].max()) if near.any() else level
        start += [g, math.log(damping_guess), math.log(max(peak * 4 * damping_guess ** 2,
                                                           1e-300))]
    start.append(math.log(max(float(np.percentile(P, 10)), 1e-300)))
    start = np.array(start)
    if previous is not None and previous.parameters is not None \
            and previous.parameters.size == start.size:
        start = previous.parameters.copy()
        rescale = math.log(level / previous.median_level)
        start[2:3 * k:3] += rescale
        start[-1] += rescale
    scale = np.ones_like(start)
    scale[0:3 * k:3] = damping_guess * guesses

    power = 4 if acceleration else 0

    def nll(qv):
        p = start + qv * scale
        D, grad = _psd(p, f, k, power)
        w = 1.0 / D - P / (D * D)
        return float(np.sum(np.log(D) + P / D)), (grad @ w) * scale

    result = minimize(nll, np.zeros_like(start), jac=True, method="L-BFGS-B",
                      options={"maxiter": 2000})
    p = start + result.x * scale
    D, grad = _psd(p, f, k, power)
    info = (grad / D) @ (grad / D).T
    try:
        cov = np.linalg.inv(info)
    except np.linalg.LinAlgError:
        raise IdentificationError(f"no information on the frequencies in {low_hz:.5g}.."
                                  f"{high_hz:.5g} Hz") from None
    freq = p[0:3 * k:3]
    zeta = np.exp(p[1:3 * k:3])
    S = np.exp(p[2:3 * k:3])
    variance = np.diag(cov)[0:3 * k:3]
    sigma = np.where(variance > 0, np.sqrt(np.abs(variance)), np.inf)  # < 0: no information
    order = np.argsort(freq)
    if np.any((freq <= low_hz) | (freq >= high_hz)):
        raise IdentificationError(f"a fitted mode left its band {low_hz:.5g}..{high_hz:.5g} Hz")
    return BandFit(freq[order], zeta[order], sigma[order],
                   (S / (4 * zeta ** 2 * math.exp(p[-1])))[order], (float(low_hz),
                                                                     float(high_hz)), p, level)

