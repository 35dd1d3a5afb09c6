"""Detection rates of the indicators from many simulated records: ROC curves, POD vs depth
at a family-wise false-alarm rate.

Records: the noise-free steady-state record of each depth (the study's sensor) plus
noise of the study's RMS [m/s^2].  Two noise models, so that the rates are measured
on data the thresholds were not tuned on:

- *training* (thresholds): white Gaussian noise, ``3 x roc_records`` intact records;
- *evaluation* (rates): white Gaussian noise from independent seeds, ``roc_records``
  records per depth (intact included);
- *robustness* (reported, not claimed): ``roc_records`` intact records with coloured
  Gaussian noise (first-order autoregressive, coefficient 0.5: more energy at low
  orders) and as many with white Student-t noise of 6 degrees of freedom (kurtosis
  6, not the Gaussian 3), both at the same RMS: the family-wise false-alarm rate
  there shows how far thresholds trained on one noise carry to another.

Each indicator is oriented by the sign of its mean shift at the deepest crack (a
score that grows with the crack).  NA4 and NB4 use the mean residual / envelope
variance of the intact training records as their reference (the healthy baseline).

Thresholds (max-T calibration, Westfall & Young 1993, with a split-conformal quantile,
Vovk et al. 2005): the first half of the intact training records gives each
indicator's mean and standard deviation; on the second half each record's largest
standardised score ``max_j (x_j - mean_j) / std_j`` is taken, and ``T`` is the
``ceil((1 - alpha)(n + 1))``-th smallest of those n values.  Indicator j alarms above
``mean_j + T std_j``.  A new intact record from the same noise then raises any alarm
with probability <= alpha whatever the indicators' distributions and correlations
(exchangeability); a Gaussian model of each indicator with Bonferroni's
``z(1 - alpha / m)`` was tried first and let 0.13 through at alpha = 0.05 on the Raba
scene at 0.5 x noise: M6A and M8A of a noise-dominated difference signal have heavier
tails than a Gaussian.
POD(depth) = share of that depth's evaluation records above the threshold; the
family-wise false-alarm rate is *measured* on the intact evaluation records (share
with any indicator above its threshold) and reported with its binomial standard error.
ROC: (false-alarm rate, detection rate) over thresholds at every intact evaluation
value, and the area under it (Mann-Whitney statistic).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.signal import lfilter

from hubvib.foundation.output import explained

from .indicators import INDICATORS, GearOrders, ensemble_variances, indicators
from .records import synchronous_average, synchronous_averages

#: degrees of freedom of the heavy-tailed check noise
STUDENT_DOF = 6
#: coefficient of the autoregressive evaluation noise
AR_COEFFICIENT = 0.5
#: points kept per ROC curve in the JSON
CURVE_POINTS = 41
#: detection rate at which a depth counts as seen
SEEN = 0.9


def _student(rng: np.random.Generator, size: int) -> np.ndarray:
    """Unit-variance Student-t noise (variance of t_nu is nu / (nu - 2))."""
    return rng.standard_t(STUDENT_DOF, size) / math.sqrt(STUDENT_DOF / (STUDENT_DOF - 2))


def _values(tsas, gear: GearOrders, reference: tuple[float, float]) -> np.ndarray:
    """Indicator table (records, indicators) against fixed NA4 / NB4 references."""
    rows = [indicators(t, gear, [reference[0]], [reference[1]]).to_dict() for t in tsas]
    return np.array([[row[n] for n in INDICATORS] for row in rows])


def _ar1(rng: np.random.Generator, size: int) -> np.ndarray:
    """Unit-variance AR(1) noise ``n_k = c n_(k-1) + sqrt(1 - c^2) w_k`` (stationary start)."""
    c = AR_COEFFICIENT
    w = rng.standard_normal(size)
    w[0] /= math.sqrt(1 - c * c)
    return lfilter([math.sqrt(1 - c * c)], [1, -c], w)


NOISE = {"gaussian": lambda rng, n: rng.standard_normal(n), "ar1": _ar1, "student": _student}


#: records resampled together
BATCH = 64


def _tsas(clean_tsa, angle, size, points, rms, count, seed, model):
    """TSAs of ``count`` records: the clean TSA plus the TSA of the noise (the resampling
    is linear), the noise's in batches."""
    rng = np.random.default_rng(seed)
    out = []
    for start in range(0, count, BATCH):
        n = min(BATCH, count - start)
        noise = np.stack([NOISE[model](rng, size) for _ in range(n)], axis=1)
        out += list(clean_tsa + synchronous_averages(angle, rms * noise, points))
    return out


def auc(intact: np.ndarray, cracked: np.ndarray) -> float:
    """Area under the ROC curve: P(cracked score > intact score) + P(tie) / 2."""
    a = np.sort(intact)
    below = np.searchsorted(a, cracked, side="left")
    ties = np.searchsorted(a, cracked, side="right") - below
    return float((below + 0.5 * ties).sum() / (intact.size * cracked.size))


def roc_curve(intact: np.ndarray, cracked: np.ndarray) -> list[list[float]]:
    """[[false-alarm rate, detection rate], ...] over thresholds at the intact values."""
    thresholds = np.concatenate([[-np.inf], np.sort(intact), [np.inf]])
    rows = [[float(np.mean(intact > t)), float(np.mean(cracked > t))] for t in thresholds]
    keep = np.unique(np.linspace(0, len(rows) - 1, CURVE_POINTS).round().astype(int))
    return [rows[i] for i in keep]


