"""The ``[crack]`` scene table both crack study kinds own (the plane crack study and the
solid crack growth): its keys, checks and the ``CrackSweep`` it gives."""
from __future__ import annotations

import math
from dataclasses import replace

from hubvib.reducer.stages import ring_gear
from hubvib.foundation.bounds import upper_bound
from hubvib.foundation.errors import SceneError
from hubvib.foundation.schema import Field, Schema
from hubvib.meshing.crack import MIN_LIGAMENT, STARTS
from hubvib.meshing.crack_kinds import start_kind
from hubvib.meshing.gear import GearGeometryError
from hubvib.cases.sweep import ACCURACY, APPLY, MAX_DEPTHS, MODELS, CrackSweep, crack_of


def _finite_list(v) -> bool:
    return isinstance(v, list) and bool(v) and all(
        isinstance(d, (int, float)) and not isinstance(d, bool) and math.isfinite(d) for d in v)


def _half_lengths_ok(v) -> bool:
    return (isinstance(v, list) and 1 <= len(v) <= MAX_HALF_LENGTHS and all(
        isinstance(c, (int, float)) and not isinstance(c, bool) and math.isfinite(c) and c > 0
        for c in v) and all(b > a for a, b in zip(v[:-1], v[1:])))


#: the words ``[crack] path`` takes besides an angle [deg]
PATH_WORDS = ("predicted", "radial")
#: at most this many half-lengths in a solid sweep
MAX_HALF_LENGTHS = 8
_INTEGERS = "{label} = {value}; allowed {allowed}"
_MOUNT = "a finite stiffness > 0 [N/m]"
#: the ``[crack]`` keys, each filling the ``CrackSweep`` attribute of its name (``attr``); a
#: new key = one entry here (and its attribute)
SCHEMA = Schema("crack", (
    Field("depths", "numbers", default=[0.0], unit="m", check=_finite_list,
          allowed="a non-empty list of numbers [m]",
          message="{label} = {value}, but it must be {allowed}",
          doc=f"along the crack path, ascending, from 0 (intact); at most {MAX_DEPTHS}"),
    Field("start", "choice", choices=STARTS, default="root", doc="where the crack starts"),
    Field("apply", "choice", choices=APPLY, default="series",
          doc="series: mounting in series with the FE ring body; ratio: FE ratio on the "
              "reducer's c_ru, c_r (the preset's or design's table, or [reducer.parameters]; "
              "an upper bound); direct: FE values alone"),
    Field("accuracy", "choice", choices=tuple(ACCURACY), default="default",
          doc="fast: element sizes doubled"),
    Field("tooth", "integer", 0, math.inf, default=0, unit="-", allowed="integers 0..",
          message=_INTEGERS, doc="the cracked ring tooth (below the ring's tooth count)"),
    Field("workers", "integer", 1, 64, default=2, unit="-", allowed="integers 1..64",
          message=_INTEGERS, doc="worker processes for the FE cases"),
    Field("angle_deg", "number", -90.0, 60.0, default=0.0, unit="deg", attr="angle",
          scale=math.pi / 180, allowed="-90..60 for start = 'root' (-60..60 for 'rim')",
          message=_INTEGERS, doc="crack direction from the radial (as path = <deg>)"),
    # checked with the start in ``_path`` (its range depends on the start kind)
    Field("path", "string", default="radial", unit="-", check=lambda v: True,
          allowed='"predicted", "radial" or an angle [deg] (as angle_deg)',
          doc='"radial": straight (at angle_deg); "predicted": the LEFM path of '
              "`hubvib crack-path`, the depths as lengths along it"),
    Field("through_rim", "bool", default=False,
          message="{label} = {value}, but it must be {allowed}",
          doc="also the depth that cuts through the rim"),
    Field("c_ru_mount", "number", 0.0, math.inf, True, True, default=None, unit="N/m",
          allowed=_MOUNT, doc='with apply = "series"; absent: identified so that the intact '
                              "total equals the reducer's c_ru"),
    Field("c_r_mount", "number", 0.0, math.inf, True, True, default=None, unit="N/m",
          allowed=_MOUNT, doc="... and c_r"),
    Field("model", "choice", choices=MODELS, default="plane",
          doc="plane, or solid: semi-elliptic root cracks in the solid ring"),
    Field("substructure", "bool", default=True,
          message="{label} = {value}, but it must be {allowed}",
          doc="plane: only the crack's block meshed and factorised per case, the intact "
              "pieces condensed once; false: the whole ring per case"),
    Field("half_lengths", "numbers", default=None, unit="m", check=_half_lengths_ok,
          allowed=f'1..{MAX_HALF_LENGTHS} ascending values > 0 [m] with model = "solid"',
          doc="solid only: one case per depth > 0 and half-length"),
))


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
    SCHEMA.check_keys(table)
    depths = table.get("depths", [0.0])
    if isinstance(depths, list) and len(depths) > MAX_DEPTHS:
        raise SceneError(f"[crack] depths: {len(depths)} values; allowed at most {MAX_DEPTHS}")
    values = SCHEMA.parse(table, defaults=True)
    if depths[0] != 0 or any(b <= a for a, b in zip(depths[:-1], depths[1:])):
        raise SceneError(f"[crack] depths = {depths!r}: allowed ascending values from 0 "
                         "(the intact ring) [m]")
    for key in ("c_ru_mount", "c_r_mount"):
        if values[key] is not None and values["apply"] != "series":
            raise SceneError(f"[crack] {key} is given, but it applies only with apply = "
                             f"\"series\" (apply = {values['apply']!r})")
    through = values.pop("through_rim")
    values["half_lengths"] = _half_lengths(values, through)
    angle, values["path"] = _path(table, values["start"])
    values["angle"] = math.radians(angle)
    sweep = CrackSweep(**values, design=design)
    if sweep.path == "predicted" and (sweep.start != "root" or through
                                      or sweep.model != "plane"):
        raise SceneError(f"[crack] path = \"predicted\" follows the LEFM path of a root crack "
                         f"in the plane model to where it severs the tooth or rim: allowed "
                         f"start = \"root\" (got {sweep.start!r}), through_rim = false (got "
                         f"{str(through).lower()}) and model = \"plane\" (got {sweep.model!r})")
    return _checked_depths(sweep, through)


