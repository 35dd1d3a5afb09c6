"""One mode's natural frequency from one record: Bayesian FFT / Whittle likelihood (SI).

Within the band ``f_g (1 +- kappa zeta_g)`` around a guess, the scaled FFT
ordinates ``F_k = sqrt(dt / N) sum_j x_j exp(-2 pi i j k / N)`` of a stationary
record are asymptotically independent complex Gaussians with variance ``D_k``,
the two-sided PSD (Yuen, Katafygiotis & Beck 2002).  For one mode under white
force plus white noise ``D_k = S |h(f_k; f, zeta)|^2 + S_e``.  The estimate
maximises ``-sum_k (ln D_k + |F_k|^2 / D_k)`` over ``(f, zeta, S, S_e)``: Au's
single-mode Bayesian FFT method (Au 2011, "Fast Bayesian FFT method for ambient
modal identification with separated modes", J. Eng. Mech. 137), whose
uncertainty is the law of :mod:`.law`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import median_filter, uniform_filter1d
from scipy.optimize import minimize

from .law import KAPPA, fisher_sigma_hz, response_shape


#: half-width of the running mean a spectral line is judged against [frequency lines]
LINE_HALF_WIDTH = 25
#: family-wise rate at which a band of a record without lines loses a line [-]
LINE_FALSE_ALARM = 1e-3
#: ordinates above this many local medians (over ln 2) are clipped out of the running mean
LINE_CLIP = 10.0
#: largest damping ratio a fit may return [-]; a fit is also refused when its half-power
#: bandwidth ``2 zeta f`` exceeds the band ``2 kappa zeta_g f`` it was fitted in
MAX_DAMPING = 0.5


def line_mask(P: np.ndarray) -> np.ndarray:
    """True where a periodogram ordinate ``P`` is a deterministic spectral line (gear mesh
    orders, shaft orders) rather than the broadband response: above ``c`` times the local
    level, the running mean over ``2 LINE_HALF_WIDTH + 1`` lines of the ordinates clipped
    at ``LINE_CLIP`` local means (estimated by the running median over ln 2).

    Without lines the ordinates are exponential about their mean ``D``, ``P(P > c D) =
    exp(-c)``; ``c = ln(n / LINE_FALSE_ALARM)`` keeps the chance that any of ``n`` lines is
    dropped near ``LINE_FALSE_ALARM`` (measured in the tests).  A periodic component's
    ordinate grows with the record length (``A^2 T / 4``), the broadband one's does not, so
    long records separate them (notching the lines, as operational modal analysis of
    gearboxes does)."""
    P = np.asarray(P, dtype=float)
    width = 2 * LINE_HALF_WIDTH + 1
    median = median_filter(P, size=width, mode="nearest") / math.log(2.0)
    level = uniform_filter1d(np.minimum(P, LINE_CLIP * median), width, mode="nearest")
    return P > math.log(P.size / LINE_FALSE_ALARM) * level


class IdentificationError(ValueError):
    """No mode could be identified in the band; the message says why, in a few words (a fit
    that left its band is not quoted: its numbers describe no resonance)."""


@dataclass(frozen=True)
class IdentifiedMode:
    """One identified mode.

    Attributes
    ----------
    frequency_hz : float
        Natural frequency [Hz].
    damping_ratio : float
        [-]
    snr : float
        Modal signal-to-noise ratio ``S / (4 zeta^2 S_e)`` [-].
    sigma_hz : float
        Standard deviation of ``frequency_hz`` [Hz]: the Cramer-Rao bound at the estimate
        (:func:`.law.fisher_sigma_hz`).
    """

    frequency_hz: float
    damping_ratio: float
    snr: float
    sigma_hz: float


def identify_mode(values, sample_rate: float, guess_hz: float, damping_guess: float = 0.02,
                  kappa: float = KAPPA, acceleration: bool = False,
                  lines: bool = False) -> IdentifiedMode:
    """Identify the mode near ``guess_hz`` [Hz] in the record ``values`` sampled at
    ``sample_rate`` [Hz]; ``damping_guess`` [-] sets the band ``guess (1 +- kappa zeta)``.
    ``acceleration``: the record is an acceleration with white noise on it; the response
    shape is ``b^4 |h|^2`` (:func:`.law.response_shape` with power 4).  ``lines``: the
    frequency lines :func:`line_mask` calls spectral lines are left out of the likelihood
    (the remaining ordinates stay independent; the Cramer-Rao bound is that of the whole
    band).

    Raises :class:`IdentificationError` when the fit finds no resonance in the band: its
    frequency outside the band, its half-power bandwidth wider than the band (or damping
    above ``MAX_DAMPING``), or its modal SNR not above 1."""
    x = np.asarray(values, dtype=float)
    n = x.size
    dt = 1.0 / sample_rate
    T = n * dt
    lo, hi = guess_hz * (1 - kappa * damping_guess), guess_hz * (1 + kappa * damping_guess)
    if not (0 < lo and hi < 0.5 * sample_rate):
        raise ValueError(f"band {lo:g}..{hi:g} Hz around {guess_hz:g} Hz must lie within "
                         f"0..{0.5 * sample_rate:g} Hz (Nyquist of the record)")
    k = np.arange(math.ceil(lo * T), math.floor(hi * T) + 1)
    if k.size < 8:
        raise ValueError(f"a {T:g} s record has only {k.size} frequency lines in "
                         f"{lo:g}..{hi:g} Hz; at least 8 are needed")
    spectrum = np.fft.rfft(x - x.mean())
    P = (dt / n) * np.abs(spectrum[k]) ** 2
    f = k / T
    if lines:
        keep = ~line_mask(P)
        P, f = P[keep], f[keep]
    power = 4 if acceleration else 0
    width = max(1, int(round(damping_guess * guess_hz * T)))
    smooth = np.convolve(P, np.ones(width) / width, mode="same")
    f_start = float(f[np.argmax(smooth)])
    floor = float(np.median(np.concatenate([P[: P.size // 10 + 1], P[-(P.size // 10 + 1):]])))
    S_start = max(float(smooth.max()) * 4 * damping_guess ** 2, 1e-300)

    def nll(q):
        p = start + q * scale
        f0, zeta, S, Se = p[0], math.exp(p[1]), math.exp(p[2]), math.exp(p[3])
        b = f / f0
        g = (1 - b * b) ** 2 + (2 * zeta * b) ** 2
        bp = b ** power
        h2 = bp / g
        D = S * h2 + Se
        w = 1.0 / D - P / (D * D)
        dg_db = -4 * b * (1 - b * b) + 8 * zeta * zeta * b
        grad = np.array([np.sum(w * S * (bp * dg_db * b / g ** 2 - power * h2) / f0),
                         np.sum(w * S * -bp / g ** 2 * 8 * zeta * b * b) * zeta,
                         np.sum(w * S * h2), np.sum(w * Se)]) * scale
        return float(np.sum(np.log(D) + P / D)), grad

    start = np.array([f_start, math.log(damping_guess), math.log(S_start),
                      math.log(max(floor, 1e-12 * smooth.max(), 1e-300))])
    scale = np.array([damping_guess * guess_hz, 1.0, 1.0, 1.0])
    result = minimize(nll, np.zeros(4), jac=True, method="BFGS", options={"gtol": 1e-8})
    p = start + result.x * scale
    f0, zeta, S, Se = float(p[0]), math.exp(p[1]), math.exp(p[2]), math.exp(p[3])
    snr = S / (4 * zeta * zeta * Se)
    band = f"{lo:.5g}..{hi:.5g} Hz"
    if not lo < f0 < hi:
        raise IdentificationError(f"no resonance found in its band {band} (the fit left "
                                  "the band)")
    if not 0 < zeta < min(MAX_DAMPING, kappa * damping_guess):
        raise IdentificationError(f"no resonance found in its band {band} (the fitted peak "
                                  "is wider than the band)")
    if not snr > 1:
        raise IdentificationError(f"no resonance found in its band {band} (no peak above the "
                                  "noise)")
    try:
        sigma = fisher_sigma_hz(f0, zeta, T, min(snr, 1e12), kappa, power)
    except np.linalg.LinAlgError:
        raise IdentificationError(f"no resonance found in its band {band} (the fit carries "
                                  "no information on the frequency)") from None
    return IdentifiedMode(f0, zeta, snr, sigma)
