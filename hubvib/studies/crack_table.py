"""The ``[crack]`` scene table both crack study kinds own (the plane crack study and the
solid crack growth): its keys, checks and the ``CrackSweep`` it gives."""
from __future__ import annotations

import math
from dataclasses import replace

from hubvib.build.stages import ring_gear
from hubvib.foundation.errors import SceneError
from hubvib.meshing.crack import MIN_LIGAMENT, STARTS
from hubvib.meshing.crack_kinds import start_kind
from hubvib.meshing.gear import GearGeometryError
from hubvib.studies.crack_sweep import ACCURACY, APPLY, CrackSweep, MAX_DEPTHS, MODELS, crack_of
from hubvib.studies.study import check_keys, string_key

#: the keys of [crack]
KEYS = {"depths", "through_rim", "tooth", "start", "angle_deg", "apply", "accuracy", "workers",
        "c_ru_mount", "c_r_mount", "model", "half_lengths", "path"}
#: the words ``[crack] path`` takes besides an angle [deg]
PATH_WORDS = ("predicted", "radial")


def crack_model(data: dict) -> str:
    """The raw ``[crack] model`` of a scene's TOML (what selects plane or solid)."""
    table = data.get("crack")
    return table.get("model", "plane") if isinstance(table, dict) else "plane"


def refuse_sweep_keys(data: dict) -> None:
    """A crack scene sweeps the crack depth: ``[study] parameter/values`` are refused."""
    study = data.get("study", {})
    if "parameter" in study or "values" in study:
        raise SceneError("[study] parameter and values are for a lumped sweep; a scene with "
                         "[crack] sweeps the crack depth instead (remove them or the [crack] "
                         "table)")


def parse_crack_table(table, design) -> CrackSweep:
    """The ``[crack]`` table: the FE crack sweep on the design's ring, every depth checked
    against the ring (no meshing) and the through depth added when asked."""
    if not isinstance(table, dict):
        raise SceneError(f"[crack] must be a table, got {table!r}")
    check_keys(table, "crack", KEYS)
    depths = table.get("depths", [0.0])
    if isinstance(depths, list) and len(depths) > MAX_DEPTHS:
        raise SceneError(f"[crack] depths: {len(depths)} values; allowed at most {MAX_DEPTHS}")
    if not isinstance(depths, list) or not depths or not all(
            isinstance(d, (int, float)) and not isinstance(d, bool) and math.isfinite(d)
            for d in depths):
        raise SceneError(f"[crack] depths = {depths!r}, but it must be a non-empty list of "
                         "numbers [m]")
    if depths[0] != 0 or any(b <= a for a, b in zip(depths[:-1], depths[1:])):
        raise SceneError(f"[crack] depths = {depths!r}: allowed ascending values from 0 "
                         "(the intact ring) [m]")
    start = string_key(table, "crack", "start", "root")
    if start not in STARTS:
        raise SceneError(f"[crack] start = {start!r}; allowed: {', '.join(STARTS)}")
    apply = string_key(table, "crack", "apply", "series")
    if apply not in APPLY:
        raise SceneError(f"[crack] apply = {apply!r}; allowed: {', '.join(APPLY)}")
    accuracy = string_key(table, "crack", "accuracy", "default")
    if accuracy not in ACCURACY:
        raise SceneError(f"[crack] accuracy = {accuracy!r}; allowed: {', '.join(ACCURACY)}")
    integers = {}
    for key, default, low, high in (("tooth", 0, 0, None), ("workers", 2, 1, 64)):
        value = table.get(key, default)
        if isinstance(value, bool) or not isinstance(value, int) or value < low or (
                high is not None and value > high):
            raise SceneError(f"[crack] {key} = {value!r}; allowed integers {low}.."
                             f"{high if high is not None else ''}")
        integers[key] = value
    angle, path = _path(table, start)
    through = table.get("through_rim", False)
    if not isinstance(through, bool):
        raise SceneError(f"[crack] through_rim = {through!r}, but it must be true or false")
    mounts = {}
    for key in ("c_ru_mount", "c_r_mount"):
        value = table.get(key)
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))
                                  or not (math.isfinite(value) and value > 0)):
            raise SceneError(f"[crack] {key} = {value!r}; allowed: a finite stiffness > 0 [N/m]")
        if value is not None and apply != "series":
            raise SceneError(f"[crack] {key} is given, but it applies only with apply = "
                             f"\"series\" (apply = {apply!r})")
        mounts[key] = None if value is None else float(value)
    model = string_key(table, "crack", "model", "plane")
    if model not in MODELS:
        raise SceneError(f"[crack] model = {model!r}; allowed: {', '.join(MODELS)}")
    sweep = CrackSweep(tuple(float(d) for d in depths), integers["tooth"], start,
                       math.radians(angle), apply, accuracy, integers["workers"], **mounts,
                       design=design, model=model,
                       half_lengths=_half_lengths(table, model, start, through), path=path)
    if path == "predicted" and (start != "root" or through or model != "plane"):
        raise SceneError(f"[crack] path = \"predicted\" follows the LEFM path of a root crack "
                         f"in the plane model to where it severs the tooth or rim: allowed "
                         f"start = \"root\" (got {start!r}), through_rim = false (got "
                         f"{str(through).lower()}) and model = \"plane\" (got {model!r})")
    return _checked_depths(sweep, through)


def _angle_range(start: str) -> tuple[float, float]:
    """The directions [deg] a crack from ``start`` may take."""
    return tuple(math.degrees(a) for a in start_kind(start).angle_range)