def _angle_range(start: str) -> tuple[float, float]:
    """The directions [deg] a crack from ``start`` may take."""
    # rounded: math.degrees(math.radians(60)) is 59.99999999999999, which refused 60 itself
    return tuple(round(math.degrees(a), 9) for a in start_kind(start).angle_range)


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


#: allowed depth / half-length of a semi-elliptic crack (the shipped scene: 0.19..2.25)
ASPECT_RATIOS = (0.125, 3.0)


def _half_lengths(values: dict, through: bool) -> tuple[float, ...]:
    """``[crack] half_lengths`` [m] of a solid sweep, checked against the model and start
    (the face width is checked with the depths)."""
    model, start, half_lengths = values["model"], values["start"], values["half_lengths"]
    if model == "plane":
        if half_lengths is not None:
            raise SceneError("[crack] half_lengths applies only with model = \"solid\" "
                             "(a plane crack runs through the face width)")
        return ()
    if start != "root" or through:
        raise SceneError(f"[crack] model = \"solid\" grows semi-elliptic root cracks inside "
                         f"the rim: allowed start = \"root\" (got {start!r}) and through_rim "
                         f"= false (got {str(through).lower()})")
    if half_lengths is None:
        raise SCHEMA.refuse(SCHEMA.by_key["half_lengths"], None)
    return half_lengths


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
    for i, depth in enumerate(depths):
        try:
            crack_of(sweep, depth).path(ring)
        except GearGeometryError as exc:
            raise SceneError(f"[crack] depths[{i}]: {exc}") from None
        if sweep.model == "solid" and crack_of(sweep, depth).is_through(ring):
            through = crack_of(sweep, 0.0).through_depth(ring)
            raise SceneError(f"[crack] depths[{i}] = {depth!r} m: a semi-elliptic crack must "
                             "stay inside the rim, allowed "
                             f"0..{upper_bound(through, strict=True)} "
                             "m (exclusive)")
    return replace(sweep, depths=tuple(depths))
