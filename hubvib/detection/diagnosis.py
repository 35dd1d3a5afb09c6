"""Crack depth from measured natural frequencies, with a credible interval (SI).

The reference is a Monte Carlo of the study's spectrum model
(:mod:`.spectrum_model`: the rigid-ring lumped model through :mod:`.uncertainty`, or
the elastic ring through :mod:`.elastic_model`): at every depth of the sweep,
the distribution of each mode's frequency as a record sees it.  For the measured modes the statistic is the shift against the
baseline (the reducer's own intact frequencies when the CSV gives
``baseline_hz``, else the model's nominal intact spectrum).  Its mean and
covariance over the samples, plus the identification noise (normal, standard
deviation ``sigma_i`` per identified frequency: the CSV's ``sigma_hz``, else the
Cramer-Rao bound of the Bayesian-FFT identification from the row's or the
scene's damping and record length, :mod:`hubvib.identification.law`; twice the
variance against a measured baseline), give a Gaussian likelihood at each depth,
interpolated linearly between the sweep's depths.  With a uniform prior on
``[0, deepest]``:

- ``not explained by a ring crack`` when no depth fits: the statistic
  ``Q = -2 max_d log L(d)`` (the whole pattern) or the largest standardised
  residual at the best depth (one mode alone) exceeds what the model itself
  produces.  Their null distributions are a parametric bootstrap (the Monte
  Carlo reducers of each sweep depth plus fresh identification noise, each
  fitted like the measurement); the p-value is the smaller tail fraction at the
  fitted depth, doubled (Bonferroni).  Below
  ``fit_false_alarm_rate`` the pattern (a rise, a uniform shift, a mode moving
  alone, a shift beyond the deepest crack) is not a ring crack; the nearest
  other explanation reported is a uniform relative shift of every mode
  (temperature or material modulus), fitted by generalised least squares with
  its own chi-squared p-value;
- ``not identifiable from these modes`` when the deepest crack moves the mean
  pattern of the measured modes by less than one standard deviation of an
  intact measurement (Mahalanobis distance < 1): the posterior is the prior;
- ``crack indicated`` when the likelihood ratio of the best depth against depth
  0 exceeds its critical value at the false-alarm rate (a one-parameter test on
  the boundary d >= 0: the 1 - 2 alpha quantile of chi-squared with one degree
  of freedom); the estimate is the posterior median, the interval the central
  credible interval at the confidence level;
- ``no crack indicated`` otherwise: depth 0, interval from 0 to the posterior
  quantile at the confidence level.

Either interval holds the posterior probability ``confidence``, so over depths
drawn from the prior it covers the true depth at that rate (law of total
probability) as far as the Gaussian likelihood is right; more identification
noise widens it.  Tests check coverage and false alarms on synthetic
measurements whose identification errors come from identified simulated records.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linear_sum_assignment
from scipy.stats import chi2, norm

from hubvib.detection.carrier import mesh_timing
from hubvib.detection.model import C_RP_RATIO, CrackModel
from hubvib.detection.options import detection_options
from hubvib.identification.law import fisher_sigma_hz
from hubvib.cases.runner import crack_cases

from .measured import Measured, MeasuredError
from .options import DetectionOptions
from .spectrum_model import as_spectrum_model

CRACK, NO_CRACK, NOT_IDENTIFIABLE, NOT_EXPLAINED = (
    "crack indicated", "no crack indicated", "not identifiable from these modes",
    "not explained by a ring crack")
#: points of the depth grid on which the posterior is evaluated
GRID = 400
#: bootstrap draws per sweep depth for the goodness-of-fit p-value
BOOTSTRAP = 1000


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
    sigma_hz : ndarray, shape (modes,)
        Standard deviation of one identified frequency of each mode [Hz] (scene's damping,
        record length and SNR).
    false_alarm_rate, detection_probability, confidence, fit_false_alarm_rate : float
        [-]
    drift_cov : ndarray, shape (modes, modes) or None
        Covariance of the drift between two records (temperature, load) [Hz^2].
    mesh_stiffness : dict
        Which ring-planet mesh stiffness the crack model uses
        (``CrackModel.mesh_stiffness``: ``c_rp_method``, ``c_rp_source``,
        ``c_rp_lumped_N_m``, ``c_rp_fe_intact_N_m``; the elastic ring's: ``k_rest_N_m``,
        its foundation and FE error).
    labels : tuple of str
        One name per mode.
    ring : str
        The spectrum model: ``"rigid"`` (9 + 3N) or ``"elastic"``.
    """

    depths: np.ndarray
    frequency_hz: np.ndarray
    nominal_hz: np.ndarray
    sigma_hz: np.ndarray
    false_alarm_rate: float
    detection_probability: float
    confidence: float
    fit_false_alarm_rate: float = 0.01
    drift_cov: np.ndarray | None = None
    mesh_stiffness: dict = field(default_factory=dict)
    labels: tuple = ()
    ring: str = "rigid"

    @property
    def n_modes(self) -> int:
        return self.nominal_hz.shape[1]

    def window(self) -> tuple[np.ndarray, np.ndarray]:
        """Per mode, the frequency range [Hz] the uncertainty model produces at any depth,
        widened by ten identification standard deviations (to pair a row with its mode)."""
        flat = self.frequency_hz.reshape(-1, self.n_modes)
        return flat.min(axis=0) - 10 * self.sigma_hz, flat.max(axis=0) + 10 * self.sigma_hz


