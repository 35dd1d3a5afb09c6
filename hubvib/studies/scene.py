"""Scene files: what to compute, validated on load.

A scene is TOML with these tables (all keys shown; SI units)::

    [reducer]
    preset = "raba118"            # a shipped design: raba118, hub4
    [design]                      # optional, instead of the preset: a design table
    file = "my_reducer.toml"      # (the keys of a design file, see hubvib.design.parse),
                                  # or file = a design file (relative to the scene),
                                  # or preset = "hub4"
    [reducer.parameters]          # optional overrides, keys as for --set
    c_ru = 1e6

    [study]
    parameter = "c_ru"            # a stiffness or mass field of PlanetaryParameters
    values = [1e6, 5e5, 1e5]      # modified values; the first is not the baseline
    detection_threshold_percent = 1.0
    method = "jacobi"             # eigensolver, see lumped.METHODS

    [crack]                       # optional: a ring-crack sweep through the FE stage
    depths = [0.0, 0.005, 0.01]   # [m] along the crack path, ascending, from 0 (intact)
    through_rim = true            # also the depth that cuts through the rim
    tooth = 0
    start = "root"                # or "rim"
    angle_deg = 0.0               # from the radial, |angle| <= 60
    apply = "series"              # mounting in series with the FE ring body (default);
                                  # "ratio": FE ratio on the preset's c_ru, c_r (the paper's
                                  # hypothesis, an upper bound); "direct": FE values alone
    c_ru_mount = 1e6              # [N/m] with "series"; absent: identified so that the
    c_r_mount = 1e8               # intact total equals the preset's c_ru / c_r
    accuracy = "default"          # or "fast" (element sizes doubled)
    workers = 2                   # worker processes for the FE cases
    model = "plane"               # or "solid": semi-elliptic root cracks in the solid ring,
    half_lengths = [0.004, 0.008] # [m] one case per depth > 0 and half-length (solid only;
                                  # depth / half_length 0.125..3); accuracy then applies to
                                  # the plane cases of the same depths that give c_rp

    [detection]                   # optional, crack scenes: record length, scatter, POD
                                  # (every key: hubvib/detection/options.py)
    [signal]                      # optional: the vibration signature (hubvib/signal/options.py)
    [execution]                   # optional: local pool or Dask (hubvib/engines.py)

    [output]
    folder = "hubvib-out"         # relative to the current directory
    plots = true
    renders = false               # pyvista PNG of each lumped mode shape and of the FE
                                  # ring: loaded (von Mises), crack tip, lowest modes
    gif = false                   # ... and an animated GIF per lumped mode
    vtm = false                   # ... and VTK files for ParaView: a multiblock per
                                  # lumped mode, the FE ring's fields as .vtu

With ``[crack]`` the study is the crack sweep and ``[study]`` needs no
``parameter``/``values``.
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field, replace
from importlib import resources
from pathlib import Path

from hubvib.build import load_design, parse_design
from hubvib.build.stages import derived_lumped_fields, ring_gear
from hubvib.design import DesignError, PRESETS, preset_design
from hubvib.detection.options import parse_detection_table
from hubvib.foundation.errors import SceneError
from hubvib.lumped import METHODS, ParameterError, PlanetaryParameters, field_names
from hubvib.meshing.crack import STARTS
from hubvib.meshing.gear import GearGeometryError
from hubvib.runtime.engines import parse_execution_table
from hubvib.runtime.params_input import load_parameters, read_text_file
from hubvib.signal.options import parse_signal_table
from hubvib.studies.crack_sweep import ACCURACY, APPLY, CrackSweep, MAX_DEPTHS, MODELS, crack_of

PARAMETER_NAMES = field_names()

#: optional tables parsed by the module that uses them: table -> parser.  The parser
#: takes the table (a dict) and returns a frozen options object, raising SceneError that
#: names the key and the allowed range; the object is in ``Scene.tables[name]``.  A new
#: table = its parser + one line here.
EXTENSION_TABLES = {
    "signal": parse_signal_table,
    "detection": parse_detection_table,
    "execution": parse_execution_table,
}

ALLOWED = {
    "": {"reducer", "design", "study", "crack", "output", *EXTENSION_TABLES},
    "reducer": {"preset", "parameters"},
    "study": {"parameter", "values", "detection_threshold_percent", "method"},
    "crack": {"depths", "through_rim", "tooth", "start", "angle_deg", "apply", "accuracy",
              "workers", "c_ru_mount", "c_r_mount", "model", "half_lengths"},
    "output": {"folder", "plots", "renders", "gif", "vtm"},
}


@dataclass(frozen=True)
class Scene:
    name: str
    params: PlanetaryParameters
    parameter: str
    values: tuple[float, ...]
    threshold_percent: float
    method: str
    folder: Path
    plots: bool
    source: dict = field(repr=False, compare=False, default_factory=dict)
    crack: CrackSweep | None = None
    renders: bool = False
    gif: bool = False
    vtm: bool = False
    design: object = None
    tables: dict = field(default_factory=dict, compare=False)

    @property
    def c_rp_given(self) -> bool:
        """Whether the lumped c_rp is a given value: a ``[reducer]`` preset's table, a
        design's ``lumped.c_rp`` or a ``[reducer.parameters]`` override.  Otherwise (a
        design-derived c_rp, ISO 6336-1 by default) a crack study uses the FE intact c_rp."""
        if "design" not in self.source or self.design is None:
            return True
        overrides = self.source.get("reducer", {}).get("parameters", {})
        return "c_rp" in self.design.lumped_fields or "c_rp" in overrides

    @property
    def kind(self) -> str:
        """The study this scene runs (``hubvib.studies.kinds.STUDIES``): "sweep" (no
        [crack] table), "crack" ([crack] model = "plane") or "growth" (model = "solid")."""
        if self.crack is None:
            return "sweep"
        return "growth" if self.crack.model == "solid" else "crack"


#: the shipped scene ``hubvib run`` runs without an argument
DEFAULT_SCENE = "raba118_crack"


def shipped_scenes() -> dict[str, str]:
    """Every shipped scene: name -> its first comment line (what it studies)."""
    out = {}
    for entry in sorted(resources.files("hubvib.scenes").iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            first = entry.read_text(encoding="utf-8").splitlines()[0]
            out[entry.name[:-5]] = first.lstrip("# ").strip()
    return out


def shipped_scene_text(name: str) -> str:
    """The text of a shipped scene."""
    if name not in shipped_scenes():
        raise SceneError(f"no scene file {name!r} and no shipped scene of that name; shipped: "
                         f"{', '.join(shipped_scenes())}")
    return resources.files("hubvib.scenes").joinpath(f"{name}.toml").read_text(encoding="utf-8")


def default_scene_text() -> str:
    """The embedded default scene (Raba 118/76 crack-sensitivity study)."""
    return shipped_scene_text(DEFAULT_SCENE)


def load_scene(path: Path | str | None = None) -> Scene:
    """Parse and validate a scene: a TOML file, a shipped scene's name, or ``None`` for
    the default."""
    if path is None:
        return parse_scene(default_scene_text(), DEFAULT_SCENE)
    path = Path(path)
    if not path.exists() and path.suffix != ".toml" and path.parent == Path("."):
        return parse_scene(shipped_scene_text(path.name), path.name)

    return parse_scene(read_text_file(path, "scene", SceneError), path.stem, path.parent)


def parse_scene(text: str, name: str, base: Path | None = None) -> Scene:
    """Parse and check a scene's text; ``base`` is the folder of relative paths in it."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"scene {name!r} is not valid TOML: {exc}") from None
    _check_keys(data, "")
    reducer = _table(data, "reducer")
    study = _table(data, "study")
    output = _table(data, "output")
    _check_keys(reducer, "reducer")
    _check_keys(study, "study")
    _check_keys(output, "output")

    overrides = reducer.get("parameters", {})
    if not isinstance(overrides, dict):
        raise SceneError(f"[reducer] parameters = {overrides!r}, but it must be a table")
    design = _design(data, reducer, base)
    try:
        if "design" in data:
            from hubvib.build.stages import lumped_parameters

            from hubvib.runtime.params_input import apply_overrides

            params = apply_overrides(lumped_parameters(design), overrides)
        else:
            params = load_parameters(_string(reducer, "reducer", "preset", "raba118"),
                                     overrides=overrides)
    except (ParameterError, ValueError) as exc:
        raise SceneError(f"[reducer]: {exc}") from None
    if "crack" in data or "design" in data:
        _check_consistent(design, params)

    crack = _crack(data["crack"], design) if "crack" in data else None
    if crack is not None and ("parameter" in study or "values" in study):
        raise SceneError("[study] parameter and values are for a lumped sweep; a scene with "
                         "[crack] sweeps the crack depth instead (remove them or the [crack] "
                         "table)")
    parameter = _string(study, "study", "parameter", "c_ru")
    numeric = [f for f in field_names() if f not in ("theta", "c_rp_factors")]
    if parameter not in numeric:
        raise SceneError(f"[study] parameter = {parameter!r}; allowed: {', '.join(numeric)}")
    values = study.get("values", [] if crack else None)
    if not isinstance(values, list) or (crack is None and not values) or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        raise SceneError(f"[study] values = {values!r}, but it must be a non-empty list of numbers")
    for i, v in enumerate(values):
        try:
            params.replace(**{parameter: float(v)})
        except ParameterError as exc:
            raise SceneError(f"[study] values[{i}]: {exc}") from None
    threshold = study.get("detection_threshold_percent", 1.0)
    if isinstance(threshold, bool) or not isinstance(threshold, (int, float)) or not (
        math.isfinite(threshold) and threshold > 0
    ):
        raise SceneError(
            f"[study] detection_threshold_percent = {threshold!r}, but it must be a number > 0"
        )
    method = _string(study, "study", "method", "jacobi")
    if method not in METHODS:
        raise SceneError(f"[study] method = {method!r}; allowed: {', '.join(METHODS)}")
    plots = output.get("plots", True)
    if not isinstance(plots, bool):
        raise SceneError(f"[output] plots = {plots!r}, but it must be true or false")
    flags = {}
    for key in ("renders", "gif", "vtm"):
        flags[key] = output.get(key, False)
        if not isinstance(flags[key], bool):
            raise SceneError(f"[output] {key} = {flags[key]!r}, but it must be true or false")
    if (flags["gif"] or flags["vtm"]) and not flags["renders"]:
        raise SceneError("[output] gif and vtm need renders = true")
    if flags["renders"] and crack is None:
        raise SceneError("[output] renders = true needs a [crack] study (it renders its modes)")
    folder = Path(_string(output, "output", "folder", "hubvib-out"))
    tables = {key: _extension(key, data[key]) for key in EXTENSION_TABLES if key in data}
    if "signal" in tables and crack is not None and crack.model == "solid":
        raise SceneError("[signal] needs a plane crack study: the tooth curves of the signal "
                         "are plane (remove [signal] or set [crack] model = \"plane\")")
    for table in tables.values():  # checks that need the design (e.g. its mesh frequency)
        if hasattr(table, "check_design"):
            table.check_design(design)
    return Scene(name, params, parameter, tuple(float(v) for v in values), float(threshold),
                 method, folder, plots, data, crack, **flags, design=design, tables=tables)


