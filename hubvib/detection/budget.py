"""Memory and work of the POD Monte Carlo and the detectability map, before they run (SI).

The Monte Carlo (:mod:`.pod`, :mod:`.diagnosis`) draws ``samples`` reducers and
solves each at every crack depth, engaged and not: ``2 samples depths``
parameter points of the lumped model (one eigen-solve each).  The solves run in
chunks of at most ``CHUNK_POINTS`` points (:func:`chunked_frequencies`), so their
working arrays (the factors ``B``, ``B^T B``; :mod:`hubvib.lumped.batch`) do not
grow with ``samples``; what grows is what the statistics keep: the sampled
frequencies and shifts, arrays of shape (samples, depths, modes).

:func:`estimate` counts both from the array shapes, and :func:`check_scene` refuses
a scene whose POD Monte Carlo (``samples``) or one Monte Carlo of its
detectability map (``map_samples``, one mounting value at a time) would take more
than ``MEMORY_BUDGET`` when it is parsed, before any FE, naming the key, the
estimate and the largest value within the budget.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubvib.foundation.errors import SceneError
from hubvib.identification.law import KAPPA
from hubvib.lumped import natural_modes
from hubvib.lumped.network import spring_network
from hubvib.lumped.parameters import MASS_FIELDS, STIFFNESS_FIELDS

from .options import DetectionOptions
from .uncertainty import Samples, observed_frequencies

#: parameter points (samples x 2 engagement states x depths) solved at once [-]
CHUNK_POINTS = 4096
#: peak memory the POD Monte Carlo or one Monte Carlo of the map may take [bytes]
MEMORY_BUDGET = 2 * 2**30
#: one float64 [bytes]
_F8 = 8
#: (samples, depths, modes) arrays alive at the peak of the statistics of ``pod_study``:
#: the sampled frequencies, the shifts, the argument of the normal CDF and its scaled
#: copy, and scipy's ``norm.cdf`` working copies and result (measured: 7.3 with
#: tracemalloc, tests/detection/test_memory_bounds.py)
KEPT_ARRAYS = 7
#: float arrays over the identification band alive at the peak of the Cramer-Rao bound
#: (:func:`hubvib.identification.law.fisher_sigma_hz`: bins, ordinates, the shape, its
#: gradients and their temporaries)
BAND_ARRAYS = 19
#: record lengths [s] the POD is also given for (``pod.RECORD_LENGTHS``)
LONGEST_RECORD = 600.0
#: the smallest value of each key (its documented range, :mod:`.options`)
LOWEST = {"samples": 100, "map_samples": 20}
_DEFAULTS = DetectionOptions()


@dataclass(frozen=True)
class Estimate:
    """Peak memory [bytes] and work of one POD Monte Carlo.

    Attributes
    ----------
    array_bytes : int
        One (samples, depths, modes) float array [bytes].
    draw_bytes : int
        The drawn reducers (one array per scattered field, per Monte Carlo) [bytes].
    solve_bytes : int
        Working arrays of one chunk of eigen-solves (at most ``CHUNK_POINTS`` points)
        [bytes].
    band_bytes : int
        Working arrays of the Cramer-Rao bound of the highest mode over its
        identification band in the longest record [bytes] (does not grow with samples).
    solves : int
        Eigen-solves (parameter points) of the run [-].
    """

    array_bytes: int
    draw_bytes: int
    solve_bytes: int
    band_bytes: int
    solves: int

    @property
    def peak_bytes(self) -> int:
        """The largest of the three phases of ``pod_study``: the solves (the frequencies
        being filled and one chunk), the identification scatter (frequencies, shifts and
        the band) and the statistics (``KEPT_ARRAYS`` arrays)."""
        return self.draw_bytes + max(self.array_bytes + self.solve_bytes,
                                     2 * self.array_bytes + self.band_bytes,
                                     KEPT_ARRAYS * self.array_bytes)


def band_bytes(params, options=None, method: str = "jacobi") -> int:
    """Working memory [bytes] of the Cramer-Rao bound of the highest mode of ``params``:
    ``BAND_ARRAYS`` float arrays over its identification band ``f (1 +- KAPPA zeta)`` of
    a record of the longest length (the scene's or ``LONGEST_RECORD``), one bin per
    ``1/T`` [Hz]."""
    options = options if options is not None else _DEFAULTS
    highest = float(natural_modes(params, method).omega[-1]) / (2 * np.pi)
    longest = max(LONGEST_RECORD, options.record_length)
    bins = 2 * KAPPA * options.damping_ratio * highest * longest + 1
    return int(_F8 * BAND_ARRAYS * bins)


def estimate(params, depths: int, samples: int, model_baseline: bool = True,
             options=None, chunk_points: int | None = None, band: int | None = None
             ) -> Estimate:
    """Peak memory and work of ``pod_study`` from the array shapes.

    ``params`` (PlanetaryParameters) gives the modes ``n`` (its DOF) and the spring rows
    ``R``; ``depths`` counts the crack depths with the intact one; ``options``
    (DetectionOptions, default the documented defaults) the record length and damping
    of :func:`band_bytes` (``band``: that value, when known).  Per parameter point a
    chunk holds the stiffnesses and masses (R + 2 n), the factor ``B`` (R n), ``B^T B``
    (n^2), the stacked changes and the frequencies (3 n); per sample the Monte Carlo
    keeps the draws (one per scattered field, twice with the model baseline) and up to
    ``KEPT_ARRAYS`` arrays of (depths, n) values (:attr:`Estimate.peak_bytes`).
    """
    rows, n = spring_network(params).k.size, params.n_dof
    fields = len(MASS_FIELDS) + len(STIFFNESS_FIELDS) + params.n_planets + 5
    per_point = _F8 * (rows * n + n * n + rows + 5 * n + fields)
    draws = 2 if model_baseline else 1
    points = 2 * samples * depths + (2 * samples if model_baseline else 0)
    chunk = min(CHUNK_POINTS if chunk_points is None else chunk_points,
                2 * samples * depths)
    band = band_bytes(params, options) if band is None else band
    return Estimate(_F8 * samples * depths * n, _F8 * draws * fields * samples,
                    per_point * chunk, band, points)


def largest_samples(params, depths: int, model_baseline: bool, options=None,
                    budget: int = MEMORY_BUDGET) -> int:
    """The largest ``samples`` whose :func:`estimate` stays within ``budget`` [bytes]
    (0 when none does)."""
    band = band_bytes(params, options)

    def fits(count):
        return estimate(params, depths, count, model_baseline, band=band).peak_bytes <= budget

    if not fits(1):
        return 0
    low, high = 1, 2
    while fits(high):
        low, high = high, 2 * high
    while high - low > 1:  # fits(low), not fits(high)
        mid = (low + high) // 2
        low, high = (mid, high) if fits(mid) else (low, mid)
    return low


def check_scene(options, study, params, budget: int = MEMORY_BUDGET) -> None:
    """Refuse ``[detection]`` settings of ``options`` (DetectionOptions) whose Monte Carlo
    over ``study.depths`` would take more than ``budget`` [bytes]: ``record_length_s``
    when the identification band alone does, else ``samples`` / ``map_samples``."""
    depths = len(getattr(study, "depths", ()) or ())
    if options is None or depths < 1:
        return
    band = band_bytes(params, options)
    if band > budget:
        raise SceneError(
            f"[detection] record_length_s = {options.record_length:g}: the identification "
            f"scatter over the band of the highest mode would take about "
            f"{band / 2**30:.1f} GiB of memory (budget {budget / 2**30:g} GiB); allowed: a "
            f"number in (0, {_longest_record(params, options, budget):.4g}]")
    for key, baseline in (("samples", True), ("map_samples", False)):
        count = getattr(options, key)
        peak = estimate(params, depths, count, baseline, band=band).peak_bytes
        if peak > budget:
            largest = largest_samples(params, depths, baseline, options, budget)
            raise SceneError(
                f"[detection] {key} = {count}: the Monte Carlo over {depths} crack depths "
                f"would take about {peak / 2**30:.1f} GiB of memory (budget "
                f"{budget / 2**30:g} GiB); allowed: an integer in [{LOWEST[key]}, {largest}]")


def _longest_record(params, options, budget: int) -> float:
    """The longest record [s] whose band fits ``budget`` [bytes]."""
    highest = float(natural_modes(params).omega[-1]) / (2 * np.pi)
    return (budget / (_F8 * BAND_ARRAYS) - 1) / (2 * KAPPA * options.damping_ratio * highest)


def chunked_frequencies(model, samples: Samples, fraction: float, long_record: bool,
                        workers: int = 1, chunk_points: int | None = None) -> np.ndarray:
    """:func:`.uncertainty.observed_frequencies` solved at most ``chunk_points`` (default
    ``CHUNK_POINTS``) parameter points at a time, shape (samples, depths, modes) [Hz].
    Each point is solved on its own (stacked LAPACK), so the numbers do not depend on
    the chunk."""
    chunk_points = CHUNK_POINTS if chunk_points is None else chunk_points
    step = max(1, chunk_points // (2 * len(model.depths)))
    if samples.n <= step:
        return observed_frequencies(model, samples, fraction, long_record, workers)
    out = None
    for start in range(0, samples.n, step):
        part = _slice(samples, slice(start, start + step))
        values = observed_frequencies(model, part, fraction, long_record, workers)
        if out is None:
            out = np.empty((samples.n,) + values.shape[1:])
        out[start:start + part.n] = values
    return out


def _slice(samples: Samples, where: slice) -> Samples:
    return Samples({name: value[where] for name, value in samples.fields.items()},
                   samples.support_ru[where], samples.support_r[where], samples.z_ru[where],
                   samples.z_r[where], samples.z_rp[where])
