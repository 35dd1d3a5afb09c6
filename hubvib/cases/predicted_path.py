"""The LEFM crack path a crack sweep follows with ``[crack] path = "predicted"`` (SI).

The path is ``hubvib crack-path``'s (``cases.path_growth.grow_path``: grown from a
radial root crack at the sweep's tooth by the MTS criterion under the planet's mesh
force) with its step refined to the sweep's depths: the largest of 0.5 mm / k
(k = 1 .. 10) of which every depth is a whole multiple, so that the crack at each depth
is a crack the growth analysed (else 0.5 mm, and the depth ends inside a segment).  It
is computed once per design, tooth and step, and cached like an FE case
(``hubvib.runtime.fe_cache``, keyed on the source of every hubvib module this one
imports too, ``cases.path_growth`` and the builders of ``hubvib.reducer`` among them).
The crack at depth d is the path's polyline up to arc length d (``truncated``).
"""
from __future__ import annotations

import functools
import json
import sys

import numpy as np

from hubvib.fem.crack_propagation import GrowthOptions
from hubvib.foundation.bounds import upper_bound
from hubvib.meshing.cache import root_folder
from hubvib.meshing.polyline_crack import PathCrack
from hubvib.runtime.fe_cache import CacheEntryError, entry_key, read_entry, write_entry

#: the crack-path command's default step [m]; a sweep refines it to 0.5 mm / k
BASE_STEP = 0.5e-3
MAX_REFINE = 10


class PathDepthError(ValueError):
    """A sweep depth beyond the end of the predicted path; the message names the key."""


def refined_step(depths) -> float:
    """The growth step [m] for ``depths`` [m]: the largest ``BASE_STEP / k``, k <= 10, of
    which every depth is a whole multiple (1e-9 relative), else ``BASE_STEP``."""
    for k in range(1, MAX_REFINE + 1):
        step = BASE_STEP / k
        ratios = np.asarray(depths, float) / step
        if np.all(np.abs(ratios - np.round(ratios)) < 1e-6):
            return step
    return BASE_STEP


def arc_lengths(points) -> np.ndarray:
    """Arc length [m] at each point of a polyline (n, 2), 0 at the first."""
    return np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(np.asarray(points), axis=0).T))])


def truncated(points, depth: float, tooth: int) -> PathCrack:
    """The crack along ``points`` [m] (mouth first) up to arc length ``depth`` [m]: every
    vertex before it, then the point at ``depth`` (a vertex within 1e-9 m is taken as
    is)."""
    points = np.asarray(points, float)
    s = arc_lengths(points)
    if not 0 < depth <= s[-1] + 1e-9:
        raise PathDepthError(f"depth {depth!r} m: allowed 0..{upper_bound(s[-1])} m along the "
                             "path")
    end = int(np.searchsorted(s, depth - 1e-9))
    if abs(s[end] - depth) <= 1e-9:
        return PathCrack(tooth, tuple(map(tuple, points[:end + 1].tolist())))
    a, b = points[end - 1], points[end]
    tip = a + (depth - s[end - 1]) / (s[end] - s[end - 1]) * (b - a)
    return PathCrack(tooth, tuple(map(tuple, np.vstack([points[:end], tip]).tolist())))


#: the entry module of the cached path (it imports ``cases.path_growth``, the growth):
#: its source key
SOURCE = (__name__,)


def path_inputs(design, tooth: int, step: float) -> dict:
    return {"design": design.fingerprint(), "tooth": int(tooth), "step_m": float(step),
            "quantities": "predicted crack path (crack-path, default mesh)"}


def _check(result: dict) -> None:
    path = np.asarray(result.get("path_m", []), float)
    if path.ndim != 2 or path.shape[1:] != (2,) or len(path) < 2 or not np.all(
            np.isfinite(path)):
        raise CacheEntryError("path_m is not a list of >= 2 finite [x, y] points")
    if result.get("fracture") not in ("tooth", "rim"):
        raise CacheEntryError(f"fracture = {result.get('fracture')!r}")


@functools.lru_cache(maxsize=16)
def _predicted(design, tooth: int, step: float) -> dict:
    from hubvib.cases.path_growth import grow_path

    inputs = path_inputs(design, tooth, step)
    path = root_folder() / "crack-path" / f"{entry_key(inputs, modules=SOURCE)}.json"
    try:
        return read_entry(path, inputs, _check, modules=SOURCE)
    except CacheEntryError as exc:
        if str(exc) != "missing":
            print(f"hubvib: cache entry {path.name} for the predicted crack path: {exc}; "
                  "recomputing", file=sys.stderr)
    grown = grow_path(design, GrowthOptions(step=step, initial_depth=step,
                                           max_steps=int(round(40 * BASE_STEP / step))),
                      tooth=tooth)
    result = json.loads(json.dumps({k: v for k, v in grown.to_dict().items() if k != "files"}))
    # the cracks the growth analysed (the exit point, if severed, is not meshable)
    result["path_m"] = grown.growth.crack.array.tolist()
    path.parent.mkdir(parents=True, exist_ok=True)
    write_entry(path, inputs, result, modules=SOURCE)
    return result


def predicted_path(design, tooth: int, depths) -> dict:
    """The crack-path result (``CrackPathResult.to_dict`` keys; ``path_m`` the analysed
    cracks' polyline [m]) for ``design`` at ``tooth``, step refined to ``depths``."""
    return _predicted(design, int(tooth), refined_step(depths))


def predicted_crack(design, tooth: int, depths, depth: float) -> PathCrack:
    """The crack at ``depth`` [m] along the predicted path of the sweep over ``depths``;
    ``PathDepthError`` names ``[crack] depths`` if the path severs before it."""
    result = predicted_path(design, tooth, depths)
    length = float(arc_lengths(result["path_m"])[-1])
    if depth > length + 1e-9:
        raise PathDepthError(
            f"[crack] depths: {depth:.6g} m is beyond the predicted path, which "
            f"{'severs the ' + result['fracture'] if result['severed'] else 'ends'} after "
            f"{length:.6g} m (the last crack the growth meshed): allowed "
            f"0..{upper_bound(length)} m "
            f"with path = \"predicted\"")
    return truncated(result["path_m"], depth, tooth)
