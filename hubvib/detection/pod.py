"""Probability of detecting a crack from the watched modes' frequencies, by Monte Carlo (SI).

Measurement: a natural frequency identified from one record of length T scatters
normally with the standard deviation of the identification method
(:meth:`.options.DetectionOptions.sigma_hz`: the Cramer-Rao bound of the
Bayesian-FFT identification, Au's law ``sqrt(zeta f / (2 pi T))`` in the limit),
independently from record to record.  Two baselines:

``measured``
    The reducer's own intact spectrum, identified the same way (monitoring).  The
    statistic of mode i, ``f_i(d) - f_i(0) + e_1 - e_0``, has noise
    ``N(0, 2 sigma_i^2)``; mode i alarms when it falls below ``-t_i`` with
    ``t_i = z(1 - alpha_m) sqrt(2) sigma_i``.  One-sided: a crack only softens
    springs, so by the Courant-Fischer min-max principle no natural frequency can
    rise.
``model``
    The model's nominal intact spectrum.  The unit's own scatter then enters the
    statistic ``f_i(d) + e - f_model,i(0)``; the threshold is the ``alpha_m``
    quantile of intact units, calibrated on samples drawn independently of those
    that give the POD.

The alarm family is the ``watched_modes`` modes with the largest mean shift at
the deepest crack against their identification scatter; every mode's threshold
holds the per-mode rate ``alpha_m = 1 - (1 - alpha)^(1/m)`` (Sidak), so an
intact reducer raises an alarm on some watched mode with probability ``alpha``
(the identification errors of different modes are independent).  The POD of a
mode at depth d is the fraction of sampled reducers (parameter scatter and FE
error, :mod:`.uncertainty`) that alarm on it, the measurement noise integrated
exactly; the family POD is the fraction that alarm on any watched mode, for
records of 10, 60 and 600 s as well as the scene's.  A nominal shift smaller
than the change that the FE error of the stiffness carrying it would cause is
flagged as not resolved: the FE stage cannot tell it apart from its own
discretisation error.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import brentq

from hubvib.identification.law import KAPPA
from hubvib.lumped import natural_modes

from .budget import chunked_frequencies
from .drift import Drift, drift_model, references
from .drift import family_pod as family_pod_mc
from .mode_names import mode_names, rigid_label
from .numbers import ROUND_OFF
from .uncertainty import draw, nominal, observed_frequencies_of

#: stiffnesses a ring crack changes, as the report names them
CARRIERS = ("c_ru", "c_r", "c_rp")


#: record lengths [s] of the family POD curves
RECORD_LENGTHS = (10.0, 60.0, 600.0)


def measured_threshold(sigma_hz, rate: float) -> np.ndarray:
    """Alarm threshold [Hz] of each mode on a shift against the reducer's own intact
    measurement: ``z(1 - rate) sqrt(2) sigma`` (``sigma_hz`` per mode [Hz], ``rate`` per
    mode [-])."""
    from scipy.stats import norm

    return norm.ppf(1.0 - rate) * math.sqrt(2.0) * np.asarray(sigma_hz, dtype=float)


def watched(shift_hz: np.ndarray, sigma_hz: np.ndarray, count: int) -> np.ndarray:
    """Indices (0-based) of the ``count`` modes whose shift ``shift_hz`` [Hz] is largest
    against their identification scatter ``sigma_hz`` [Hz], best first."""
    return np.argsort(-np.abs(shift_hz) / sigma_hz, kind="stable")[:min(count, shift_hz.size)]


@dataclass(frozen=True)
class NominalShifts:
    """Shifts of the nominal reducer as a record sees them, and what carries them.

    Attributes
    ----------
    frequency_hz : ndarray, shape (depths, modes)
        Observed frequencies [Hz].
    partial_hz : dict
        Shift [Hz] with only ``c_ru``, only ``c_r`` or only ``c_rp`` at the crack depth.
    fe_error_hz : dict
        Change of the frequency [Hz] when that stiffness's FE value at the crack depth
        moves by its error estimate.
    """

    frequency_hz: np.ndarray
    partial_hz: dict
    fe_error_hz: dict

    @property
    def shift_hz(self) -> np.ndarray:
        return self.frequency_hz - self.frequency_hz[0]

    @property
    def round_off_hz(self) -> np.ndarray:
        """Shift [Hz] below which a mode does not move (eigensolver round-off), per mode."""
        return ROUND_OFF * self.frequency_hz[0]

    @property
    def carried_by(self) -> np.ndarray:
        """Per depth and mode, the stiffness whose change alone shifts it most; ``"none"``
        where no change moves it beyond round-off."""
        stacked = np.abs(np.array([self.partial_hz[c] for c in CARRIERS]))
        names = np.array(CARRIERS)[stacked.argmax(axis=0)]
        return np.where(stacked.max(axis=0) > self.round_off_hz, names, "none")

    @property
    def carrier_error_hz(self) -> np.ndarray:
        """FE error effect [Hz] of the stiffness that carries each shift."""
        errors = np.array([self.fe_error_hz[c] for c in CARRIERS])
        index = np.abs(np.array([self.partial_hz[c] for c in CARRIERS])).argmax(axis=0)
        return np.take_along_axis(errors, index[None], axis=0)[0]


def nominal_shifts(model, fraction: float, long_record: bool) -> NominalShifts:
    """Nominal observed frequencies of ``model`` and the split of their shifts."""
    depths = len(model.depths)
    intact = {"c_ru": dict(c_ru_body=(model.c_ru_body[0],) * depths),
              "c_r": dict(c_r_body=(model.c_r_body[0],) * depths),
              "c_rp": dict(c_rp_ratio=(model.c_rp_ratio[0],) * depths)}
    variants = [model]
    for carrier in CARRIERS:
        others = {k: v for c, change in intact.items() if c != carrier for k, v in change.items()}
        variants.append(replace(model, **others))
    moved = {"c_ru": ("c_ru_body", "c_ru_body_error"), "c_r": ("c_r_body", "c_r_body_error"),
             "c_rp": ("c_rp_ratio", "c_rp_ratio_error")}
    for value, error in moved.values():
        values, errs = getattr(model, value), getattr(model, error)
        variants.append(replace(model, **{value: (values[0],) + tuple(
            v - e for v, e in zip(values[1:], errs[1:]))}))
    # the seven variants differ in stiffness values only: one batch (the same numbers)
    observed = [f[0] for f in observed_frequencies_of(
        [(v, nominal(v)) for v in variants], fraction, long_record)]
    total = observed[0]
    partial = {c: f - total[0] for c, f in zip(CARRIERS, observed[1:4])}
    errors = {c: np.abs(f - total) for c, f in zip(moved, observed[4:])}
    return NominalShifts(total, partial, errors)


@dataclass(frozen=True)
class PodResult:
    """Monte Carlo detection of a crack per depth and mode.

    Attributes
    ----------
    depths : ndarray
        [m]
    kind : tuple of str
        Mode types of the nominal intact spectrum.
    nominal : NominalShifts
    shift_mean_hz, shift_p05_hz, shift_p95_hz : ndarray, shape (depths, modes)
        Mean and 5 / 95 % quantiles of the sampled shift [Hz] (no measurement noise).
    sigma_hz : ndarray, shape (modes,)
        Standard deviation of one identified frequency [Hz] (scene's record length).
    watched : ndarray of int
        The alarm family (0-based mode indices).
    per_mode_rate : float
        False-alarm rate of each mode's threshold [-].
    threshold_hz : ndarray, shape (modes,)
        Alarm threshold against the reducer's own intact measurement [Hz].
    pod : ndarray, shape (depths, modes)
        Probability of detection against the reducer's own intact measurement [-].
    family_pod : dict
        Record length [s] -> ndarray (depths,): probability that some watched mode
        alarms (own intact baseline) [-].
    drift : Drift or None
        Temperature and load drift between records (:mod:`.drift`).
    references : ndarray of int or None
        Per watched mode, its reference mode for drift compensation (-1: none).
    family_pod_drift, family_pod_compensated : dict
        Record length [s] -> family POD (depths,) with the drift between the records,
        without and with compensation by the reference modes [-].
    threshold_model_hz, pod_model : ndarray or None
        The same against the model's nominal intact spectrum [Hz], [-].
    false_alarm_rate, detection_probability : float
        [-]
    samples : int
    """

    depths: np.ndarray
    kind: tuple
    nominal: NominalShifts
    shift_mean_hz: np.ndarray
    shift_p05_hz: np.ndarray
    shift_p95_hz: np.ndarray
    sigma_hz: np.ndarray
    watched: np.ndarray
    per_mode_rate: float
    threshold_hz: np.ndarray
    pod: np.ndarray
    family_pod: dict
    threshold_model_hz: np.ndarray | None
    pod_model: np.ndarray | None
    false_alarm_rate: float
    detection_probability: float
    samples: int
    drift: Drift | None = None
    references: np.ndarray | None = None
    family_pod_drift: dict = field(default_factory=dict)
    family_pod_compensated: dict = field(default_factory=dict)

    @property
    def resolved(self) -> np.ndarray:
        """(depths, modes): the nominal shift exceeds the FE error of what carries it (and
        round-off)."""
        nominal = self.nominal
        return np.abs(nominal.shift_hz) > np.maximum(nominal.carrier_error_hz,
                                                     nominal.round_off_hz)

    def detectable_depth(self, model_baseline: bool = False) -> np.ndarray:
        """Per mode, the smallest depth [m] with POD >= the required probability and a
        resolved shift; NaN where none is."""
        pod = self.pod_model if model_baseline else self.pod
        ok = (pod >= self.detection_probability) & self.resolved
        ok[0] = False
        first = np.where(ok.any(axis=0), ok.argmax(axis=0), -1)
        return np.where(first >= 0, self.depths[np.maximum(first, 0)], np.nan)

    def family_detectable_depth(self, record_length: float, which: str = "") -> float:
        """Smallest depth [m] whose family POD with records of ``record_length`` [s]
        reaches the required probability (``which``: ``""``, ``"drift"`` or
        ``"compensated"``); NaN when none does."""
        table = getattr(self, f"family_pod_{which}" if which else "family_pod")
        if record_length not in table:
            raise KeyError(f"no family POD for {record_length} s records"
                           + (" (a run without family curves)" if not table else
                              f"; it has {', '.join(f'{T:g} s' for T in table)}"))
        ok = table[record_length] >= self.detection_probability
        ok[0] = False
        return float(self.depths[int(ok.argmax())]) if ok.any() else math.nan

    def family_rows(self) -> list[dict]:
        """Family POD per depth and record length (``pod_family.csv``)."""
        f0 = self.nominal.frequency_hz[0]
        modes = "; ".join(rigid_label(int(i), self.kind[i], f0[i]) for i in self.watched)
        def at(table, T, k):
            return float(table[T][k]) if T in table else None

        return [{"depth_mm": 1e3 * float(d), "record_s": float(T), "watched_modes": modes,
                 "family_false_alarm_rate": self.false_alarm_rate,
                 "pod": float(self.family_pod[T][k]),
                 "pod_with_drift": at(self.family_pod_drift, T, k),
                 "pod_drift_compensated": at(self.family_pod_compensated, T, k)}
                for T in sorted(self.family_pod) for k, d in enumerate(self.depths)]

    def rows(self) -> list[dict]:
        nominal = self.nominal
        carried = nominal.carried_by
        names = mode_names(nominal.frequency_hz[0])
        rows = []
        for k, depth in enumerate(self.depths):
            for i, kind in enumerate(self.kind):
                rows.append({
                    "depth_mm": 1e3 * depth, "mode": i + 1, "mode_name": names[i],
                    "mode_label": rigid_label(i, kind, nominal.frequency_hz[0, i]),
                    "kind": kind,
                    "frequency_intact_hz": float(nominal.frequency_hz[0, i]),
                    "shift_hz": float(nominal.shift_hz[k, i]),
                    "shift_percent": float(100 * nominal.shift_hz[k, i]
                                           / nominal.frequency_hz[0, i]),
                    "shift_mean_hz": float(self.shift_mean_hz[k, i]),
                    "shift_p05_hz": float(self.shift_p05_hz[k, i]),
                    "shift_p95_hz": float(self.shift_p95_hz[k, i]),
                    "carried_by": str(carried[k, i]),
                    "fe_error_hz": float(nominal.carrier_error_hz[k, i]),
                    "resolved": bool(self.resolved[k, i]) if k else None,
                    "sigma_hz": float(self.sigma_hz[i]),
                    "watched": bool(i in self.watched),
                    "threshold_hz": float(self.threshold_hz[i]),
                    "pod": float(self.pod[k, i]),
                    "threshold_model_hz": (None if self.threshold_model_hz is None
                                           else float(self.threshold_model_hz[i])),
                    "pod_model": None if self.pod_model is None else float(self.pod_model[k, i])})
        return rows


def pod_study(model, options, timing, samples: int | None = None, model_baseline: bool = True,
              seed: int | None = None, workers: int = 1,
              chunk_points: int | None = None, family_curves: bool = True) -> PodResult:
    """POD of every mode at every depth of ``model`` (CrackModel).

    Parameters
    ----------
    model : CrackModel
    options : DetectionOptions
    timing : MeshTiming
        When the cracked tooth is in mesh (see :mod:`.carrier`).
    samples : int, optional
        Monte Carlo samples (default ``options.samples``).
    model_baseline : bool
        Also compute the POD against the model's intact spectrum.
    seed : int, optional
        Default ``options.seed``.
    chunk_points : int, optional
        Parameter points solved at once (default :data:`.budget.CHUNK_POINTS`; the numbers
        do not depend on it).
    family_curves : bool
        Also the watched family's POD per record length, the drift model and the
        reference modes (``family_pod``, ``drift``, ``references``; without it they are
        empty or None).  The map's POD runs use none of them, and the Cramer-Rao bounds
        of the 60 and 600 s records at every mounting value would be most of its work.
    """
    from scipy.stats import norm

    n = samples or options.samples
    rng = np.random.default_rng(options.seed if seed is None else seed)
    fraction, long = timing.engaged_fraction, timing.long_record(options.record_length)
    frequencies = chunked_frequencies(model, draw(model, options, n, rng), fraction, long,
                                      workers, chunk_points)
    shifts = frequencies - frequencies[:, :1]
    nominal_result = nominal_shifts(model, fraction, long)
    f0 = nominal_result.frequency_hz[0]
    sigma = options.sigma_hz(f0)
    family = watched(shifts[:, -1].mean(axis=0), sigma, options.watched_modes)
    rate = options.per_mode_rate(family.size)
    threshold = measured_threshold(sigma, rate)
    pod = norm.cdf((-threshold - shifts) / (math.sqrt(2) * sigma)).mean(axis=0)
    family_pod, drift, refs, drifting, compensated = {}, None, None, {}, {}
    if family_curves:
        for T in sorted({*RECORD_LENGTHS, options.record_length}):
            s_T = options.sigma_hz(f0[family], T)
            p = norm.cdf((-measured_threshold(s_T, rate) - shifts[..., family])
                         / (math.sqrt(2) * s_T))
            family_pod[T] = 1.0 - np.prod(1.0 - p, axis=-1).mean(axis=0)
        drift = drift_model(model.parameters(0), f0, options, model.method)
        refs = references(shifts[:, -1].mean(axis=0), sigma, drift, f0, family,
                          KAPPA * options.damping_ratio)
    if family_curves and model_baseline:  # the scene's study
        drift_rng = np.random.default_rng((options.seed, 7))
        for T in sorted({*RECORD_LENGTHS, options.record_length}):
            s_T = options.sigma_hz(f0, T)
            drifting[T] = family_pod_mc(shifts, s_T, f0, family, options.false_alarm_rate,
                                        drift_rng, drift)
            compensated[T] = family_pod_mc(shifts, s_T, f0, family,
                                           options.false_alarm_rate, drift_rng, drift, refs)
    threshold_model = pod_model = None
    if model_baseline:
        calibration = chunked_frequencies(model.at_depths([0.0]),
                                          draw(model, options, n, rng), fraction, long,
                                          workers, chunk_points)[:, 0]
        threshold_model = np.array([_quantile_threshold(calibration[:, i] - f0[i], sigma[i],
                                                        rate) for i in range(f0.size)])
        pod_model = norm.cdf((-threshold_model - (frequencies - f0)) / sigma).mean(axis=0)
    kind = natural_modes(model.parameters(0), model.method).kind
    return PodResult(np.array(model.depths), kind, nominal_result, shifts.mean(axis=0),
                     np.quantile(shifts, 0.05, axis=0), np.quantile(shifts, 0.95, axis=0),
                     sigma, family, rate, threshold, pod, family_pod, threshold_model,
                     pod_model, options.false_alarm_rate, options.detection_probability, n,
                     drift, refs, drifting, compensated)


def family_pod(shift_hz: np.ndarray, sigma_hz: np.ndarray, watched, rate: float) -> np.ndarray:
    """Probability that some watched mode alarms against the reducer's own intact record
    (the rule of this module's docstring, any spectrum model), per depth [-]: ``shift_hz`` (depths,
    modes) of one reducer, or (samples, depths, modes) of Monte Carlo reducers (their mean
    probability).  A NaN shift (the mode is not tracked) counts as no change."""
    from scipy.stats import norm

    z = norm.ppf(1.0 - rate)
    shift_hz = np.asarray(shift_hz, dtype=float)
    miss = np.ones(shift_hz.shape[:-1])
    for i in watched:
        d = np.nan_to_num(shift_hz[..., i], nan=0.0)
        scale = math.sqrt(2.0) * sigma_hz[i]
        miss *= norm.cdf((d + z * scale) / scale)
    pod = 1.0 - miss
    return pod if pod.ndim == 1 else pod.mean(axis=0)


def monte_carlo_shifts(model, options, timing=None, seed: int | None = None) -> np.ndarray:
    """Changes of every mode of ``options.samples`` Monte Carlo reducers of ``model`` (a
    ``SpectrumModel``) against their own intact spectrum [Hz], (samples, depths, modes);
    NaN where the model's nominal continuation of a mode is not tracked (its ``tracked``,
    (depths, modes), when it has one)."""
    rng = np.random.default_rng(options.seed + 3 if seed is None else seed)
    f = model.sampled_hz(options, timing, options.samples, rng)
    shift = f - f[:, :1]
    tracked = getattr(model, "tracked", None)
    if tracked is not None:
        shift[:, ~np.asarray(tracked)] = np.nan
    return shift


def watched_by_drop(shift_hz: np.ndarray, sigma_hz: np.ndarray, seen, count: int) -> tuple:
    """The ``count`` modes among ``seen`` (0-based) whose largest drop over the sweep
    (``shift_hz`` (depths, modes) [Hz], NaN: not tracked) is largest against their
    identification scatter ``sigma_hz`` [Hz], best first."""
    drop = np.nan_to_num(np.clip(-shift_hz, 0.0, None), nan=0.0).max(axis=0)
    seen = np.asarray(seen, dtype=int)
    order = seen[np.argsort(-drop[seen] / sigma_hz[seen], kind="stable")]
    return tuple(int(i) for i in order[:count])


def _quantile_threshold(offsets: np.ndarray, sigma: float, alpha: float) -> float:
    """t with mean(P(offset + e < -t)) = alpha, e normal with standard deviation sigma."""
    from scipy.stats import norm

    def excess(t):
        return norm.cdf((-t - offsets) / sigma).mean() - alpha

    low = -offsets.max() - 10 * sigma
    high = -offsets.min() + 10 * sigma
    return float(brentq(excess, low, high, xtol=1e-12 * max(1.0, abs(high))))