def detection_rates(depths, clean, angle: np.ndarray, points: int, gear: GearOrders,
                    noise_rms: float, records: int, alpha: float, seed: int = 1) -> dict:
    """ROC / POD data of every indicator (see the module docstring).

    Parameters
    ----------
    depths : sequence of float
        Crack depths [m], intact (0) first.
    clean : list of (time [s], values [m/s^2])
        Noise-free record of each depth.
    angle : ndarray
        Carrier angle of the samples [rad] (tacho or constant speed).
    records : int
        Evaluation records per depth (training: 3 x as many intact ones).
    alpha : float
        Family-wise false-alarm rate, in (0, 0.5).

    Raises
    ------
    ValueError
        No intact depth first, no noise (every record alike), or ``alpha`` out of range.
    """
    if not depths or depths[0] != 0.0:
        raise ValueError("detection rates need the intact case (depth 0) first in [crack] "
                         "depths")
    if not 0 < alpha < 0.5:
        raise ValueError(f"[signal] false_alarm_rate = {alpha!r}; allowed: (0, 0.5)")
    if noise_rms <= 0:
        raise ValueError("[signal] noise_level = 0: every record is the same, no detection "
                         "rate; allowed: noise_level > 0 with roc_records > 0")
    clean_tsa = [synchronous_average(angle, v, points) for _, v in clean]
    size = clean[0][1].size
    train = _tsas(clean_tsa[0], angle, size, points, noise_rms, 3 * records, seed,
                  "gaussian")
    pairs = np.array([ensemble_variances(t, gear) for t in train])
    reference = (float(pairs[:, 0].mean()), float(pairs[:, 1].mean()))
    trained = _values(train, gear, reference)
    evaluated = [_values(_tsas(c, angle, size, points, noise_rms, records,
                               seed + 1000 * (i + 1), "gaussian"), gear, reference)
                 for i, c in enumerate(clean_tsa)]
    heavy = _values(_tsas(clean_tsa[0], angle, size, points, noise_rms, records,
                          seed + 999, "student"), gear, reference)
    coloured = _values(_tsas(clean_tsa[0], angle, size, points, noise_rms, records,
                             seed + 998, "ar1"), gear, reference)
    direction = np.sign(evaluated[-1].mean(axis=0) - evaluated[0].mean(axis=0))
    direction[direction == 0] = 1.0
    trained = trained * direction
    half = trained.shape[0] // 2
    mean, spread = trained[:half].mean(axis=0), trained[:half].std(axis=0, ddof=1)
    spread[spread == 0] = np.finfo(float).tiny
    largest = np.sort(((trained[half:] - mean) / spread).max(axis=1))
    n = largest.size
    rank = math.ceil((1 - alpha) * (n + 1))
    if rank > n:
        raise ValueError(f"[signal] roc_records = {records}: {n} calibration records cannot "
                         f"set a family-wise rate of {alpha:g}; allowed: roc_records >= "
                         f"{math.ceil(2 * (1 - alpha) / alpha / 3) + 1}")
    z = float(largest[rank - 1])
    threshold = mean + z * spread
    scores = [e * direction for e in evaluated]
    alarms = [s > threshold for s in scores]
    family = float(alarms[0].any(axis=1).mean())
    heavy_alarms = heavy * direction > threshold
    coloured_alarms = coloured * direction > threshold
    out = {"false_alarm_rate": alpha, "max_z_threshold": z, "training_records": 3 * records,
           "records_per_depth": records, "noise_rms_m_s2": noise_rms,
           "training_noise": "white Gaussian", "evaluation_noise":
               "white Gaussian, independent seeds",
           "coloured_noise": f"Gaussian AR(1), coefficient {AR_COEFFICIENT}, same RMS",
           "family_false_alarm_coloured": float(coloured_alarms.any(axis=1).mean()),
           "heavy_tail_noise": f"white Student-t, {STUDENT_DOF} degrees of freedom, same RMS",
           "family_false_alarm_heavy_tail": float(heavy_alarms.any(axis=1).mean()),
           "depth_mm": [1e3 * d for d in depths],
           "family_false_alarm_measured": family,
           "family_false_alarm_standard_error": math.sqrt(max(family * (1 - family), 1e-12)
                                                          / records),
           "any_indicator_pod": [float(a.any(axis=1).mean()) for a in alarms],
           "indicators": {}}
    for j, name in enumerate(INDICATORS):
        pod = [float(a[:, j].mean()) for a in alarms]
        seen = next((1e3 * d for d, p in zip(depths[1:], pod[1:]) if p >= SEEN), None)
        out["indicators"][name] = explained({
            "direction": "increasing" if direction[j] > 0 else "decreasing",
            "threshold": float(threshold[j] * direction[j]),
            "false_alarm_measured": pod[0], "pod": pod,
            "false_alarm_heavy_tail": float(heavy_alarms[:, j].mean()),
            "false_alarm_coloured": float(coloured_alarms[:, j].mean()),
            "auc": [auc(scores[0][:, j], s[:, j]) for s in scores],
            "first_depth_seen_mm": seen,
            "roc": [roc_curve(scores[0][:, j], s[:, j]) for s in scores[1:]]},
            first_depth_seen_mm=f"no cracked depth of the sweep raises this indicator's "
                                f"alarm rate to {SEEN:g}")
    return out
