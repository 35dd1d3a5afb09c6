"""The spectrum a record sees while the crack opens and closes as the planets pass (Hz).

A root crack in the ring opens and closes as the planets pass, so each coupled mode's
instantaneous natural frequency ``f_k(theta)`` is periodic in the carrier angle with the
period of one planet pitch, in time ``1 / f_pp`` with the planet-pass frequency
``f_pp = N Omega_c / 2 pi`` [Hz] (:attr:`hubvib.detection.carrier.MeshTiming.pass_frequency`).
A record spans many passes.  The carrier positions ``j`` sample one pitch; ``w_j`` is the
share of time the carrier spends at position ``j`` (normalised here).  Every mode keeps its
damping ratio ``zeta`` and its modal participation (modal force over modal mass) in every
state; only its stiffness changes.

Time scales of mode ``k``, with its dwell-weighted mean ``fbar = sum_j w_j f_j``:

* decay time ``tau = 1 / (2 pi zeta fbar)`` [s] (the amplitude falls by ``e`` in ``tau``);
* half-power bandwidth ``B = 2 zeta fbar`` [Hz], ``= 1 / (pi tau)``;
* the time the mode stays within half a bandwidth of where it is at position ``j``,
  ``t_j = s_j / f_pp`` with ``s_j = sum_i w_i [|f_i - f_j| <= zeta fbar]``: the dwell of
  all the positions whose frequencies cannot be told apart from ``f_j``, assumed visited in
  one stretch per pass (a crack that opens once and closes once per pass).  For a state
  that switches this is its duration; for a frequency swept smoothly over a span ``S``
  twice per pass it is ``~ B / (2 S f_pp)``, and ``t_j >> tau`` is then the usual
  quasi-stationary sweep condition ``S f_pp << B^2``.

The adiabatic ratio ``r = sum_j w_j t_j / tau = 2 pi zeta fbar sum_j w_j s_j / f_pp`` [-]
says which limit holds (it needs no order of the positions: a permutation of the
positions changes nothing).

**Quasi-static, ``r >= 1`` (ADIABATIC_LIMIT).**  Each state lasts longer than the decay
time, so the mode's response settles to that state's stationary response before the
state changes (the transients after a switch fill a share ``~ 2 tau f_pp`` of the record).
The record's power spectral density is the dwell-weighted mixture of the states'
responses to broadband forcing, here the velocity response of a damped mode::

    P(f) = sum_j w_j f^2 / ((f_j^2 - f^2)^2 + (2 zeta f_j f)^2)     (common factor dropped)

Its derivative in ``g = f^2`` is ``sum_j w_j (f_j^4 - g^2) / D_j^2``, so one state peaks
exactly at its natural frequency (the velocity response is the one without the
``sqrt(1 - 2 zeta^2)`` bias of the displacement peak or the ``1 / sqrt(1 - 2 zeta^2)`` of
the acceleration peak: a modal fit of a one-state record returns ``f_j``), and every
component rises below ``f_j`` and falls above it, so all peaks of ``P`` lie in
``[f_min, f_max]``.
The mixture is the limit ``r -> infinity``: at finite ``r`` each state's line is broadened
by its finite duration ``w_j / f_pp``, which pulls a smaller peak towards a larger one by
``O(gamma / r)``.

*Swing well inside the bandwidth* (``S = f_max - f_min << B``): near the peak each
component is a Lorentzian of half-width ``gamma = zeta fbar``; expanding ``P'`` in the
deviations ``d_j = f_j - fbar`` puts the peak at the dwell-weighted mean,
``f_peak = fbar + O(d^2)`` (first-order averaging; Nayfeh & Mook, Nonlinear Oscillations,
1979, ch. 5).  The second-order correction is
``f_peak - fbar ~= -2 mu_3 / gamma^2 - 5 sigma^2 / (2 fbar)`` with ``sigma^2 = sum w d^2``
[Hz^2] and ``mu_3 = sum w d^3`` [Hz^3]: the skew of the dwell distribution pulls the peak
towards the state that holds most of the time (dominant when ``zeta`` is small), and the
states' widths ``zeta f_j`` and heights ``~ 1 / f_j^2`` favour the lower ones.  Both are
``<< gamma`` while ``sigma << gamma``; as the swing approaches ``gamma`` the top of ``P``
flattens and the shift outgrows the expansion (two equal states ``gamma`` apart: four
times it).  This
module does not use the expansion: it finds the peaks of ``P`` numerically, at any swing.

*Beyond the bandwidth* the peaks of ``P`` are found on a grid over
``[f_min - gamma / 4, f_max + gamma / 4]`` no coarser than ``gamma / 16``, then refined by a
safeguarded Newton iteration on ``dP/dg = 0`` (to machine precision; the grid has at most
4097 points, coarser only for swings beyond 256 ``gamma``).  A local maximum is a
peak when its topographic prominence is at least ``PROMINENCE`` (5 %) of the highest value
of ``P``: a shallower dip is lost in the scatter of an averaged PSD estimate (relative
standard deviation ``1 / sqrt(segments)``, 5 % for 400 segments).  Peaks closer than the
resolution ``resolution_hz`` merge into the higher one.  Two Lorentzians of equal weight
form two maxima only when they are more than ``2 gamma / sqrt(3) = 0.58 B`` apart; unequal
dwell needs more.  Regimes (``regime``):

* ``"averaged"``: one peak within the resolution of the mean ``fbar``;
* ``"mixture"``: one peak, shifted from the mean by more than the resolution;
* ``"split"``: two or more peaks.

**Fast modulation, ``r < 1``.**  The states change faster than the mode decays: the
response never settles in any one state.  With ``f_pp << f`` (many cycles per pass) the
response is a mode of constant amplitude envelope whose phase runs at the instantaneous
frequency, a frequency modulation at ``f_pp``: a central line at the time average of the
instantaneous frequency, ``fbar`` (the phase the record accumulates per pass divided by
the pass duration; the Floquet frequency of the periodic system to first order), and
sidebands at ``fbar +- k f_pp``.  Regime ``"averaged"``, ``frequency_hz = fbar``.  The
sidebands are separate lines, each of width ``B``, when ``f_pp`` exceeds the bandwidth;
their power relative to the central line grows with the peak-to-peak phase excursion per
pass ``beta = pi sum_j w_j |f_j - fbar| / f_pp`` [rad] (``modulation_index``, for a
frequency that crosses its mean twice per pass); the central line is the highest while
``beta`` stays below about 1 rad.  :mod:`hubvib.detection.carrier` averages eigenvalues,
``sqrt(sum w f_j^2)``: the same to first order, higher by ``sigma^2 / (2 fbar)``; the phase
average ``fbar`` is the one the switching oscillator's Floquet exponent follows when
``f_pp << f`` (checked in the tests).

Neither limit is exact near ``r ~ 1``; both put a swing inside the bandwidth at ``fbar``.

``frequency_hz`` is the frequency an identification of the record returns, by this rule:
the highest peak of the mixture (quasi-static) or the central line (fast).  A peak-picking
identification returns it; a single-mode fit over a skewed hump lands between the peak
and ``fbar`` (in the ``"averaged"`` regime the two agree within the resolution).
``peaks_hz`` lists every peak; ``sidebands_hz`` the planet-pass sidebands
``fbar + (-2, -1, 1, 2) f_pp``, where a record with resolved sidebands shows lines that are
not modes.

Untracked positions (NaN) are left out of that mode, its dwell renormalised over the
rest; a mode with no tracked position of positive dwell has NaN results and regime
``"untracked"``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.signal import find_peaks

from hubvib.foundation.errors import InputError
from hubvib.foundation.output import finite_or_none

#: adiabatic ratio (dwell-weighted state time over decay time) from which a mode's record
#: is the dwell-weighted mixture of its states' responses [-]
ADIABATIC_LIMIT = 1.0
#: a local maximum of the mixture is a peak when its prominence is at least this share of
#: the mixture's highest value [-]
PROMINENCE = 0.05
#: default resolution: this share of each mode's half-power bandwidth [-]
RESOLUTION_SHARE = 0.01
#: planet-pass sideband orders reported, in the order of ``sidebands_hz``' columns
SIDEBAND_ORDERS = (-2, -1, 1, 2)
#: grid points per half-bandwidth ``zeta fbar`` of the peak search, and the grid's bounds
_GRID_PER_GAMMA = 16
_GRID_MIN, _GRID_MAX = 17, 4097
_NEWTON_STEPS = 40

__all__ = ["RecordSpectrum", "RecordSpectrumError", "record_spectrum", "ADIABATIC_LIMIT",
           "PROMINENCE", "RESOLUTION_SHARE", "SIDEBAND_ORDERS"]


class RecordSpectrumError(InputError):
    """An argument of :func:`record_spectrum` out of its range; the message names it."""


@dataclass(frozen=True, eq=False)
class RecordSpectrum:
    """What a record spanning many planet passes shows of each mode (Hz).

    Attributes
    ----------
    frequency_hz : ndarray, shape (modes,)
        The frequency an identification of the record returns [Hz]: the highest peak of
        the dwell-weighted mixture (quasi-static) or the central line (fast modulation).
    peaks_hz : tuple of tuple of float
        Every peak of each mode's record spectrum, ascending [Hz] (empty: untracked).
    mean_hz : ndarray, shape (modes,)
        Dwell-weighted mean of the instantaneous frequency [Hz].
    instantaneous_min_hz, instantaneous_max_hz, swing_hz : ndarray, shape (modes,)
        Lowest and highest instantaneous frequency over the positions with dwell, and
        their difference [Hz].
    bandwidth_hz : ndarray, shape (modes,)
        Half-power bandwidth ``2 zeta mean_hz`` [Hz].
    resolution_hz : ndarray, shape (modes,)
        Resolution [Hz] below which two peaks merge and a shift from the mean is none.
    adiabatic_ratio : ndarray, shape (modes,)
        Dwell-weighted time the mode stays within half a bandwidth, over its decay
        time [-]; at least ``ADIABATIC_LIMIT``: quasi-static.
    modulation_index : ndarray, shape (modes,)
        Peak-to-peak phase excursion per pass ``pi sum w |f - mean| / pass_hz`` [rad].
    regime : tuple of str
        Per mode ``"averaged"``, ``"mixture"``, ``"split"`` or ``"untracked"``.
    sidebands_hz : ndarray, shape (modes, 4)
        Planet-pass sidebands ``mean_hz + k pass_hz``, ``k`` in ``SIDEBAND_ORDERS`` [Hz].
    pass_hz : float
        Planet-pass frequency [Hz].
    damping_ratio : float
        Modal damping ratio [-].
    """

    frequency_hz: np.ndarray
    peaks_hz: tuple
    mean_hz: np.ndarray
    instantaneous_min_hz: np.ndarray
    instantaneous_max_hz: np.ndarray
    swing_hz: np.ndarray
    bandwidth_hz: np.ndarray
    resolution_hz: np.ndarray
    adiabatic_ratio: np.ndarray
    modulation_index: np.ndarray
    regime: tuple
    sidebands_hz: np.ndarray
    pass_hz: float
    damping_ratio: float

    def rows(self) -> list[dict]:
        """One dict per mode for JSON (NaN as None)."""
        out = []
        for k, regime in enumerate(self.regime):
            out.append({
                "mode": k + 1, "regime": regime,
                "frequency_hz": finite_or_none(self.frequency_hz[k]),
                "peaks_hz": [finite_or_none(p) for p in self.peaks_hz[k]],
                "mean_hz": finite_or_none(self.mean_hz[k]),
                "instantaneous_min_hz": finite_or_none(self.instantaneous_min_hz[k]),
                "instantaneous_max_hz": finite_or_none(self.instantaneous_max_hz[k]),
                "swing_hz": finite_or_none(self.swing_hz[k]),
                "bandwidth_hz": finite_or_none(self.bandwidth_hz[k]),
                "resolution_hz": finite_or_none(self.resolution_hz[k]),
                "adiabatic_ratio": finite_or_none(self.adiabatic_ratio[k]),
                "modulation_index": finite_or_none(self.modulation_index[k]),
                "sidebands_hz": [finite_or_none(s) for s in self.sidebands_hz[k]],
            })
        return out


def record_spectrum(instantaneous_hz, dwell, damping_ratio: float, pass_hz: float, *,
                    resolution_hz: float | None = None) -> RecordSpectrum:
    """What a record spanning many planet passes shows of each mode (module docstring).

    Parameters
    ----------
    instantaneous_hz : array_like, shape (positions, modes) or (positions,)
        Each mode's natural frequency at each carrier position [Hz]; NaN where a mode is
        not tracked (that position is left out for that mode).
    dwell : array_like, shape (positions,)
        Share of time at each position [-], any positive scale (normalised).
    damping_ratio : float
        Modal damping ratio of every mode and state, in (0, 1) [-].
    pass_hz : float
        Planet-pass frequency ``N Omega_c / 2 pi`` [Hz], > 0.
    resolution_hz : float, optional
        Frequency resolution [Hz] (> 0); default ``RESOLUTION_SHARE`` of each mode's
        bandwidth.

    Returns
    -------
    RecordSpectrum
    """
    freq, weights = _checked(instantaneous_hz, dwell, damping_ratio, pass_hz, resolution_hz)
    zeta = float(damping_ratio)
    valid = weights > 0
    tracked = valid.any(axis=0)
    total = weights.sum(axis=0)
    w = np.divide(weights, total, out=np.zeros_like(weights), where=tracked)
    filled = np.where(valid, freq, 0.0)
    mean = np.where(tracked, (w * filled).sum(axis=0), np.nan)
    filled = np.where(valid, freq, mean)
    low = np.where(tracked, np.min(np.where(valid, freq, np.inf), axis=0), np.nan)
    high = np.where(tracked, np.max(np.where(valid, freq, -np.inf), axis=0), np.nan)
    gamma = zeta * mean
    near = np.abs(filled[:, None, :] - filled[None, :, :]) <= gamma
    together = np.einsum("im,ijm->jm", w, near)
    adiabatic = 2 * math.pi * zeta * mean * (w * together).sum(axis=0) / pass_hz
    beta = math.pi * (w * np.abs(filled - mean)).sum(axis=0) / pass_hz
    beta = np.where(tracked, beta, np.nan)
    resolution = (RESOLUTION_SHARE * 2 * gamma if resolution_hz is None
                  else np.where(tracked, float(resolution_hz), np.nan))

    modes = freq.shape[1]
    frequency = mean.copy()
    peaks: list[tuple] = [() if not t else (float(m),) for t, m in zip(tracked, mean)]
    regime = ["untracked" if not t else "averaged" for t in tracked]
    slow = np.flatnonzero(tracked & (adiabatic >= ADIABATIC_LIMIT))
    if slow.size:
        found = _mixture_peaks(filled[:, slow], w[:, slow], zeta, low[slow], high[slow],
                               mean[slow], resolution[slow])
        for k, (where, highest) in zip(slow, found):
            peaks[k] = tuple(float(p) for p in where)
            frequency[k] = highest
            if len(where) > 1:
                regime[k] = "split"
            elif abs(highest - mean[k]) > resolution[k]:
                regime[k] = "mixture"
    sidebands = mean[:, None] + pass_hz * np.asarray(SIDEBAND_ORDERS, float)[None, :]
    return RecordSpectrum(
        frequency_hz=frequency, peaks_hz=tuple(peaks), mean_hz=mean,
        instantaneous_min_hz=low, instantaneous_max_hz=high, swing_hz=high - low,
        bandwidth_hz=2 * gamma, resolution_hz=np.broadcast_to(resolution, (modes,)).copy(),
        adiabatic_ratio=np.where(tracked, adiabatic, np.nan), modulation_index=beta,
        regime=tuple(regime), sidebands_hz=sidebands, pass_hz=float(pass_hz),
        damping_ratio=zeta)


def _mixture_peaks(freq, w, zeta, low, high, mean, resolution):
    """Per mode (columns), the ascending peaks of the dwell-weighted mixture of velocity
    PSDs and its highest peak [Hz]; frequencies scaled by the mean inside."""
    lam = np.square(freq / mean)                                    # (positions, modes)
    gamma = zeta  # half-bandwidth in units of the mean
    lo = low / mean - gamma / 4
    hi = high / mean + gamma / 4
    points = int(np.clip(np.max(np.ceil(_GRID_PER_GAMMA * (hi - lo) / gamma)) + 1,
                         _GRID_MIN, _GRID_MAX))
    grid = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, points)[None, :]
    values = _mixture(np.square(grid), lam.T, w.T, zeta)            # (modes, points)
    step = (hi - lo) / (points - 1)
    # zero beyond both ends: outside [f_min, f_max] the mixture falls monotonically towards
    # 0, so the padded ends give each peak its topographic prominence
    padded = np.pad(values, ((0, 0), (1, 1)))
    rising = np.diff(padded, axis=1) > 0
    maxima = (rising[:, :-1] & ~rising[:, 1:]).sum(axis=1)
    mode_of, start = [], []
    for k in range(values.shape[0]):
        if maxima[k] <= 1:
            index = np.array([int(np.argmax(values[k]))])
        else:
            index, _ = find_peaks(padded[k], prominence=PROMINENCE * values[k].max())
            index = index - 1
        mode_of.extend([k] * index.size)
        start.extend(grid[k, index])
    mode_of = np.array(mode_of)
    x = _refine(np.array(start), step[mode_of], lam.T[mode_of], w.T[mode_of], zeta)
    height = _mixture(np.square(x)[:, None], lam.T[mode_of], w.T[mode_of], zeta)[:, 0]
    out = []
    for k in range(values.shape[0]):
        mine = mode_of == k
        f, h = x[mine] * mean[k], height[mine]
        order = np.argsort(-h)
        kept: list[float] = []
        for i in order:
            if all(abs(f[i] - q) > resolution[k] for q in kept):
                kept.append(float(f[i]))
        out.append((sorted(kept), kept[0]))
    return out


def _mixture(g, lam, w, zeta):
    """Dwell-weighted sum of velocity PSDs at ``g = f^2`` (rows: modes or peaks)."""
    g = g[..., None]
    lam = lam[:, None, :]
    return np.sum(w[:, None, :] * g / ((lam - g) ** 2 + 4 * zeta**2 * lam * g), axis=-1)


def _refine(x0, step, lam, w, zeta):
    """Safeguarded Newton on ``dP/dg = 0`` in ``g = x^2``, within one grid step of the
    grid maximum ``x0`` (rows: peaks)."""
    a, b = np.square(x0 - step), np.square(x0 + step)
    g = np.square(x0)
    for _ in range(_NEWTON_STEPS):
        gg = g[:, None]
        d = (lam - gg) ** 2 + 4 * zeta**2 * lam * gg
        dd = -2 * (lam - gg) + 4 * zeta**2 * lam
        num = lam**2 - gg**2
        slope = np.sum(w * num / d**2, axis=1)
        curve = np.sum(w * (-2 * gg / d**2 - 2 * num * dd / d**3), axis=1)
        a = np.where(slope > 0, np.maximum(a, g), a)
        b = np.where(slope < 0, np.minimum(b, g), b)
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = g - slope / curve
        inside = np.isfinite(newton) & (newton >= a) & (newton <= b)
        nxt = np.where(inside, newton, 0.5 * (a + b))
        if np.all(np.abs(nxt - g) <= 1e-14 * g):
            g = nxt
            break
        g = nxt
    return np.sqrt(g)


def _checked(instantaneous_hz, dwell, damping_ratio, pass_hz, resolution_hz):
    freq = np.asarray(instantaneous_hz, dtype=float)
    if freq.ndim == 1:
        freq = freq[:, None]
    if freq.ndim != 2 or freq.shape[0] == 0:
        raise RecordSpectrumError(
            f"instantaneous_hz must have shape (positions, modes) with positions >= 1; "
            f"got shape {np.shape(instantaneous_hz)}")
    known = freq[~np.isnan(freq)]
    if known.size and not (np.all(np.isfinite(known)) and np.all(known > 0)):
        raise RecordSpectrumError(
            "instantaneous_hz must be finite and > 0 Hz (NaN: untracked); got "
            f"{known[~(np.isfinite(known) & (known > 0))][0]!r}")
    share = np.asarray(dwell, dtype=float)
    if share.shape != (freq.shape[0],):
        raise RecordSpectrumError(
            f"dwell must have shape ({freq.shape[0]},), one share per position of "
            f"instantaneous_hz; got shape {share.shape}")
    if not (np.all(np.isfinite(share)) and np.all(share >= 0) and share.sum() > 0):
        raise RecordSpectrumError(
            "dwell must be finite and >= 0 at every position with a positive sum; got "
            f"{np.array2string(share, precision=3, threshold=8)}")
    if not (0.0 < float(damping_ratio) < 1.0):
        raise RecordSpectrumError(f"damping_ratio must be in (0, 1); got {damping_ratio!r}")
    if not (math.isfinite(float(pass_hz)) and float(pass_hz) > 0):
        raise RecordSpectrumError(f"pass_hz must be finite and > 0 Hz; got {pass_hz!r}")
    if resolution_hz is not None and not (math.isfinite(float(resolution_hz))
                                          and float(resolution_hz) > 0):
        raise RecordSpectrumError(
            f"resolution_hz must be finite and > 0 Hz; got {resolution_hz!r}")
    weights = np.where(np.isnan(freq), 0.0, share[:, None])
    return freq, weights
