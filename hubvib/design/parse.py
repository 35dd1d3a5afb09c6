"""Design files (TOML) into a ``ReducerDesign``, every key checked before any work.

The ``[design]`` table (SI units; ``_deg`` keys in degrees)::

    [design]
    name = "demo"                  # optional, default: the file's stem
    n_planets = 3                  # 1..12
    planet_angles_deg = [0, 120, 240]   # optional; default equally spaced from 0
    module = 2.5e-3                # [m], (0, 0.05]
    pressure_angle_deg = 20.0      # optional, 10..35, default 20
    face_width = 0.030             # [m], (0, 1]
    sun = { teeth = 20, shift = 0.2, bore = 0.02 }      # shift -2..2 (default 0);
    planet = { teeth = 31, shift = 0.2, bore = 0.03 }   # bore [m] optional: 0.4 x root dia.
    ring = { teeth = 82, shift = 0.6, rim_thickness = 0.012 }  # or mass = 4.0 [kg]
    supports = { count = 6, arc_deg = 20.0, first_deg = 0.0 }  # optional; count 0 = all
    material = { E = 210e9, nu = 0.3, density = 7850.0 }      # optional, steel
    load = { sun_torque = 500.0 }  # [N m], optional, default 1000
    [design.bearings]              # optional: c_p, c_c by Palmgren line contact
    planet = { rollers = 16, roller_length = 0.03 }          # load: from the sun torque
    carrier = { rollers = 40, roller_length = 0.02, load = 25e3 }   # load [N] required
    [design.lumped]                # optional: lumped fields the geometry does not give
    c_ru = 1e6                     # [N/m] ring mounting, torsional (reduced)
    c_r = 1e8                      # [N/m] ring mounting, radial
    c_su = 1e6                     # [N/m] sun shaft; c_cu: carrier shaft
    c_cu = 1e6
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

from hubvib.foundation.files import read_text
from hubvib.foundation.schema import REQUIRED, Field, Schema

from .fields import DIAMETER_FIELDS, MASS_FIELDS, STIFFNESS_FIELDS
from .model import (BearingSpec, DesignError, GearSpec, MaterialSpec, ReducerDesign, RimSpec,
                    SupportSpec)

MAX_FILE_BYTES = 1_000_000
_DEG = math.pi / 180
_STEEL = MaterialSpec()


def _schema(table: str, *fields: Field) -> Schema:
    """A design table's schema: keys named ``design.table.key``, the design's messages."""
    return Schema(table, fields, error=DesignError, label="{table}.{key}",
                  unknown="unknown key(s) {labels}; allowed: {names}")


def _number(key, low, high, default=REQUIRED, open_low=False, unit="", doc="", scale=1.0):
    return Field(key, "number", low, high, open_low, default=default, unit=unit, doc=doc,
                 scale=scale)


def _integer(key, low, high, default=REQUIRED, doc=""):
    return Field(key, "integer", low, high, default=default, unit="-", doc=doc)


def _table_field(key, default=None, doc=""):
    return Field(key, "table", default=default, doc=doc)


def _accepted_later(value) -> bool:  # checked with another key (see table_design)
    return True


def _name_ok(value) -> bool:
    return isinstance(value, str) and bool(value.strip()) and len(value) <= 80


#: every design table's keys; a new key = one entry here (and its field in the model)
DESIGN = _schema(
    "design",
    Field("name", "string", default=None, check=_name_ok, doc="default: the file's stem",
          allowed="a non-empty string of <= 80 characters"),
    _integer("n_planets", 1, 12, doc="number of planets"),
    Field("planet_angles_deg", "numbers", default=None, unit="deg", check=_accepted_later,
          allowed="a list of n_planets finite angles [deg] (one per planet)",
          doc="default: equally spaced from 0"),
    _number("module", 0, 0.05, open_low=True, unit="m", doc="normal module"),
    _number("pressure_angle_deg", 10, 35, 20.0, unit="deg", doc="pressure angle", scale=_DEG),
    _number("face_width", 0, 1, open_low=True, unit="m", doc="face width of every gear"),
    _table_field("sun", REQUIRED, "teeth, shift, bore"),
    _table_field("planet", REQUIRED, "teeth, shift, bore"),
    _table_field("ring", REQUIRED, "teeth, shift, rim_thickness or mass"),
    _table_field("supports", doc="count, arc_deg, first_deg"),
    _table_field("material", doc="E, nu, density (default steel)"),
    _table_field("load", doc="sun_torque"),
    _table_field("bearings", doc="planet, carrier: c_p, c_c by Palmgren line contact"),
    _table_field("lumped", doc="lumped fields the geometry does not give (SI)"),
)
_GEAR = (_integer("teeth", 6, 1000, doc="tooth count"),
         _number("shift", -2, 2, 0.0, unit="-", doc="profile shift coefficient"),
         _number("bore", 0, 10, None, True, "m", "default: 0.4 x root diameter"))
SUN = _schema("design.sun", *_GEAR)
PLANET = _schema("design.planet", *_GEAR)
RING = _schema("design.ring", _integer("teeth", 12, 1000, doc="tooth count"),
               _number("shift", -2, 2, 0.0, unit="-", doc="profile shift coefficient"),
               _number("rim_thickness", 0, 1, None, True, "m", "or mass"),
               _number("mass", 0, 1e5, None, True, "kg", "or rim_thickness"))
SUPPORTS = _schema("design.supports",
                   _integer("count", 0, 360, 6, "clamped arcs on the ring's outer surface; 0: all"),
                   _number("arc_deg", 0, 360, 20.0, True, "deg", "angular width of each arc", _DEG),
                   _number("first_deg", -360, 360, 0.0, unit="deg",
                           doc="polar angle of the middle of the first arc", scale=_DEG))
MATERIAL = _schema("design.material",
                   _number("E", 1e6, 1e13, _STEEL.E, unit="Pa", doc="Young's modulus"),
                   _number("nu", -0.99, 0.49, _STEEL.nu, unit="-", doc="Poisson's ratio"),
                   _number("density", 1, 1e5, _STEEL.density, unit="kg/m^3", doc="density"))
LOAD = _schema("design.load", _number("sun_torque", 0, 1e7, 1000.0, True, "N m", "input torque"))
BEARINGS = _schema("design.bearings", _table_field("planet", doc="planet bearing"),
                   _table_field("carrier", doc="carrier bearing"))
_ROLLERS = (_integer("rollers", 1, 1000, doc="rolling elements"),
            _number("roller_length", 0, 1, open_low=True, unit="m", doc="effective length"))
BEARING = {"planet": _schema("design.bearings.planet", *_ROLLERS,
                             _number("load", 0, 1e8, None, True, "N", "default: from the torque")),
           "carrier": _schema("design.bearings.carrier", *_ROLLERS,
                              _number("load", 0, 1e8, REQUIRED, True, "N", "radial load"))}
#: the tables of a design file, for the docs
SCHEMAS = (DESIGN, SUN, PLANET, RING, SUPPORTS, MATERIAL, LOAD, BEARINGS, *BEARING.values())


#: tables that make a TOML file a scene (``hubvib.studies.scene``), not a design file
SCENE_TABLES = frozenset({"reducer", "study", "crack", "output", "detection", "signal",
                          "execution", "elastic"})


def read_design(path: Path) -> ReducerDesign:
    """Read a design file (its ``[design]`` table), every key's type and range checked.

    The assembly rules need the stages' geometry and are checked one layer up
    (``hubvib.reducer.load_design``)."""
    path = Path(path)
    text = read_text(path, "design file", DesignError, kind="TOML", max_bytes=MAX_FILE_BYTES)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DesignError(f"design file {str(path)!r} is not valid TOML: {exc}") from None
    if set(data) != {"design"}:
        study = sorted(set(data) & SCENE_TABLES)
        if study:
            raise DesignError(
                f"{str(path)!r} is a scene, not a design file (it has "
                f"{', '.join(f'[{t}]' for t in study)}): run it with `hubvib run {path}`; a "
                "design file holds one [design] table (docs/design.md)")
        raise DesignError(f"design file {str(path)!r}: expected one [design] table, found "
                          f"{sorted(data) or 'nothing'}")
    return table_design(data["design"], default_name=path.stem)


def table_design(table, default_name: str = "design") -> ReducerDesign:
    """A ``[design]`` table (dict) into a ``ReducerDesign``, every key's type and range
    checked (``SCHEMAS``).  ``hubvib.reducer.parse_design`` adds the assembly rules
    (``hubvib.reducer.assembly.check_assembly``).
    """
    d = _parse(DESIGN, table)
    n = d["n_planets"]
    angles = None
    if d["planet_angles_deg"] is not None:
        values = table["planet_angles_deg"]
        if not isinstance(values, list) or len(values) != n or not all(
                _is_number(v) and math.isfinite(v) for v in values):
            raise DesignError(f"design.planet_angles_deg = {values!r}; allowed: a list of "
                              f"{n} finite angles [deg] (one per planet)")
        angles = tuple(math.radians(v % 360.0) for v in values)
    ring = _parse(RING, d["ring"])
    if (ring["rim_thickness"] is None) == (ring["mass"] is None):
        raise DesignError("design.ring: give exactly one of rim_thickness [m] or mass [kg]")
    supports = _parse(SUPPORTS, d["supports"] or {})
    bearings = _parse(BEARINGS, d["bearings"] or {})
    return ReducerDesign(
        name=default_name if d["name"] is None else d["name"], n_planets=n,
        module=d["module"], pressure_angle=d["pressure_angle_deg"], face_width=d["face_width"],
        sun=GearSpec(**_parse(SUN, d["sun"])), planet=GearSpec(**_parse(PLANET, d["planet"])),
        ring=GearSpec(ring["teeth"], ring["shift"]),
        rim=RimSpec(thickness=ring["rim_thickness"], mass=ring["mass"]),
        planet_angles=angles,
        supports=SupportSpec(supports["count"], supports["arc_deg"], supports["first_deg"]),
        material=MaterialSpec(**_parse(MATERIAL, d["material"] or {})),
        sun_torque=_parse(LOAD, d["load"] or {})["sun_torque"],
        planet_bearing=_bearing(bearings, "planet"),
        carrier_bearing=_bearing(bearings, "carrier"),
        lumped=_lumped(d["lumped"] or {}))


def _parse(schema: Schema, table) -> dict:
    """The table's SI values (defaults for the keys absent); a table that is not one is
    refused as ``design.x = value; allowed: a table``."""
    if not isinstance(table, dict):
        raise DesignError(f"{schema.table} = {table!r}; allowed: a table")
    return schema.parse(table, defaults=True)


def _bearing(bearings: dict, key: str) -> BearingSpec | None:
    if bearings[key] is None:
        return None
    return BearingSpec(**_parse(BEARING[key], bearings[key]))


def _lumped(t: dict) -> dict:
    """``[design.lumped]``: any lumped stiffness, mass or diameter field (SI)."""
    allowed = STIFFNESS_FIELDS + MASS_FIELDS + DIAMETER_FIELDS
    for key, v in t.items():
        if key not in allowed:
            raise DesignError(f"unknown key design.lumped.{key}; allowed: {', '.join(allowed)}")
        if not _is_number(v) or not math.isfinite(v) or v < 0 or v > 1e15:
            raise DesignError(f"design.lumped.{key} = {v!r}; allowed: a number in [0, 1e15] "
                              "(SI: N/m, kg, m)")
    return {k: float(v) for k, v in t.items()}


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)