def _path(table, start) -> tuple[float, str]:
    """``[crack] path`` and ``angle_deg``: the angle [deg] and the sweep's path kind.
    ``path = "radial"`` is a straight radial crack, a number a straight crack at that
    angle (as ``angle_deg``), ``"predicted"`` the LEFM path."""
    low, high = _angle_range(start)
    angle = table.get("angle_deg", 0.0)
    if isinstance(angle, bool) or not isinstance(angle, (int, float)) or not (
            low <= angle <= high):
        raise SceneError(f"[crack] angle_deg = {angle!r}; allowed {low:g}..{high:g} for "
                         f"start = {start!r}")
    if "path" not in table:
        return float(angle), "straight"
    path = table["path"]
    allowed = f"allowed: \"predicted\", \"radial\" or an angle {low:g}..{high:g} [deg]"
    if isinstance(path, str) and path not in PATH_WORDS or not isinstance(path, str) and (
            isinstance(path, bool) or not isinstance(path, (int, float))
            or not low <= path <= high):
        raise SceneError(f"[crack] path = {path!r}; {allowed} for start = {start!r}")
    direction = 0.0 if isinstance(path, str) else float(path)
    if "angle_deg" in table and angle != direction:
        raise SceneError(f"[crack] angle_deg = {angle!r} and path = {path!r} disagree: give "
                         "the angle as path = <degrees> or as angle_deg, not both")
    return direction, "predicted" if path == "predicted" else "straight"


#: at most this many half-lengths in a solid sweep
MAX_HALF_LENGTHS = 8
#: allowed depth / half-length of a semi-elliptic crack (the shipped scene: 0.19..2.25)
ASPECT_RATIOS = (0.125, 3.0)


def _half_lengths(table, model, start, through) -> tuple[float, ...]:
    """``[crack] half_lengths`` [m] of a solid sweep (the face width is checked with the
    depths)."""
    values = table.get("half_lengths")
    if model == "plane":
        if values is not None:
            raise SceneError("[crack] half_lengths applies only with model = \"solid\" "
                             "(a plane crack runs through the face width)")
        return ()
    if start != "root" or through:
        raise SceneError(f"[crack] model = \"solid\" grows semi-elliptic root cracks inside "
                         f"the rim: allowed start = \"root\" (got {start!r}) and through_rim "
                         f"= false (got {str(through).lower()})")
    if not isinstance(values, list) or not 1 <= len(values) <= MAX_HALF_LENGTHS or not all(
            isinstance(c, (int, float)) and not isinstance(c, bool) and math.isfinite(c)
            and c > 0 for c in values) or any(b <= a for a, b in zip(values[:-1], values[1:])):
        raise SceneError(f"[crack] half_lengths = {values!r}; allowed: 1..{MAX_HALF_LENGTHS} "
                         "ascending values > 0 [m] with model = \"solid\"")
    return tuple(float(c) for c in values)


def _checked_depths(sweep: CrackSweep, through: bool) -> CrackSweep:
    """Validate every depth against the design's ring (no meshing) and add the through depth."""
    if sweep.tooth >= sweep.reducer.ring.teeth:
        raise SceneError(f"[crack] tooth = {sweep.tooth}; allowed 0..{sweep.reducer.ring.teeth - 1} "
                         f"(the ring of {sweep.reducer.name!r} has {sweep.reducer.ring.teeth} teeth)")
    ring = ring_gear(sweep.reducer)
    depths = list(sweep.depths)
    if sweep.half_lengths:
        limit = sweep.reducer.face_width / 2 - MIN_LIGAMENT
        if sweep.half_lengths[-1] > limit:
            raise SceneError(f"[crack] half_lengths = {list(sweep.half_lengths)!r}; allowed "
                             f"values up to {limit:.6g} m (half the {sweep.reducer.face_width:g} "
                             f"m face width less {1e3 * MIN_LIGAMENT:g} mm)")
        if len(depths) < 2:
            raise SceneError("[crack] depths = [0.0]: model = \"solid\" needs a depth > 0")
        low, high = ASPECT_RATIOS
        for depth in depths[1:]:
            for half in sweep.half_lengths:
                if not low <= depth / half <= high:
                    raise SceneError(
                        f"[crack] depth {depth!r} m with half_length {half!r} m: allowed "
                        f"depth / half_length {low:g}..{high:g} (the front's ends curve with "
                        "radius depth^2 / half_length or half_length^2 / depth, which the "
                        "mesh must resolve)")
    if through and sweep.start == "root":
        try:
            limit = crack_of(sweep, 0.0).through_depth(ring)
        except GearGeometryError as exc:
            raise SceneError(f"[crack]: {exc}") from None
        if depths[-1] < limit:
            depths.append(limit)
    if sweep.path == "predicted":  # checked against the path when it is grown
        return replace(sweep, depths=tuple(depths))
    for i, depth in enumerate(depths):
        try:
            crack_of(sweep, depth).path(ring)
        except GearGeometryError as exc:
            raise SceneError(f"[crack] depths[{i}]: {exc}") from None
        if sweep.model == "solid" and crack_of(sweep, depth).is_through(ring):
            raise SceneError(f"[crack] depths[{i}] = {depth!r} m: a semi-elliptic crack must "
                             f"stay inside the rim, allowed 0..{crack_of(sweep, 0.0).through_depth(ring):.6g} "
                             "m (exclusive)")
    return replace(sweep, depths=tuple(depths))