def _design(data, reducer, base: Path | None):
    """The scene's design: its [design] table, else the [reducer] preset's design."""
    preset = _string(reducer, "reducer", "preset", "raba118")
    try:
        if "design" not in data:
            return preset_design(preset) if preset in PRESETS else None
        if "preset" in reducer:
            raise SceneError("give either [reducer] preset or [design], not both")
        table = data["design"]
        if not isinstance(table, dict):
            raise SceneError(f"[design] must be a table, got {table!r}")
        if set(table) == {"file"}:
            path = Path(table["file"]) if isinstance(table["file"], str) else None
            if path is None:
                raise SceneError(f"[design] file = {table['file']!r}; allowed: a path (string)")
            return load_design(path if path.is_absolute() or base is None else base / path)
        if set(table) == {"preset"}:
            return preset_design(table["preset"])
        return parse_design(table, default_name="design")
    except DesignError as exc:
        raise SceneError(f"[design]: {exc}") from None


def _check_consistent(design, params) -> None:
    """Refuse lumped parameters that contradict the design (N, angles, diameters)."""
    if design is None:
        return
    n = len(params.theta)
    if n != design.n_planets:
        raise SceneError(f"[reducer.parameters] give {n} planets, but the design "
                         f"{design.name!r} has n_planets = {design.n_planets}")
    for i, (a, b) in enumerate(zip(params.theta, design.angles)):
        if abs(math.remainder(a - b, 2 * math.pi)) > 1e-9:
            raise SceneError(f"[reducer.parameters] planet {i + 1} at {math.degrees(a):.6g} deg, "
                             f"but the design {design.name!r} puts it at "
                             f"{math.degrees(b):.6g} deg")
    given = design.lumped_fields
    derived = derived_lumped_fields(design, skip=set(PARAMETER_NAMES) - set(GEOMETRIC))
    for key in GEOMETRIC:
        expected = given.get(key, derived.get(key))
        value = getattr(params, key)
        if expected is not None and abs(value - expected) > 1e-9 * abs(expected):
            raise SceneError(f"[reducer.parameters] {key} = {value:.9g}, but the design "
                             f"{design.name!r} gives {key} = {expected:.9g}")


