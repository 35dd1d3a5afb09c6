"""From noise-free sampled records to noisy records, TSAs and indicators (SI).

One pipeline for the study's sensor, the extra sensors and the detection rates:
white Gaussian noise of a given RMS [m/s^2] per seed, the time-synchronous
average on ``points`` angle steps per carrier revolution, then the indicators with
the NA4 / NB4 ensemble of the run so far (depth by depth, intact first).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import CubicSpline

from .indicators import GearOrders, ensemble_variances, indicators
from .accelerometer import add_noise
from .spectral import angle_domain


def synchronous_average(angle: np.ndarray, values: np.ndarray, points: int) -> np.ndarray:
    """TSA of a record whose samples sit at carrier angles ``angle`` [rad] (from the
    tacho or the constant speed); samples past ``angle``'s end are left out."""
    return angle_domain(angle, np.asarray(values)[:len(angle)], points).synchronous_average()


def synchronous_averages(angle: np.ndarray, values: np.ndarray, points: int) -> np.ndarray:
    """TSAs of several records on the same sample angles, ``values`` (samples, records):
    the same cubic-spline resampling as :func:`synchronous_average`, all columns at once.
    Returns (records, points)."""
    angle = np.asarray(angle)
    values = np.asarray(values)[:angle.size]
    whole = int(math.floor((angle[-1] - angle[0]) / (2 * math.pi) + 1e-9))
    if whole < 1:
        raise ValueError(f"the record covers {(angle[-1] - angle[0]) / (2 * math.pi):.3g} "
                         f"revolutions; allowed: >= 1")
    grid = angle[0] + 2 * math.pi * np.arange(whole * points) / points
    on_grid = CubicSpline(angle, values, axis=0)(grid)
    return on_grid.reshape(whole, points, -1).mean(axis=0).T


def indicator_run(clean, angle: np.ndarray, points: int, gear: GearOrders, noise_rms: float,
                  seeds) -> tuple[list, list, list]:
    """Per depth (``clean``: list of (time [s], values [m/s^2])): the first seed's noisy
    record, the TSA of every seed and its indicators; ``angle`` [rad]: the carrier
    angle of the samples (see :func:`synchronous_average`).

    Returns
    -------
    first_records, tsas, values : list (per depth)
    """
    variances, envelopes = [], []
    first, tsas, values = [], [], []
    for t, v in clean:
        records = [add_noise(v, noise_rms, seed) for seed in seeds]
        first.append(records[0])
        averaged = [synchronous_average(angle, r, points) for r in records]
        for tsa in averaged:
            r, s = ensemble_variances(tsa, gear)
            variances.append(r)
            envelopes.append(s)
        tsas.append(averaged)
        values.append([indicators(tsa, gear, variances, envelopes) for tsa in averaged])
    return first, tsas, values


def summarise(values, names) -> dict:
    """Mean and standard deviation of each indicator over the records."""
    table = np.array([[getattr(v, name) for name in names] for v in values])
    return {name: {"mean": float(table[:, i].mean()), "std": float(table[:, i].std())}
            for i, name in enumerate(names)}