def reference(model, options, timing, seed: int | None = None, workers: int = 1) -> Reference:
    """Monte Carlo reference of ``model`` (a ``SpectrumModel``, or a ``CrackModel``: the
    rigid-ring lumped model) under ``options``."""
    model = as_spectrum_model(model)
    rng = np.random.default_rng(options.seed + 1 if seed is None else seed)
    samples = model.sampled_hz(options, timing, options.samples, rng, workers)
    nominal_hz = model.nominal_hz(options, timing)
    drift = model.drift(nominal_hz[0], options)
    return Reference(np.array(model.depths), samples, nominal_hz,
                     options.sigma_hz(nominal_hz[0]), options.false_alarm_rate,
                     options.detection_probability, options.confidence,
                     options.fit_false_alarm_rate, drift.covariance(),
                     model.mesh_stiffness(), tuple(model.mode_labels()), model.ring)


def pair_modes(measured: Measured, ref: Reference) -> np.ndarray:
    """Model mode index (0-based) of every measured row; raises MeasuredError naming the line."""
    n, source = ref.n_modes, measured.source
    count = measured.frequency_hz.size
    if count > n:
        raise MeasuredError(f"{source}: {count} frequencies, but the {ref.ring} ring's model "
                            f"has only {n} modes")
    low, high = ref.window()
    if measured.mode is not None:
        for mode, line in zip(measured.mode, measured.lines):
            if mode > n:
                raise MeasuredError(f"{source} line {line}: mode = {mode}, but the {ref.ring} "
                                    f"ring's model has {n} modes (1..{n})")
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
                    f"nearest is {ref.ring} mode {i + 1} at {ref.nominal_hz[0, i]:.4g} Hz "
                    f"(range {low[i]:.4g}..{high[i]:.4g} Hz)")
            raise MeasuredError(
                f"{source} line {line}: {column} = {value:g} Hz lies outside the range of its "
                f"{ref.ring} mode {i + 1} ({low[i]:.4g}..{high[i]:.4g} Hz); it fits "
                f"{ref.ring} mode(s) "
                f"{', '.join(str(j + 1) for j in inside)}")
    return index