#: lumped fields that follow from the design's geometry
GEOMETRIC = ("d_s", "d_c", "d_r", "d_p", "alpha_s", "alpha_r")


def _extension(key: str, table):
    if not isinstance(table, dict):
        raise SceneError(f"[{key}] must be a table, got {table!r}")
    return EXTENSION_TABLES[key](table)


def _crack(table, design) -> CrackSweep:
    if not isinstance(table, dict):
        raise SceneError(f"[crack] must be a table, got {table!r}")
    _check_keys(table, "crack")
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
    start = _string(table, "crack", "start", "root")
    if start not in STARTS:
        raise SceneError(f"[crack] start = {start!r}; allowed: {', '.join(STARTS)}")
    apply = _string(table, "crack", "apply", "series")
    if apply not in APPLY:
        raise SceneError(f"[crack] apply = {apply!r}; allowed: {', '.join(APPLY)}")
    accuracy = _string(table, "crack", "accuracy", "default")
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
    angle = table.get("angle_deg", 0.0)
    if isinstance(angle, bool) or not isinstance(angle, (int, float)) or not abs(angle) <= 60:
        raise SceneError(f"[crack] angle_deg = {angle!r}; allowed -60..60")
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
    model = _string(table, "crack", "model", "plane")
    if model not in MODELS:
        raise SceneError(f"[crack] model = {model!r}; allowed: {', '.join(MODELS)}")
    sweep = CrackSweep(tuple(float(d) for d in depths), integers["tooth"], start,
                       math.radians(angle), apply, accuracy, integers["workers"], **mounts,
                       design=design, model=model,
                       half_lengths=_half_lengths(table, model, start, through))
    return _checked_depths(sweep, through)


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
        from hubvib.meshing.crack import MIN_LIGAMENT

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
            raise SceneError(f"[crack] depths[{i}] = {depth!r} m: a semi-elliptic crack must "
                             f"stay inside the rim, allowed 0..{crack_of(sweep, 0.0).through_depth(ring):.6g} "
                             "m (exclusive)")
    return replace(sweep, depths=tuple(depths))


def _table(data, key):
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise SceneError(f"[{key}] must be a table, got {value!r}")
    return value


def _check_keys(table, where):
    unknown = set(table) - ALLOWED[where]
    if unknown:
        place = f"[{where}]" if where else "top level"
        raise SceneError(
            f"unknown key(s) {sorted(unknown)} at {place}; allowed: {sorted(ALLOWED[where])}"
        )


def _string(table, where, key, default):
    value = table.get(key, default)
    if not isinstance(value, str):
        raise SceneError(f"[{where}] {key} = {value!r}, but it must be a string")
    return value
