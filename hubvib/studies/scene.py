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
    angle_deg = 0.0               # from the radial: root -90..60, rim -60..60
    path = "radial"               # or "predicted" (the LEFM path of hubvib crack-path,
                                  # depths along it; root, plane, no through_rim) or an
                                  # angle [deg] (= angle_deg)
    apply = "series"              # mounting in series with the FE ring body (default);
                                  # "ratio": FE ratio on the reducer's c_ru, c_r (the paper's
                                  # hypothesis, an upper bound); "direct": FE values alone
    c_ru_mount = 1e6              # [N/m] with "series"; absent: identified so that the
    c_r_mount = 1e8               # intact total equals the reducer's c_ru / c_r
    accuracy = "default"          # or "fast" (element sizes doubled)
    workers = 2                   # worker processes for the FE cases
    model = "plane"               # or "solid": semi-elliptic root cracks in the solid ring,
    half_lengths = [0.004, 0.008] # [m] one case per depth > 0 and half-length (solid only;
                                  # depth / half_length 0.125..3); accuracy then applies to
                                  # the plane cases of the same depths that give c_rp

    [detection]                   # optional, crack scenes: record length, scatter, POD
                                  # (every key: hubvib/detection/options.py)
    [signal]                      # optional: the vibration signature (hubvib/signal/options.py)
    [execution]                   # optional: local pool or Dask (hubvib/runtime/engines.py)
    [elastic]                     # optional, plane crack scenes: ring = "rigid" (default),
                                  # "elastic" or "both" (hubvib/elastic/options.py)

    [output]
    folder = "hubvib-out"         # relative to the current directory
    plots = true
    renders = false               # pyvista PNG of each lumped mode shape and of the FE
                                  # ring: loaded (von Mises), crack tip, lowest modes
    gif = false                   # ... and an animated GIF per lumped mode
    vtm = false                   # ... and VTK files for ParaView: a multiblock per
                                  # lumped mode, the FE ring's fields as .vtu

