"""Scatter-interval screening of the NX computational experiment (seed 002, eqs. 21-22).

Prudnikov & Bodunova 2021 simulate the torus screw gear in Siemens NX and screen the input
torque record of each factor: values outside ``[y_mean - Delta, y_mean + Delta]``,
``Delta = k S`` (eq. 21, k the Student quantile, S the sample standard deviation; eq. 22), are
dropped and the mean is recomputed; then ``eta = M2 / (M1 u)``. The paper prints the bounds and
the screened means, not the records; :data:`PAPER_NX` holds them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import t


@dataclass(frozen=True)
class ScatterInterval:
    """Eqs. (21)-(22): centre, half-width ``Delta = k S`` and bounds [units of the data]."""

    mean: float
    half_width: float

    @property
    def low(self) -> float:
        return self.mean - self.half_width

    @property
    def high(self) -> float:
        return self.mean + self.half_width

    def to_dict(self) -> dict:
        return {"mean": self.mean, "half_width": self.half_width, "low": self.low,
                "high": self.high}


@dataclass(frozen=True)
class Screening:
    """A record screened by its scatter interval.

    Attributes
    ----------
    interval : ScatterInterval
        Bounds from the whole record.
    k : float
        Student quantile t_{(1 + confidence)/2, n - 1} [-].
    std : float
        Sample standard deviation S (ddof = 1).
    kept : tuple of float
        Values inside the interval.
    """

    interval: ScatterInterval
    k: float
    std: float
    kept: tuple[float, ...]

    @property
    def kept_mean(self) -> float:
        """Mean of the kept values (the paper's screened mean)."""
        return float(np.mean(self.kept))


def scatter_interval(mean: float, std: float, k: float) -> ScatterInterval:
    """Eq. (21) ``Delta = k S`` and eq. (22) ``[mean - Delta, mean + Delta]``."""
    if not (std >= 0.0 and k >= 0.0):
        raise ValueError(f"S and k must be >= 0, got S = {std:g}, k = {k:g}")
    return ScatterInterval(float(mean), float(k * std))


def interval_from_bounds(low: float, high: float) -> ScatterInterval:
    """The centre and ``Delta`` behind printed bounds ``[y_min, y_max]`` (eq. 22 inverted)."""
    if not high >= low:
        raise ValueError(f"y_max must be >= y_min, got [{low:g}, {high:g}]")
    return ScatterInterval((low + high) / 2.0, (high - low) / 2.0)


def screen(values, confidence: float = 0.95) -> Screening:
    """Drop the values outside the scatter interval of the record (one pass).

    Parameters
    ----------
    values : sequence of float
        The record, at least two finite values.
    confidence : float
        Two-sided confidence level of the Student quantile, in (0, 1).
    """
    data = np.asarray(values, dtype=float)
    if data.size < 2 or not np.all(np.isfinite(data)):
        raise ValueError(f"a record needs at least two finite values, got {data.size}")
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence:g}")
    k = float(t.ppf((1.0 + confidence) / 2.0, data.size - 1))
    std = float(np.std(data, ddof=1))
    interval = scatter_interval(float(np.mean(data)), std, k)
    kept = tuple(float(v) for v in data if interval.low <= v <= interval.high)
    return Screening(interval, k, std, kept)


def efficiency_from_torques(input_torque_n_m: float, output_torque_n_m: float,
                            ratio: float) -> float:
    """eta = M2 / (M1 u) [-]."""
    if not (input_torque_n_m > 0 and output_torque_n_m > 0 and ratio > 0):
        raise ValueError(f"M1, M2 and u must be > 0, got {input_torque_n_m:g}, "
                         f"{output_torque_n_m:g}, {ratio:g}")
    return output_torque_n_m / (input_torque_n_m * ratio)


@dataclass(frozen=True)
class NxFactor:
    """One factor of the paper's NX experiment, as printed.

    Attributes
    ----------
    label : str
        Finger shape and count.
    low, high : float
        Printed bounds y_min, y_max of the input torque [N m] (table).
    screened_mean : float
        Printed mean input torque after screening [N m].
    published_eta : float
        Printed efficiency [-].
    """

    label: str
    low: float
    high: float
    screened_mean: float
    published_eta: float

    def efficiency(self, output_torque_n_m: float = 150.0, ratio: float = 48.0) -> float:
        """eta from the screened mean, M2 = 150 N m and u = 48 as in the experiment [-]."""
        return efficiency_from_torques(self.screened_mean, output_torque_n_m, ratio)

    def to_dict(self) -> dict:
        interval = interval_from_bounds(self.low, self.high)
        return {"label": self.label, "y_min_n_m": self.low, "y_max_n_m": self.high,
                "centre_n_m": interval.mean, "delta_n_m": interval.half_width,
                "screened_mean_n_m": self.screened_mean, "eta": self.efficiency(),
                "published_eta": self.published_eta}


#: The paper's NX experiment: table of bounds, screened means and the printed eta.
PAPER_NX = (NxFactor("1: spherical fingers, 2 per roller", 2.780, 5.265, 4.013, 0.78),
            NxFactor("2: cylindrical fingers, 2 per roller", 1.127, 5.184, 3.257, 0.95),
            NxFactor("3: cylindrical fingers, 4 per roller", 0.351, 7.909, 3.788, 0.82))


def rounds_to(value: float, printed: float) -> bool:
    """True when ``value`` rounded to the printed digits gives ``printed``."""
    text = repr(float(printed))
    digits = len(text.split(".")[1]) if "." in text else 0
    return math.isclose(round(value, digits), printed, abs_tol=10.0 ** -(digits + 3))
