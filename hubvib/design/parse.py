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

from .fields import DIAMETER_FIELDS, MASS_FIELDS, STIFFNESS_FIELDS
from .model import (BearingSpec, DesignError, GearSpec, MaterialSpec, ReducerDesign, RimSpec,
                    SupportSpec)

MAX_FILE_BYTES = 1_000_000
KEYS = {
    "design": {"name", "n_planets", "planet_angles_deg", "module", "pressure_angle_deg",
               "face_width", "sun", "planet", "ring", "supports", "material", "load",
               "bearings", "lumped"},
    "sun": {"teeth", "shift", "bore"},
    "planet": {"teeth", "shift", "bore"},
    "ring": {"teeth", "shift", "rim_thickness", "mass"},
    "supports": {"count", "arc_deg", "first_deg"},
    "material": {"E", "nu", "density"},
    "load": {"sun_torque"},
    "bearings": {"planet", "carrier"},
    "bearings.planet": {"rollers", "roller_length", "load"},
    "bearings.carrier": {"rollers", "roller_length", "load"},
}
REQUIRED = {"design": ("n_planets", "module", "face_width", "sun", "planet", "ring"),
            "sun": ("teeth",), "planet": ("teeth",), "ring": ("teeth",),
            "bearings.planet": ("rollers", "roller_length"),
            "bearings.carrier": ("rollers", "roller_length", "load")}


def read_design(path: Path) -> ReducerDesign:
    """Read a design file (its ``[design]`` table), every key's type and range checked.

    The assembly rules need the stages' geometry and are checked one layer up
    (``hubvib.build.load_design``)."""
    path = Path(path)
    try:
        if path.is_dir():
            raise DesignError(f"design file {str(path)!r} is a directory")
        with open(path, "rb") as handle:
            raw = handle.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise DesignError(f"cannot read design file {str(path)!r}: {exc.strerror}") from None
    if len(raw) > MAX_FILE_BYTES:
        raise DesignError(f"design file {str(path)!r} is larger than {MAX_FILE_BYTES} bytes")
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise DesignError(f"design file {str(path)!r} is not UTF-8 TOML: {exc}") from None
    if set(data) != {"design"}:
        raise DesignError(f"design file {str(path)!r}: expected one [design] table, found "
                          f"{sorted(data) or 'nothing'}")
    return table_design(data["design"], default_name=path.stem)


def table_design(table, default_name: str = "design") -> ReducerDesign:
    """A ``[design]`` table (dict) into a ``ReducerDesign``, every key's type and range
    checked.  ``hubvib.build.parse_design`` adds the assembly rules
    (``hubvib.build.assembly.check_assembly``).
    """
    t = _table(table, "design")
    n = _integer(t, "design", "n_planets", low=1, high=12)
    angles = None
    if "planet_angles_deg" in t:
        values = t["planet_angles_deg"]
        if not isinstance(values, list) or len(values) != n or not all(
                _is_number(v) and math.isfinite(v) for v in values):
            raise DesignError(f"design.planet_angles_deg = {values!r}; allowed: a list of "
                              f"{n} finite angles [deg] (one per planet)")
        angles = tuple(math.radians(v % 360.0) for v in values)
    rim = _table(t["ring"], "ring")
    if ("rim_thickness" in rim) == ("mass" in rim):
        raise DesignError("design.ring: give exactly one of rim_thickness [m] or mass [kg]")
    supports = _table(t.get("supports", {}), "supports")
    material = _table(t.get("material", {}), "material")
    load = _table(t.get("load", {}), "load")
    bearings = _table(t.get("bearings", {}), "bearings")
    lumped = _lumped(t.get("lumped", {}))
    name = t.get("name", default_name)
    if not isinstance(name, str) or not name.strip() or len(name) > 80:
        raise DesignError(f"design.name = {name!r}; allowed: a non-empty string of <= 80 "
                          "characters")
    default_material = MaterialSpec()
    design = ReducerDesign(
        name=name, n_planets=n,
        module=_number(t, "design", "module", low=0, high=0.05, open_low=True),
        pressure_angle=math.radians(_number(t, "design", "pressure_angle_deg", 20.0, 10, 35)),
        face_width=_number(t, "design", "face_width", low=0, high=1, open_low=True),
        sun=_gear(t["sun"], "sun"), planet=_gear(t["planet"], "planet"),
        ring=GearSpec(_integer(rim, "ring", "teeth", low=12, high=1000),
                      _number(rim, "ring", "shift", 0.0, -2, 2)),
        rim=RimSpec(thickness=_number(rim, "ring", "rim_thickness", None, 0, 1, open_low=True),
                    mass=_number(rim, "ring", "mass", None, 0, 1e5, open_low=True)),
        planet_angles=angles,
        supports=SupportSpec(
            count=_integer(supports, "supports", "count", 6, 0, 360),
            arc=math.radians(_number(supports, "supports", "arc_deg", 20.0, 0, 360,
                                     open_low=True)),
            first=math.radians(_number(supports, "supports", "first_deg", 0.0, -360, 360))),
        material=MaterialSpec(
            E=_number(material, "material", "E", default_material.E, 1e6, 1e13),
            nu=_number(material, "material", "nu", default_material.nu, -0.99, 0.49),
            density=_number(material, "material", "density", default_material.density, 1,
                            1e5)),
        sun_torque=_number(load, "load", "sun_torque", 1000.0, 0, 1e7, open_low=True),
        planet_bearing=_bearing(bearings, "planet"),
        carrier_bearing=_bearing(bearings, "carrier"),
        lumped=lumped)
    return design


