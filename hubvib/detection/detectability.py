"""Smallest detectable crack depth of every mode against the rigid ring's mounting
stiffness (the rigid ring's side of :mod:`.mounting_map`).

The mounting sits in series with the FE ring body (:mod:`.series`), so it
decides how much of a body softening reaches the lumped ``c_ru`` and ``c_r``.
The map sweeps the torsional mounting (``c_ru_mount``, radial one fixed at the
scene's) and the radial mounting (``c_r_mount``, torsional one fixed), log-spaced,
and runs the Monte Carlo POD (:mod:`.pod`) at each value: the smallest depth with
POD >= the required probability and a shift resolved by the FE, per mode.  Each
row also names the stiffness whose change carries the signal there.

A map of more than ``PROGRESS_SOLVES`` eigen-solves (:func:`.budget.estimate`) reports
one line per mounting value off a terminal, with the time left
(:func:`hubvib.runtime.progress.progress`).
"""
from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from hubvib.foundation.blas import blas_threads
from hubvib.runtime.progress import progress

from .budget import estimate
from .mode_names import rigid_label
from .pod import pod_study
from .series import DIRECT, SERIES

SWEPT = ("c_ru_mount", "c_r_mount")
#: eigen-solves of a map above which it reports its progress per mounting value [-]
PROGRESS_SOLVES = 1_000_000


@dataclass(frozen=True)
class DetectabilityMap:
    """Per swept mounting and value: smallest detectable depth and carrier per mode.

    Attributes
    ----------
    mounts : ndarray
        Mounting stiffnesses [N/m], log-spaced.
    fixed : dict
        Swept name -> the other mounting's value during that sweep [N/m] (``inf``: rigid).
    depth : dict
        Swept name -> ndarray (mounts, modes) [m], NaN where no depth of the sweep is
        detectable.
    carried_by : dict
        Swept name -> ndarray (mounts, modes) of ``"c_ru"``, ``"c_r"``, ``"c_rp"`` or
        ``"none"``: the stiffness whose change alone moves the mode most at the deepest
        crack (record-averaged), the same rule as the modes table's ``signal_in``.
    frequency_hz : ndarray
        Per swept name, the nominal intact frequencies [Hz], shape (mounts, modes).
    kind : tuple of str
    depths : tuple of float
        The sweep's depths [m], the first 0.
    """

    mounts: np.ndarray
    fixed: dict
    depth: dict
    carried_by: dict
    frequency_hz: dict
    kind: tuple
    depths: tuple = ()

    def rows(self) -> list[dict]:
        rows = []
        for swept in SWEPT:
            for m, mount in enumerate(self.mounts):
                for i, kind in enumerate(self.kind):
                    depth = self.depth[swept][m, i]
                    f = float(self.frequency_hz[swept][m, i])
                    rows.append({
                        "swept": swept, "mount_N_m": float(mount),
                        "other_mount_N_m": _finite(self.fixed[swept]),
                        "mode": i + 1, "mode_label": rigid_label(i, kind, f), "kind": kind,
                        "frequency_intact_hz": f,
                        "smallest_detectable_depth_mm": (None if math.isnan(depth)
                                                         else 1e3 * float(depth)),
                        "signal_in": str(self.carried_by[swept][m, i])})
        return rows

    def smallest(self, swept: str) -> np.ndarray:
        """Per mount value, the smallest detectable depth over all modes [m] (NaN: none)."""
        depth = self.depth[swept]
        return np.where(np.isnan(depth).all(axis=1), np.nan,
                        np.nanmin(np.where(np.isnan(depth), np.inf, depth), axis=1))


def _finite(value: float):
    return None if math.isinf(value) else float(value)


def series_base(model):
    """The scene's model as a series composition: ``"direct"`` is a rigid mounting,
    ``"ratio"`` the mounting that gives the preset's intact totals."""
    if model.apply == SERIES:
        return model
    if model.apply == DIRECT:
        return model.with_mounts(math.inf, math.inf)
    return model.with_mounts()


def detectability_map(model, options, timing, workers: int = 1) -> DetectabilityMap:
    """Sweep both mountings over ``options.mount_min .. mount_max`` (CrackModel ``model``).

    The mounting values are independent POD runs (each seeded by its index), run on
    ``workers`` threads at one BLAS thread (numpy releases the GIL in the bands and the
    eigen-solves); the numbers do not depend on ``workers``."""
    base = series_base(model)
    mounts = np.geomspace(options.mount_min, options.mount_max, options.mount_points)
    fixed = {"c_ru_mount": base.c_r_mount, "c_r_mount": base.c_ru_mount}
    solves = len(SWEPT) * mounts.size * estimate(base.params, len(base.depths),
                                                  options.map_samples, False).solves
    bar = (progress(len(SWEPT) * mounts.size, "detectability map", "mounting")
           if solves > PROGRESS_SOLVES else None)
    points = [(swept, m, float(mount)) for swept in SWEPT for m, mount in enumerate(mounts)]

    def point(item):
        swept, m, mount = item
        mounted = (base.with_mounts(mount, base.c_r_mount) if swept == "c_ru_mount"
                   else base.with_mounts(base.c_ru_mount, mount))
        result = pod_study(mounted, options, timing, samples=options.map_samples,
                           model_baseline=False, seed=options.seed + m, workers=1,
                           family_curves=False)
        return (result.kind, result.detectable_depth(), result.nominal.carried_by[-1],
                result.nominal.frequency_hz[0])

    def done(results):
        # the bar is advanced here, in the calling thread (its count is not thread-safe)
        for (swept, _, mount), result in zip(points, results):
            if bar is not None:
                bar.update(note=f"{swept} = {mount:.3g} N/m")
            yield result

    threads = max(1, min(int(workers), len(points)))
    # one BLAS thread for the whole map (set once here: the threads must not set and
    # restore the process-wide count under each other); the same digits as more threads
    with blas_threads(1):
        if threads == 1:
            results = list(done(map(point, points)))
        else:
            with ThreadPoolExecutor(threads) as pool:
                results = list(done(pool.map(point, points)))
    if bar is not None:
        bar.close()
    depth, carried, frequency = {}, {}, {}
    for swept in SWEPT:
        rows = [r for (name, _, _), r in zip(points, results) if name == swept]
        depth[swept] = np.array([r[1] for r in rows])
        carried[swept] = np.array([r[2] for r in rows])
        frequency[swept] = np.array([r[3] for r in rows])
    return DetectabilityMap(mounts, fixed, depth, carried, frequency, results[-1][0],
                            tuple(float(d) for d in base.depths))
