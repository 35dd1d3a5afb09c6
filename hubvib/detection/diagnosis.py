"""Crack depth from measured natural frequencies, with a credible interval (SI).

The reference is a Monte Carlo of the study's crack model (:mod:`.uncertainty`):
at every depth of the sweep, the distribution of each mode's frequency as a
record sees it.  For the measured modes the statistic is the shift against the
baseline (the reducer's own intact frequencies when the CSV gives
``baseline_hz``, else the model's nominal intact spectrum).  Its mean and
covariance over the samples, plus the measurement noise (uniform within
+-1/(2T) per identified frequency), give a Gaussian likelihood at each depth,
interpolated linearly between the sweep's depths.  With a uniform prior on
``[0, deepest]`` the posterior gives:

- ``not identifiable from these modes`` when no measured mode would tell the
  deepest crack from an intact reducer (its mean shift there stays within the
  false-alarm quantile at depth 0 plus the detection quantile at that depth);
- ``crack indicated`` when the likelihood ratio of the best depth against depth
  0 exceeds its critical value at the false-alarm rate (a one-parameter test on
  the boundary d >= 0: the 1 - 2 alpha quantile of chi-squared with one degree
  of freedom); the estimate is the posterior median, the interval the central
  credible interval at the confidence level;
- ``no crack indicated`` otherwise: depth 0, interval from 0 to the posterior
  quantile at the confidence level.

Either interval holds the posterior probability ``confidence``, so over depths
drawn from the prior it covers the true depth at that rate (law of total
probability) as far as the Gaussian likelihood is right; tests check it on
synthetic measurements.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment
from scipy.stats import chi2, norm

from hubvib.detection.carrier import mesh_timing
from hubvib.detection.model import CrackModel
from hubvib.detection.options import detection_options
from hubvib.studies.crack_sweep import run_fe_cases

from .measured import Measured, MeasuredError
from .uncertainty import draw, nominal, observed_frequencies

CRACK, NO_CRACK, NOT_IDENTIFIABLE = ("crack indicated", "no crack indicated",
                                     "not identifiable from these modes")
#: points of the depth grid on which the posterior is evaluated
GRID = 400


@dataclass(frozen=True)
class Reference:
    """Monte Carlo reference of a crack model.

    Attributes
    ----------
    depths : ndarray
        Sweep depths [m].
    frequency_hz : ndarray, shape (samples, depths, modes)
        Observed frequencies of the sampled reducers [Hz].
    nominal_hz : ndarray, shape (depths, modes)
        Observed frequencies of the nominal reducer [Hz].
    resolution_hz : float
        Frequency grid spacing 1/T [Hz].
    false_alarm_rate, detection_probability, confidence : float
        [-]
    """

    depths: np.ndarray
    frequency_hz: np.ndarray
    nominal_hz: np.ndarray
    resolution_hz: float
    false_alarm_rate: float
    detection_probability: float
    confidence: float

    @property
    def n_modes(self) -> int:
        return self.nominal_hz.shape[1]

    def window(self) -> tuple[np.ndarray, np.ndarray]:
        """Per mode, the frequency range [Hz] the uncertainty model produces at any depth,
        widened by one resolution step."""
        flat = self.frequency_hz.reshape(-1, self.n_modes)
        return flat.min(axis=0) - self.resolution_hz, flat.max(axis=0) + self.resolution_hz


def reference(model, options, timing, seed: int | None = None, workers: int = 1) -> Reference:
    """Monte Carlo reference of ``model`` (CrackModel) under ``options``."""
    rng = np.random.default_rng(options.seed + 1 if seed is None else seed)
    fraction, long = timing.engaged_fraction, timing.long_record(options.record_length)
    samples = observed_frequencies(model, draw(model, options, options.samples, rng), fraction,
                                   long, workers)
    nominal_hz = observed_frequencies(model, nominal(model), fraction, long)[0]
    return Reference(np.array(model.depths), samples, nominal_hz, options.resolution_hz,
                     options.false_alarm_rate, options.detection_probability,
                     options.confidence)


def pair_modes(measured: Measured, ref: Reference) -> np.ndarray:
    """Model mode index (0-based) of every measured row; raises MeasuredError naming the line."""
    n, source = ref.n_modes, measured.source
    count = measured.frequency_hz.size
    if count > n:
        raise MeasuredError(f"{source}: {count} frequencies, but the model has only {n} modes")
    low, high = ref.window()
    if measured.mode is not None:
        for mode, line in zip(measured.mode, measured.lines):
            if mode > n:
                raise MeasuredError(f"{source} line {line}: mode = {mode}, but the model has "
                                    f"{n} modes (1..{n})")
        index = measured.mode - 1
    else:
        cost = np.abs(measured.frequency_hz[:, None] - ref.nominal_hz[0][None, :])
        rows, cols = linear_sum_assignment(cost)
        index = cols[np.argsort(rows)]
    for column, values in (("frequency_hz", measured.frequency_hz),
                           ("baseline_hz", measured.baseline_hz)):
        if values is None:
            continue
        for value, i, line in zip(values, index, measured.lines):
            if low[i] <= value <= high[i]:
                continue
            inside = np.flatnonzero((low <= value) & (value <= high))
            if inside.size == 0:
                raise MeasuredError(
                    f"{source} line {line}: {column} = {value:g} Hz is far from every model "
                    f"mode; the model's modes span {low.min():.4g}..{high.max():.4g} Hz, the "
                    f"nearest is mode {i + 1} at {ref.nominal_hz[0, i]:.4g} Hz "
                    f"(range {low[i]:.4g}..{high[i]:.4g} Hz)")
            raise MeasuredError(
                f"{source} line {line}: {column} = {value:g} Hz lies outside the range of its "
                f"mode {i + 1} ({low[i]:.4g}..{high[i]:.4g} Hz); it fits mode(s) "
                f"{', '.join(str(j + 1) for j in inside)}")
    return index


@dataclass(frozen=True)
class Diagnosis:
    """What measured frequencies say about the crack.

    Attributes
    ----------
    verdict : str
        ``"crack indicated"``, ``"no crack indicated"`` or
        ``"not identifiable from these modes"``.
    depth, depth_low, depth_high : float or None
        Estimate and interval [m]; None when not identifiable.
    confidence : float
        Posterior probability of the interval [-].
    baseline : str
        ``"measured"`` (the CSV's baseline_hz) or ``"model"`` (nominal intact spectrum).
    modes : tuple of int
        Model modes used (1-based).
    shift_hz : ndarray
        Measured shift of each mode against the baseline [Hz].
    informative : tuple of bool
        Per mode, whether it can tell the deepest crack from an intact reducer.
    likelihood_ratio, critical : float
        Test statistic against depth 0 and its critical value.
    """

    verdict: str
    depth: float | None
    depth_low: float | None
    depth_high: float | None
    confidence: float
    baseline: str
    modes: tuple[int, ...]
    shift_hz: np.ndarray
    informative: tuple[bool, ...]
    likelihood_ratio: float | None
    critical: float

    def to_dict(self) -> dict:
        return {"verdict": self.verdict, "depth_m": self.depth, "depth_low_m": self.depth_low,
                "depth_high_m": self.depth_high, "confidence": self.confidence,
                "baseline": self.baseline, "modes": list(self.modes),
                "shift_hz": [float(s) for s in self.shift_hz],
                "informative": list(self.informative),
                "likelihood_ratio": self.likelihood_ratio, "critical_value": self.critical}


class Posterior:
    """Gaussian likelihood of the shifts of chosen modes over a fine depth grid."""

    def __init__(self, ref: Reference, modes: np.ndarray, measured_baseline: bool):
        self.ref, self.modes = ref, np.asarray(modes)
        w = ref.resolution_hz
        X = ref.frequency_hz[:, :, self.modes]
        if measured_baseline:
            X = X - X[:, :1]
            noise = 2 * w * w / 12  # two uniform errors on the frequency grid
        else:
            X = X - ref.nominal_hz[0, self.modes]
            noise = w * w / 12
        mean = X.mean(axis=0)
        centred = X - mean
        cov = np.einsum("sdi,sdj->dij", centred, centred) / (X.shape[0] - 1)
        cov += noise * np.eye(self.modes.size)
        self.sweep_mean, self.sweep_cov = mean, cov
        self.grid = np.linspace(0.0, ref.depths[-1], GRID)
        self.mean = _interpolate(ref.depths, mean, self.grid)
        self.cov = _interpolate(ref.depths, cov, self.grid)
        self.inverse = np.linalg.inv(self.cov)
        self.logdet = np.linalg.slogdet(self.cov)[1]

    def informative(self) -> np.ndarray:
        """Per mode: the deepest crack's mean shift exceeds the false-alarm quantile at
        depth 0 plus the detection quantile at the deepest depth."""
        a = norm.ppf(1 - self.ref.false_alarm_rate)
        b = norm.ppf(self.ref.detection_probability)
        spread0 = np.sqrt(np.diagonal(self.sweep_cov[0]))
        spread = np.sqrt(np.diagonal(self.sweep_cov[-1]))
        return np.abs(self.sweep_mean[-1] - self.sweep_mean[0]) > a * spread0 + b * spread

    def log_likelihood(self, y: np.ndarray) -> np.ndarray:
        """Log-likelihood on the grid, shape (..., GRID), for shifts ``y`` (..., modes)."""
        r = np.asarray(y)[..., None, :] - self.mean
        return -0.5 * (np.einsum("...gi,gij,...gj->...g", r, self.inverse, r) + self.logdet)

    def diagnose(self, y: np.ndarray, baseline: str) -> Diagnosis:
        """Diagnosis for one vector of measured shifts ``y`` [Hz]."""
        ref = self.ref
        informative = self.informative()
        critical = float(chi2.ppf(1 - 2 * ref.false_alarm_rate, 1))
        modes = tuple(int(m) + 1 for m in self.modes)
        if not informative.any():
            return Diagnosis(NOT_IDENTIFIABLE, None, None, None, ref.confidence, baseline,
                             modes, np.asarray(y), tuple(bool(b) for b in informative), None,
                             critical)
        loglike = self.log_likelihood(y)
        ratio = float(2 * (loglike.max() - loglike[0]))
        cdf = _cdf(self.grid, loglike)
        c = ref.confidence
        if ratio > critical:
            depth, low, high = (np.interp(q, cdf, self.grid)
                                for q in (0.5, (1 - c) / 2, (1 + c) / 2))
            verdict = CRACK
        else:
            depth, low, high = 0.0, 0.0, np.interp(c, cdf, self.grid)
            verdict = NO_CRACK
        return Diagnosis(verdict, float(depth), float(low), float(high), c, baseline, modes,
                         np.asarray(y), tuple(bool(b) for b in informative), ratio, critical)


def _interpolate(x: np.ndarray, values: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Linear interpolation along the first axis."""
    index = np.clip(np.searchsorted(x, at, side="right") - 1, 0, x.size - 2)
    t = ((at - x[index]) / (x[index + 1] - x[index])).reshape((-1,) + (1,) * (values.ndim - 1))
    return (1 - t) * values[index] + t * values[index + 1]


def _cdf(grid: np.ndarray, loglike: np.ndarray) -> np.ndarray:
    """Posterior CDF on the grid under a uniform prior (trapezoidal rule)."""
    density = np.exp(loglike - loglike.max())
    steps = 0.5 * (density[1:] + density[:-1]) * np.diff(grid)
    cdf = np.concatenate([[0.0], np.cumsum(steps)])
    return cdf / cdf[-1]


def diagnose(measured: Measured, ref: Reference) -> Diagnosis:
    """Pair the measured frequencies with model modes and diagnose the crack."""
    index = pair_modes(measured, ref)
    measured_baseline = measured.baseline_hz is not None
    base = measured.baseline_hz if measured_baseline else ref.nominal_hz[0, index]
    posterior = Posterior(ref, index, measured_baseline)
    return posterior.diagnose(measured.frequency_hz - base,
                              "measured" if measured_baseline else "model")


def synthetic_measurements(model, options, timing, depths: np.ndarray, seed: int,
                           workers: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies and own baselines [Hz] of reducers drawn from the uncertainty model
    with cracks of ``depths`` [m], each identified on the 1/T grid (uniform error).

    Returns arrays of shape (len(depths), modes): cracked and intact measurement.
    """
    rng = np.random.default_rng(seed)
    depths = np.asarray(depths, dtype=float)
    at = model.at_depths(np.concatenate([[0.0], depths]))
    samples = draw(at, options, depths.size, rng)
    f = observed_frequencies(at, samples, timing.engaged_fraction,
                             timing.long_record(options.record_length), workers,
                             depth_index=np.arange(1, depths.size + 1))
    w = options.resolution_hz
    noise = rng.uniform(-w / 2, w / 2, size=f.shape)
    return f[:, 1] + noise[:, 1], f[:, 0] + noise[:, 0]


def diagnose_scene(scene, measured: Measured, progress: bool = True,
                   workers: int = 2) -> tuple[Diagnosis, Reference]:
    """Diagnosis of ``measured`` against the crack study of ``scene`` (FE cases from the
    cache or computed, then the Monte Carlo reference)."""
    if scene.crack is None:
        raise ValueError(f"--scene {scene.name!r} has no [crack] study: diagnosis needs the "
                         "crack sweep it compares the measurement with")
    if scene.crack.model != "plane":
        raise ValueError(f"--scene {scene.name!r} is a solid crack-growth study (depth x "
                         "half-length): diagnosis needs a plane crack sweep, one crack "
                         "per depth ([crack] model = \"plane\")")
    options = detection_options(scene)
    fe, _ = run_fe_cases(scene.crack, progress)
    model = CrackModel.from_fe(scene.params, scene.crack, fe, scene.method)
    ref = reference(model, options, mesh_timing(scene.crack.reducer, options.carrier_speed),
                    workers=workers)
    return diagnose(measured, ref), ref