def _gear(value, where) -> GearSpec:
    t = _table(value, where)
    return GearSpec(_integer(t, where, "teeth", low=6, high=1000),
                    _number(t, where, "shift", 0.0, -2, 2),
                    _number(t, where, "bore", None, 0, 10, open_low=True))


def _bearing(bearings: dict, key: str) -> BearingSpec | None:
    if key not in bearings:
        return None
    where = f"bearings.{key}"
    t = _table(bearings[key], where)
    return BearingSpec(_integer(t, where, "rollers", low=1, high=1000),
                       _number(t, where, "roller_length", low=0, high=1, open_low=True),
                       _number(t, where, "load", None, 0, 1e8, open_low=True))


def _lumped(value) -> dict:
    t = _table(value, "lumped", check=False)
    allowed = STIFFNESS_FIELDS + MASS_FIELDS + DIAMETER_FIELDS
    for key, v in t.items():
        if key not in allowed:
            raise DesignError(f"unknown key design.lumped.{key}; allowed: {', '.join(allowed)}")
        if not _is_number(v) or not math.isfinite(v) or v < 0 or v > 1e15:
            raise DesignError(f"design.lumped.{key} = {v!r}; allowed: a number in [0, 1e15] "
                              "(SI: N/m, kg, m)")
    return {k: float(v) for k, v in t.items()}


def _table(value, where, check=True) -> dict:
    label = "design" if where == "design" else f"design.{where}"
    if not isinstance(value, dict):
        raise DesignError(f"{label} = {value!r}; allowed: a table")
    if check:
        unknown = sorted(set(value) - KEYS[where])
        if unknown:
            raise DesignError(f"unknown key(s) {', '.join(f'{label}.{k}' for k in unknown)}; "
                              f"allowed: {', '.join(sorted(KEYS[where]))}")
        missing = [k for k in REQUIRED.get(where, ()) if k not in value]
        if missing:
            raise DesignError(f"missing required key(s) "
                              f"{', '.join(f'{label}.{k}' for k in missing)}")
    return value


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _number(t, where, key, default=..., low=-math.inf, high=math.inf, open_low=False):
    label = "design" if where == "design" else f"design.{where}"
    if key not in t:
        if default is ...:
            raise DesignError(f"missing required key {label}.{key}")
        return default
    v = t[key]
    ok = _is_number(v) and math.isfinite(v) and (low < v if open_low else low <= v) and v <= high
    if not ok:
        bracket = "(" if open_low else "["
        raise DesignError(f"{label}.{key} = {v!r}; allowed: a number in {bracket}{low:g}, "
                          f"{high:g}]")
    return float(v)


def _integer(t, where, key, default=..., low=0, high=None):
    label = "design" if where == "design" else f"design.{where}"
    if key not in t:
        if default is ...:
            raise DesignError(f"missing required key {label}.{key}")
        return default
    v = t[key]
    if isinstance(v, bool) or not isinstance(v, int) or v < low or (high is not None and v > high):
        raise DesignError(f"{label}.{key} = {v!r}; allowed: an integer in {low}..{high}")
    return v