@dataclass(frozen=True)
class Diagnosis:
    """What measured frequencies say about the crack.

    Attributes
    ----------
    verdict : str
        ``"crack indicated"``, ``"no crack indicated"``, ``"not explained by a ring
        crack"`` or ``"not identifiable from these modes"``.
    depth, depth_low, depth_high : float or None
        Estimate and interval [m]; None when not identifiable or not explained.
    confidence : float
        Posterior probability of the interval [-].
    baseline : str
        ``"measured"`` (the CSV's baseline_hz) or ``"model"`` (nominal intact spectrum).
    modes : tuple of int
        Model modes used (1-based).
    shift_hz : ndarray
        Measured shift of each mode against the baseline [Hz].
    sigma_hz : ndarray
        Standard deviation of each identified frequency [Hz].
    informative : tuple of bool
        Per mode, whether the deepest crack moves it by more than one standard deviation
        of an intact measurement.
    likelihood_ratio, critical : float
        Test statistic against depth 0 and its critical value.
    fit_statistic, fit_p_value : float
        ``-2 max log L`` and the bootstrap p-value of the fit under the crack model [-].
    fit_depth : float
        Depth of the best fit [m].
    worst_mode : int
        Mode (1-based) with the largest standardised residual at the best fit.
    worst_z : float
        That residual [-] (positive: the mode lies above what the crack model predicts).
    uniform_shift, uniform_p_value : float
        Relative shift [-] common to all modes that fits best (temperature, material
        modulus) and its chi-squared p-value (1 for one mode: it always fits).
    """

    verdict: str
    depth: float | None
    depth_low: float | None
    depth_high: float | None
    confidence: float
    baseline: str
    modes: tuple[int, ...]
    shift_hz: np.ndarray
    sigma_hz: np.ndarray
    informative: tuple[bool, ...]
    likelihood_ratio: float | None
    critical: float
    fit_statistic: float
    fit_p_value: float
    fit_depth: float
    worst_mode: int
    worst_z: float
    uniform_shift: float
    uniform_p_value: float
    below: float | None = None

    @property
    def words(self) -> str:
        """The depth answer in words: ``depth 4.2 mm, 90 % interval 3.6 .. 4.9 mm``, ``below
        3 mm`` (under the shallowest computed crack: the sweep says no more), ``below 3 mm at
        90 %`` (no crack indicated) or ``-``."""
        if self.depth_high is None:
            return "-"
        c = f"{100 * self.confidence:g} %"
        if self.verdict == NO_CRACK:
            return f"below {1e3 * self.depth_high:.3g} mm at {c}"
        if self.below is not None:
            return (f"below {1e3 * self.below:.3g} mm, the shallowest crack computed "
                    f"({c} interval up to {1e3 * self.depth_high:.3g} mm)")
        low = ("below" if self.depth_low == 0 else f"{1e3 * self.depth_low:.3g}")
        return (f"depth {1e3 * self.depth:.3g} mm (posterior median), {c} interval {low} .. "
                f"{1e3 * self.depth_high:.3g} mm")

    def explanation(self, labels=()) -> str | None:
        """The nearest other explanation when the crack model does not fit (``labels``: the
        model's mode names, 0-based; default ``mode 7``)."""
        if self.verdict != NOT_EXPLAINED:
            return None
        worst = (labels[self.worst_mode - 1] if len(labels) >= self.worst_mode
                 else f"mode {self.worst_mode}")
        text = (f"{worst} misfits most ({self.worst_z:+.1f} standard "
                f"deviations {'above' if self.worst_z > 0 else 'below'} the best ring-crack "
                f"fit)")
        if len(self.modes) == 1:
            text += ("; with one mode a uniform relative shift of every mode (temperature or "
                     f"material modulus, here {100 * self.uniform_shift:+.3g} %) cannot be "
                     "ruled out")
        elif self.uniform_p_value >= 0.01:
            text += (f"; a uniform relative shift of {100 * self.uniform_shift:+.3g} % of every "
                     f"mode (temperature or material modulus) fits (p = "
                     f"{self.uniform_p_value:.2g})")
        else:
            text += (f"; a uniform relative shift does not fit either (best "
                     f"{100 * self.uniform_shift:+.3g} %, p = {self.uniform_p_value:.2g})")
        return text

    def to_dict(self) -> dict:
        return {"verdict": self.verdict, "depth_m": self.depth, "depth_low_m": self.depth_low,
                "depth_high_m": self.depth_high, "confidence": self.confidence,
                "baseline": self.baseline, "modes": list(self.modes),
                "shift_hz": [float(s) for s in self.shift_hz],
                "sigma_hz": [float(s) for s in self.sigma_hz],
                "informative": list(self.informative),
                "likelihood_ratio": self.likelihood_ratio, "critical_value": self.critical,
                "fit_statistic": self.fit_statistic, "fit_p_value": self.fit_p_value,
                "fit_depth_m": self.fit_depth, "worst_mode": self.worst_mode,
                "worst_mode_z": self.worst_z, "uniform_shift_relative": self.uniform_shift,
                "uniform_shift_p_value": self.uniform_p_value,
                "below_m": self.below, "answer": self.words,
                "explanation": self.explanation()}

    def labelled(self, labels) -> dict:
        """:meth:`to_dict` with each mode's name (``labels``: the model's, 0-based)."""
        return {**self.to_dict(), "mode_labels": [labels[m - 1] for m in self.modes],
                "explanation": self.explanation(labels)}


