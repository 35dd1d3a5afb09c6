"""Parameters from the edges (CLI ``--set``, TOML files) into SI dataclasses.

Keys are the field names of :class:`lumped.PlanetaryParameters` (SI).  Edge
conveniences, converted here and nowhere else:

``n_planets``   N equally spaced planets starting at theta = 0 (1..MAX_PLANETS)
``theta_deg``   planet angles [deg] in [-360, 360], comma separated on the command line
``alpha_w_deg`` one working pressure angle for both meshes [deg], in (0, 90)

One source gives the planets one way: ``n_planets`` with ``theta`` or
``theta_deg`` of a different count, ``theta`` with ``theta_deg``, or
``alpha_w_deg`` with ``alpha_s``/``alpha_r`` is refused, not silently resolved.
A parameters file is a regular UTF-8 TOML file of at most ``MAX_FILE_BYTES``.
"""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

from hubvib.foundation.files import MAX_FILE_BYTES, read_text
from hubvib.reducer import lumped_preset
from hubvib.design import PRESETS
from hubvib.lumped import ParameterError, PlanetaryParameters, equally_spaced_angles, field_names

CONVENIENCE_KEYS = ("n_planets", "theta_deg", "alpha_w_deg")
TUPLE_KEYS = ("theta", "theta_deg", "c_rp_factors")
#: keys that say the same thing and must not both be given by one source
_EXCLUSIVE = (("theta", "theta_deg"), ("alpha_w_deg", "alpha_s"), ("alpha_w_deg", "alpha_r"))


def apply_overrides(params: PlanetaryParameters, overrides: dict) -> PlanetaryParameters:
    """Apply ``{key: value}`` overrides (field names or convenience keys)."""
    _check_exclusive(overrides)
    changes = {}
    for key, value in overrides.items():
        if key == "n_planets":
            if isinstance(value, float) and value.is_integer():
                value = int(value)
            if "theta" not in overrides and "theta_deg" not in overrides:
                changes["theta"] = equally_spaced_angles(value)
        elif key == "theta_deg":
            values = value if isinstance(value, (list, tuple)) else [value]
            for i, v in enumerate(values):
                if abs(_number(f"{key}[{i}]", v)) > 360:
                    raise ParameterError(f"{key}[{i}] = {v!r}, but planet angles must lie in "
                                         "[-360, 360] deg")
            changes["theta"] = tuple(math.radians(v) for v in values)
        elif key == "alpha_w_deg":
            value = _number(key, value)
            if not 0 < value < 90:
                raise ParameterError(f"{key} = {value!r}, but it must lie in (0, 90) deg")
            changes["alpha_s"] = changes["alpha_r"] = math.radians(value)
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
        parts = [parse_number(key, p) for p in text.split(",")]
        result[key.strip()] = parts if len(parts) > 1 or key.strip() in TUPLE_KEYS else parts[0]
    return result


def load_parameters(preset_name: str = "raba118", params_file: Path | None = None,
                    overrides: dict | None = None) -> PlanetaryParameters:
    """Preset, then the TOML file's keys (may name its own ``preset``), then overrides."""
    file_values = {}
    if params_file is not None:
        file_values = read_toml_file(params_file, "parameters file")
        preset_name = file_values.pop("preset", preset_name)
        if not isinstance(preset_name, str):
            raise ParameterError(f"parameters file {str(params_file)!r}: preset = "
                                 f"{preset_name!r}, but it must be a string")
        try:
            params = apply_overrides(preset_parameters(preset_name), file_values)
        except ParameterError as exc:
            raise ParameterError(f"parameters file {str(params_file)!r}: {exc}") from None
    else:
        params = preset_parameters(preset_name)
    return apply_overrides(params, overrides or {})


def preset_parameters(name: str) -> PlanetaryParameters:
    """The lumped parameters of a registered design preset (``hubvib.design.PRESETS``),
    built from its design (``hubvib.reducer.lumped_preset``); an unknown name is a
    ``ParameterError`` naming the presets."""
    if name not in PRESETS:
        raise ParameterError(f"unknown preset {name!r}; available: {sorted(PRESETS)}")
    return lumped_preset(name)


def read_toml_file(path: Path, what: str = "parameters file", error=ParameterError) -> dict:
    """The TOML table in ``path`` (read by :func:`read_text_file`); errors name the file."""
    text = read_text_file(path, what, error)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise error(f"{what} {str(path)!r} is not valid TOML: {exc}") from None


def read_text_file(path: Path, what: str = "parameters file", error=ParameterError) -> str:
    """The UTF-8 text of a TOML file ``path``, read by the one guarded reader
    (:func:`hubvib.foundation.files.read_text`: regular files of at most
    ``MAX_FILE_BYTES`` only); every refusal names ``what`` and the file."""
    return read_text(path, what, error, kind="TOML", max_bytes=MAX_FILE_BYTES)


def _check_exclusive(overrides: dict) -> None:
    for a, b in _EXCLUSIVE:
        if a in overrides and b in overrides:
            raise ParameterError(f"{a} and {b} are both given; they set the same thing, "
                                 "give one of them")
    if "n_planets" in overrides:
        n = overrides["n_planets"]
        if isinstance(n, float) and n.is_integer():
            n = int(n)  # --set gives 4.0
        for key in ("theta", "theta_deg"):
            angles = overrides.get(key)
            count = len(angles) if isinstance(angles, (list, tuple)) else 1
            if key in overrides and count != n:
                raise ParameterError(
                    f"n_planets = {n!r}, but {key} gives {count} planet angle(s); give one "
                    "of them (n_planets spaces the planets equally)")


def parse_number(key: str, text: str) -> float:
    """``text`` as a float; a ``ParameterError`` naming ``key`` otherwise."""
    try:
        return float(text)
    except ValueError:
        raise ParameterError(f"{key} = {text!r}, but it must be a number") from None


def _number(key, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(f"{key} = {value!r}, but it must be a number")
    return value
