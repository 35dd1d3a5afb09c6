"""Parameters from the edges (CLI ``--set``, TOML files) into SI dataclasses.

Keys are the field names of :class:`lumped.PlanetaryParameters` (SI).  Edge
conveniences, converted here and nowhere else:

``n_planets``   N equally spaced planets starting at theta = 0
``theta_deg``   planet angles [deg], comma separated on the command line
``alpha_w_deg`` one working pressure angle for both meshes [deg]
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

from hubvib.lumped import ParameterError, PlanetaryParameters, equally_spaced_angles, field_names, preset

CONVENIENCE_KEYS = ("n_planets", "theta_deg", "alpha_w_deg")
TUPLE_KEYS = ("theta", "theta_deg", "c_rp_factors")


def apply_overrides(params: PlanetaryParameters, overrides: dict) -> PlanetaryParameters:
    """Apply ``{key: value}`` overrides (field names or convenience keys)."""
    changes = {}
    for key, value in overrides.items():
        if key == "n_planets":
            if isinstance(value, float) and value.is_integer():
                value = int(value)
            changes["theta"] = equally_spaced_angles(value)
        elif key == "theta_deg":
            values = value if isinstance(value, (list, tuple)) else [value]
            changes["theta"] = tuple(math.radians(_number(key, v)) for v in values)
        elif key == "alpha_w_deg":
            alpha = math.radians(_number(key, value))
            changes["alpha_s"] = changes["alpha_r"] = alpha
        elif key in ("theta", "c_rp_factors"):
            changes[key] = tuple(value) if isinstance(value, (list, tuple)) else (value,)
        elif key in field_names():
            changes[key] = _number(key, value)
        else:
            raise ParameterError(
                f"unknown parameter {key!r}; allowed: {', '.join(field_names() + CONVENIENCE_KEYS)}"
            )
    return params.replace(**changes)


def parse_set(items: list[str]) -> dict:
    """``["c_ru=1e5", "theta_deg=0,100,220"]`` -> ``{"c_ru": 1e5, "theta_deg": [0, 100, 220]}``."""
    result = {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or not key:
            raise ParameterError(f"--set {item!r}: expected KEY=VALUE, e.g. c_ru=1e5")
        parts = [_parse_number(key, p) for p in text.split(",")]
        result[key.strip()] = parts if len(parts) > 1 or key.strip() in TUPLE_KEYS else parts[0]
    return result


def load_parameters(preset_name: str = "raba118", params_file: Path | None = None,
                    overrides: dict | None = None) -> PlanetaryParameters:
    """Preset, then the TOML file's keys (may name its own ``preset``), then overrides."""
    file_values = {}
    if params_file is not None:
        with open(params_file, "rb") as handle:
            file_values = tomllib.load(handle)
        preset_name = file_values.pop("preset", preset_name)
    params = apply_overrides(preset(preset_name), file_values)
    return apply_overrides(params, overrides or {})


def _parse_number(key, text):
    try:
        return float(text)
    except ValueError:
        raise ParameterError(f"{key} = {text!r}, but it must be a number") from None


def _number(key, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(f"{key} = {value!r}, but it must be a number")
    return value