class Posterior:
    """Gaussian likelihood of the shifts of chosen modes over a fine depth grid.

    ``sigma_hz``: identification standard deviation of each chosen mode [Hz] (default the
    reference's); against a measured baseline both frequencies carry it.  The drift
    between records (the reference's ``drift_cov``) adds to the noise covariance.
    """

    def __init__(self, ref: Reference, modes: np.ndarray, measured_baseline: bool,
                 sigma_hz=None, seed: int = 0):
        self.ref, self.modes = ref, np.asarray(modes)
        self.sigma = (ref.sigma_hz[self.modes] if sigma_hz is None
                      else np.asarray(sigma_hz, dtype=float))
        X = ref.frequency_hz[:, :, self.modes]
        if measured_baseline:
            X = X - X[:, :1]
        else:
            X = X - ref.nominal_hz[0, self.modes]
        noise = np.diag((2.0 if measured_baseline else 1.0) * self.sigma ** 2)
        if ref.drift_cov is not None:
            noise = noise + ref.drift_cov[np.ix_(self.modes, self.modes)]
        self.noise = noise
        mean = X.mean(axis=0)
        centred = X - mean
        cov = np.einsum("sdi,sdj->dij", centred, centred) / (X.shape[0] - 1)
        cov += noise
        self.sweep_mean, self.sweep_cov = mean, cov
        self.grid = np.linspace(0.0, ref.depths[-1], GRID)
        self.mean = _interpolate(ref.depths, mean, self.grid)
        self.cov = _interpolate(ref.depths, cov, self.grid)
        self.inverse = np.linalg.inv(self.cov)
        self.logdet = np.linalg.slogdet(self.cov)[1]
        self.null = self._bootstrap(X, np.random.default_rng(seed))

    def _bootstrap(self, X: np.ndarray, rng) -> np.ndarray:
        """Sorted fit statistics (:meth:`fit_statistics`) of model reducers plus noise,
        shape (2, depths, draws); the drawn reducers and their noise are kept for the null
        between the sweep's depths (:meth:`null_at`)."""
        draws = min(BOOTSTRAP, X.shape[0])
        pick = rng.choice(X.shape[0], draws, replace=False)
        root = np.linalg.cholesky(self.noise)
        self._drawn = X[pick]
        self._noise_draws = rng.standard_normal((draws, 1, self.modes.size)) @ root.T
        y = self._drawn + self._noise_draws
        stats = np.stack([np.stack(self.fit_statistics(y[:, k])) for k in range(X.shape[1])],
                         axis=1)
        return np.sort(stats, axis=-1)

    def null_at(self, depth: float) -> np.ndarray:
        """Sorted fit statistics (2, draws) of the bootstrap reducers with a crack of
        ``depth`` [m]: at a sweep depth the stored ones, between two the same reducers'
        frequencies interpolated linearly (what the model says a crack there does), plus
        the same noise draws."""
        depths = self.ref.depths
        at = np.flatnonzero(np.isclose(depths, depth, rtol=0, atol=1e-12 * depths[-1]))
        if at.size:
            return self.null[:, int(at[0])]
        k = int(np.clip(np.searchsorted(depths, depth) - 1, 0, depths.size - 2))
        t = (depth - depths[k]) / (depths[k + 1] - depths[k])
        y = ((1 - t) * self._drawn[:, k] + t * self._drawn[:, k + 1]
             + self._noise_draws[:, 0])
        return np.sort(np.stack(self.fit_statistics(y)), axis=-1)

    def fit_statistics(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """For shifts ``y`` (..., modes): ``-2 max_d log L(d)`` (the whole pattern) and the
        largest standardised residual ``max_i |y_i - mu_i| / s_i`` at the best depth (one
        mode alone: a rise, a mode moving without the others)."""
        loglike = self.log_likelihood(y)
        best = loglike.argmax(axis=-1)
        r = np.asarray(y) - self.mean[best]
        spread = np.sqrt(np.diagonal(self.cov, axis1=-2, axis2=-1))[best]
        return -2 * loglike.max(axis=-1), np.abs(r / spread).max(axis=-1)

    def fit_p_value(self, statistics, depth: float) -> float:
        """Bootstrap p-value of the two fit statistics under a crack of ``depth`` [m]
        (:meth:`null_at`): the smaller tail fraction, doubled (Bonferroni over the two
        statistics), at most 1."""
        null = self.null_at(depth)
        draws = null.shape[-1]
        p = [(1.0 + draws - np.searchsorted(row, value, side="left")) / (draws + 1.0)
             for row, value in zip(null, statistics)]
        return float(min(1.0, 2 * min(p)))

    def informative(self) -> np.ndarray:
        """Per mode: the deepest crack's mean shift exceeds one standard deviation of an
        intact measurement."""
        spread0 = np.sqrt(np.diagonal(self.sweep_cov[0]))
        return np.abs(self.sweep_mean[-1] - self.sweep_mean[0]) > spread0

    def separation(self) -> float:
        """Mahalanobis distance [-] between the mean patterns of the deepest crack and of an
        intact reducer, in the intact covariance: below 1 the posterior is the prior."""
        d = self.sweep_mean[-1] - self.sweep_mean[0]
        return float(np.sqrt(d @ np.linalg.solve(self.sweep_cov[0], d)))

    def log_likelihood(self, y: np.ndarray) -> np.ndarray:
        """Log-likelihood on the grid, shape (..., GRID), for shifts ``y`` (..., modes)."""
        r = np.asarray(y)[..., None, :] - self.mean
        return -0.5 * (np.einsum("...gi,gij,...gj->...g", r, self.inverse, r) + self.logdet)

    def uniform_fit(self, y: np.ndarray, frequency_hz: np.ndarray) -> tuple[float, float]:
        """Relative shift common to all modes (``y = eps f``) by generalised least squares
        with the intact covariance, and its chi-squared p-value (m - 1 degrees of freedom)."""
        C = self.cov[0]
        f = np.asarray(frequency_hz, dtype=float)
        w = np.linalg.solve(C, f)
        eps = float(w @ y / (w @ f))
        r = y - eps * f
        dof = y.size - 1
        p = 1.0 if dof == 0 else float(chi2.sf(float(r @ np.linalg.solve(C, r)), dof))
        return eps, p

    def diagnose(self, y: np.ndarray, baseline: str, frequency_hz=None) -> Diagnosis:
        """Diagnosis for one vector of measured shifts ``y`` [Hz]; ``frequency_hz``: the
        modes' intact frequencies [Hz] for the uniform-shift alternative (default the
        model's nominal ones)."""
        ref = self.ref
        y = np.asarray(y, dtype=float)
        informative = self.informative()
        critical = float(chi2.ppf(1 - 2 * ref.false_alarm_rate, 1))
        modes = tuple(int(m) + 1 for m in self.modes)
        loglike = self.log_likelihood(y)
        best = int(np.argmax(loglike))
        statistic = float(-2 * loglike[best])
        fit_depth = float(self.grid[best])
        p_fit = self.fit_p_value(self.fit_statistics(y), fit_depth)
        z = (y - self.mean[best]) / np.sqrt(np.diagonal(self.cov[best]))
        worst = int(np.argmax(np.abs(z)))
        f0 = ref.nominal_hz[0, self.modes] if frequency_hz is None else frequency_hz
        eps, p_uniform = self.uniform_fit(y, f0)
        ratio = float(2 * (loglike[best] - loglike[0]))
        common = dict(confidence=ref.confidence, baseline=baseline, modes=modes, shift_hz=y,
                      sigma_hz=self.sigma, informative=tuple(bool(b) for b in informative),
                      critical=critical, fit_statistic=statistic, fit_p_value=p_fit,
                      fit_depth=fit_depth, worst_mode=modes[worst], worst_z=float(z[worst]),
                      uniform_shift=eps, uniform_p_value=p_uniform)
        if p_fit < ref.fit_false_alarm_rate:
            return Diagnosis(NOT_EXPLAINED, None, None, None, likelihood_ratio=ratio, **common)
        if self.separation() < 1.0:
            return Diagnosis(NOT_IDENTIFIABLE, None, None, None, likelihood_ratio=None,
                             **common)
        cdf = _cdf(self.grid, loglike)
        c = ref.confidence
        computed = ref.depths
        shallowest = float(computed[1])
        below = None
        if ratio > critical:
            depth, low, high = (float(np.interp(q, cdf, self.grid))
                                for q in (0.5, (1 - c) / 2, (1 + c) / 2))
            verdict = CRACK
            if depth < shallowest:  # no depth computed there: the sweep says "below"
                depth, low, high, below = None, 0.0, max(high, shallowest), shallowest
            elif low < shallowest:
                low = 0.0
        else:
            bound = float(np.interp(c, cdf, self.grid))
            # the bound rounded up to a computed depth: the sweep tells no finer
            high = float(computed[min(np.searchsorted(computed, bound * (1 - 1e-12)),
                                      computed.size - 1)])
            depth, low, verdict = 0.0, 0.0, NO_CRACK
        return Diagnosis(verdict, depth, low, high, likelihood_ratio=ratio, below=below,
                         **common)


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


def measured_sigma(measured: Measured, ref: Reference, index: np.ndarray,
                   options=None) -> np.ndarray:
    """Identification standard deviation [Hz] of every measured row: its ``sigma_hz``,
    else the Cramer-Rao bound from its ``damping_ratio`` / ``record_s`` (the scene's
    where a column is missing), else the reference's value for its mode."""
    options = options or DetectionOptions()
    sigma = ref.sigma_hz[index].copy()
    if measured.sigma_hz is not None:
        return np.asarray(measured.sigma_hz, dtype=float)
    if measured.damping_ratio is None and measured.record_s is None:
        return sigma
    for row, f in enumerate(measured.frequency_hz):
        zeta = (options.damping_ratio if measured.damping_ratio is None
                else measured.damping_ratio[row])
        T = options.record_length if measured.record_s is None else measured.record_s[row]
        sigma[row] = fisher_sigma_hz(f, zeta, T, options.snr)
    return sigma


def diagnose(measured: Measured, ref: Reference, options=None) -> Diagnosis:
    """Pair the measured frequencies with model modes and diagnose the crack
    (``options``: the scene's DetectionOptions, for rows that give their own damping or
    record length)."""
    index = pair_modes(measured, ref)
    measured_baseline = measured.baseline_hz is not None
    base = measured.baseline_hz if measured_baseline else ref.nominal_hz[0, index]
    posterior = Posterior(ref, index, measured_baseline,
                          measured_sigma(measured, ref, index, options))
    return posterior.diagnose(measured.frequency_hz - base,
                              "measured" if measured_baseline else "model", base)


def synthetic_measurements(model, options, timing, depths: np.ndarray, seed: int,
                           workers: int = 1, errors=None) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies and own baselines [Hz] of reducers drawn from the uncertainty model of
    ``model`` (a ``SpectrumModel`` or a ``CrackModel``) with cracks of ``depths`` [m], each
    identified with the scene's identification scatter ``options.sigma_hz``, the drift
    between the two records (:mod:`.drift`) on the cracked one.

    ``errors(rng, shape)``: standardised identification errors (default standard normal),
    e.g. resampled from identified simulated records.  Returns arrays of shape
    (len(depths), modes): cracked and intact measurement.
    """
    rng = np.random.default_rng(seed)
    depths = np.asarray(depths, dtype=float)
    at = as_spectrum_model(model).at_depths(np.concatenate([[0.0], depths]))
    f = at.sampled_hz(options, timing, depths.size, rng, workers,
                      depth_index=np.arange(1, depths.size + 1))
    intact = at.nominal_hz(options, timing, long_record=True)[0]
    sigma = options.sigma_hz(intact)
    draw_errors = errors or (lambda generator, shape: generator.standard_normal(shape))
    noise = draw_errors(rng, f.shape) * sigma
    drift = at.drift(intact, options)
    return f[:, 1] + noise[:, 1] + drift.draw(rng, depths.size), f[:, 0] + noise[:, 0]


def scene_ring(scene) -> str:
    """The ring model(s) the scene's ``[elastic] ring`` asks for: rigid, elastic or both."""
    return scene.elastic.ring


def elastic_scene_model(scene):
    """The elastic-ring spectrum model of ``scene``'s crack sweep (its ``[elastic]`` table,
    or the defaults) over the depths the crack study computes: the sweep's, less a crack
    through the rim (it opens the ring), and those the study adds where the POD crosses
    the required probability (:func:`.elastic_refinement.refined_elastic`, the function
    ``hubvib run`` refines with).  The ring's cases come from the result cache, or are
    computed."""
    from hubvib.cases.sweep import crack_of
    from hubvib.reducer.stages import ring_gear

    from . import elastic_model
    from .elastic_refinement import refined_elastic

    table = scene.elastic
    sweep = scene.crack
    ring = ring_gear(sweep.reducer)
    depths = tuple(d for d in sweep.depths
                   if d == 0 or not crack_of(sweep, d).is_through(ring))
    crack = lambda d: crack_of(sweep, d)  # noqa: E731
    cases = [elastic_model.cached_case(*a)
             for a in elastic_model.case_arguments(sweep.reducer, depths, crack, table)]
    options = detection_options(scene)
    first = elastic_model.elastic_result(sweep.reducer, depths, crack, table, options, cases)
    refined, cases = refined_elastic(sweep.reducer, crack, table, options, first, cases)
    return elastic_model.elastic_spectrum_model(
        refined.depths, cases, load=None if table.crack_load == "open" else "working",
        options=options)


def scene_reference(scene, progress: bool = True, workers: int = 2, ring: str = "rigid"):
    """The Monte Carlo reference of ``scene``'s crack study and its DetectionOptions (FE
    cases from the cache or computed).  ``ring``: ``"rigid"`` (the 9 + 3N model) or
    ``"elastic"`` (the FE ring coupled to the lumped bodies).  A scene whose ``[signal]``
    table simulates with ``mesh_stiffness = "ratio"`` is diagnosed on the rigid ring with
    the crack entering c_rp by the same ratio (the model its simulated records come
    from)."""
    if ring not in ("rigid", "elastic"):
        raise ValueError(f"ring = {ring!r}; allowed: rigid, elastic")
    if scene.crack is None:
        raise ValueError(f"--scene {scene.name!r} has no [crack] study: diagnosis needs the "
                         "crack sweep it compares the measurement with")
    if scene.crack.model != "plane":
        raise ValueError(f"--scene {scene.name!r} is a solid crack-growth study (depth x "
                         "half-length): diagnosis needs a plane crack sweep, one crack "
                         "per depth ([crack] model = \"plane\")")
    options = detection_options(scene)
    timing = mesh_timing(scene.crack.reducer, options.carrier_speed)
    if ring == "elastic":
        return reference(elastic_scene_model(scene), options, timing, workers=workers), options
    fe, _ = crack_cases(scene.crack, progress)
    model = CrackModel.from_fe(scene.params, scene.crack, fe, scene.method,
                               c_rp_given=scene.c_rp_given)
    signal = scene.given("signal")  # absent: the records are not simulated by the scene
    if signal is not None and signal.mesh_stiffness == C_RP_RATIO:
        # the scene's records come from its [signal] model, whose cracked mesh is the FE
        # ratio on the preset's c_rp (hubvib.signal.signature_study.curves_for): compare like with like
        model = model.with_c_rp_method(C_RP_RATIO)
    ref = reference(model, options, timing, workers=workers)
    return ref, options


def diagnose_scene(scene, measured: Measured, progress: bool = True,
                   workers: int = 2, ring: str = "rigid") -> tuple[Diagnosis, Reference]:
    """Diagnosis of ``measured`` against the crack study of ``scene`` on the ``ring``
    model (``"rigid"`` or ``"elastic"``)."""
    ref, options = scene_reference(scene, progress, workers, ring)
    return diagnose(measured, ref, options), ref