Which study a scene runs is the one registered study kind its tables select
(``hubvib.studies.kind_registry.select_study``): no study table, the lumped sweep of ``[study]``
``parameter``/``values``; ``[crack]``, the plane crack study (model = "plane") or the solid
crack growth (model = "solid"), and ``[study]`` needs no ``parameter``/``values``.  Each
kind parses its own tables (``Scene.study``); this module checks the common ones.
"""
from __future__ import annotations

import math
import tomllib
from importlib import resources
from pathlib import Path

from hubvib.reducer import load_design, parse_design
from hubvib.reducer.consistency import check_consistent
from hubvib.reducer.stages import lumped_parameters
from hubvib.design import DesignError, PRESETS, preset_design
from hubvib.detection.budget import check_scene as check_detection_budget
from hubvib.foundation.errors import SceneError
from hubvib.foundation.schema import Field, Schema
from hubvib.lumped import METHODS, ParameterError, field_names
from hubvib.runtime.params_input import apply_overrides, load_parameters, read_text_file
from hubvib.studies.kinds import STUDIES
from hubvib.studies.kind_registry import Scene, check_keys, select_study, study_tables
from hubvib.studies.sections import SECTIONS

__all__ = ["DEFAULT_SCENE", "Scene", "SceneError", "STUDIES", "default_scene_text",
           "load_scene", "parse_scene", "shipped_scene_text", "shipped_scenes"]

PARAMETER_NAMES = field_names()

#: optional tables parsed by the module that uses them (``hubvib.studies.sections``):
#: table -> parser; the parsed object is ``Scene.section(name)``
EXTENSION_TABLES = {name: section.parse for name, section in SECTIONS.items()}

#: the common tables (each study kind checks its own tables); a new key = one entry
_BUT = "{label} = {value}, but it must be {allowed}"
REDUCER = Schema("reducer", (
    Field("preset", "string", default="raba118",
          doc="a shipped design: " + ", ".join(PRESETS)),
    Field("parameters", "table", default=None,
          doc="lumped parameter overrides, keys as for --set"),
), message=_BUT)
STUDY = Schema("study", (
    Field("parameter", "string", default="c_ru",
          doc="lumped sweep: a stiffness or mass field of PlanetaryParameters"),
    Field("values", "numbers", default=None, allowed="a non-empty list of numbers",
          check=lambda v: isinstance(v, list) and bool(v) and all(
              isinstance(x, (int, float)) and not isinstance(x, bool) for x in v),
          doc="lumped sweep: modified values (SI); the first is not the baseline"),
    Field("detection_threshold_percent", "number", 0.0, math.inf, True, True, default=1.0,
          unit="%", doc="frequency shift that counts as detectable", allowed="a number > 0"),
    Field("method", "choice", choices=tuple(METHODS), default="jacobi",
          doc="eigensolver, see lumped.METHODS", message="{label} = {value}; allowed: {allowed}"),
), message=_BUT)
OUTPUT = Schema("output", (
    Field("plots", "bool", default=True, doc="PNG figures"),
    Field("renders", "bool", default=False,
          doc="pyvista PNG of each lumped mode shape and of the FE ring (crack studies)"),
    Field("gif", "bool", default=False, doc="... and an animated GIF per lumped mode"),
    Field("vtm", "bool", default=False, doc="... and VTK files for ParaView"),
    Field("folder", "string", default="hubvib-out", doc="relative to the current directory"),
), message=_BUT)
#: the tables every scene may hold besides its study kind's
TOP_LEVEL = {"reducer", "design", "study", "output", *EXTENSION_TABLES}


#: the shipped scene ``hubvib run`` runs without an argument
DEFAULT_SCENE = "raba118_crack"


def shipped_scenes() -> dict[str, str]:
    """Every shipped scene: name -> what it studies, its leading comment lines up to the
    first that ends a sentence (``.`` or ``)``), joined into one line (the first line
    alone cut sentences in two)."""
    out = {}
    for entry in sorted(resources.files("hubvib.scenes").iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            lines = []
            for line in entry.read_text(encoding="utf-8").splitlines():
                if not line.startswith("#"):
                    break
                lines.append(line.lstrip("# ").strip())
                if lines[-1].endswith((".", ")")):
                    break
            out[entry.name[:-5]] = " ".join(part for part in lines if part)
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
    """Parse and check a scene's text; ``base`` is the folder of relative paths in it.

    The common tables are checked here; the registry says which study kind the scene's
    tables select (``hubvib.studies.kind_registry.select_study``) and that kind parses its own."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"scene {name!r} is not valid TOML: {exc}") from None
    _refuse_design_file(data, name if base is None else str(base / f"{name}.toml"))
    check_keys(data, "", TOP_LEVEL | study_tables())
    reducer = _table(data, "reducer")
    study = _table(data, "study")
    output = _table(data, "output")
    for schema, table in ((REDUCER, reducer), (STUDY, study), (OUTPUT, output)):
        schema.check_keys(table)
    kind = select_study(data)

    overrides = REDUCER.value(reducer, "parameters") or {}
    design = _design(data, reducer, base)
    try:
        if "design" in data:
            params = apply_overrides(lumped_parameters(design), overrides)
        else:
            params = load_parameters(REDUCER.value(reducer, "preset"),
                                     overrides=overrides)
    except (ParameterError, ValueError) as exc:
        raise SceneError(f"[reducer]: {exc}") from None
    if kind.fe or "design" in data:
        check_consistent(design, params, "[reducer.parameters]", SceneError)

    options = kind.parse(data, design, params)
    threshold = STUDY.value(study, "detection_threshold_percent")
    method = STUDY.value(study, "method")
    out = OUTPUT.parse(output, defaults=True)
    plots = out.pop("plots")
    folder = Path(out.pop("folder"))
    flags = out
    if (flags["gif"] or flags["vtm"]) and not flags["renders"]:
        raise SceneError("[output] gif and vtm need renders = true")
    if flags["renders"] and not kind.renders:
        raise SceneError("[output] renders = true needs a [crack] study (it renders its modes)")
    tables = {key: _extension(key, data[key]) for key in EXTENSION_TABLES if key in data}
    for table in tables.values():  # checks that need the design (e.g. its mesh frequency)
        if hasattr(table, "check_design"):
            table.check_design(design)
    scene = Scene(name, params, threshold, method, folder, plots, kind.kind, options,
                  data, **flags, design=design, tables=tables)
    # memory of the Monte Carlo of a given [detection] table, from the study's depths,
    # before any FE
    check_detection_budget(scene.given("detection"), options, params)
    return scene


def _refuse_design_file(data: dict, where: str) -> None:
    """A design file given where a scene belongs (one ``[design]`` table of design keys and
    nothing to compute) is named as such, with the two ways to use it."""
    table = data.get("design")
    if set(data) == {"design"} and isinstance(table, dict) and not set(table) <= {"file",
                                                                                   "preset"}:
        raise SceneError(
            f"{where!r} is a design file (one [design] table), not a scene: check it with "
            f"`hubvib design check {where}`, or run a study of it from a scene that names "
            f"it, [design] file = \"{Path(where).name}\" beside a [crack] or [study] table "
            "(docs/design.md)")


def _design(data, reducer, base: Path | None):
    """The scene's design: its [design] table, else the [reducer] preset's design."""
    preset = REDUCER.value(reducer, "preset")
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


def _extension(key: str, table):
    if not isinstance(table, dict):
        raise SceneError(f"[{key}] must be a table, got {table!r}")
    return EXTENSION_TABLES[key](table)


def _table(data, key):
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise SceneError(f"[{key}] must be a table, got {value!r}")
    return value
