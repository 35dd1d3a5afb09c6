"""Scene files: what to compute, validated on load.

A scene is TOML with these tables (all keys shown; SI units)::

    [reducer]
    preset = "raba118"            # see lumped.PRESETS
    [reducer.parameters]          # optional overrides, keys as for --set
    c_ru = 1e6

    [study]
    parameter = "c_ru"            # a stiffness or mass field of PlanetaryParameters
    values = [1e6, 5e5, 1e5]      # modified values; the first is not the baseline
    detection_threshold_percent = 1.0
    method = "jacobi"             # eigensolver, see lumped.METHODS

    [output]
    folder = "hubvib-out"         # relative to the current directory
    plots = true
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from lumped import METHODS, ParameterError, PlanetaryParameters, field_names

from .params_input import load_parameters

ALLOWED = {
    "": {"reducer", "study", "output"},
    "reducer": {"preset", "parameters"},
    "study": {"parameter", "values", "detection_threshold_percent", "method"},
    "output": {"folder", "plots"},
}


class SceneError(ValueError):
    """The scene file is invalid; the message names the key and what is allowed."""


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


def default_scene_text() -> str:
    """The embedded default scene (Raba 118/76, ring stiffness lowered by a crack)."""
    return resources.files("hubvib.scenes").joinpath("default.toml").read_text(encoding="utf-8")


def load_scene(path: Path | None = None) -> Scene:
    """Parse and validate a scene file; ``None`` gives the embedded default."""
    if path is None:
        return parse_scene(default_scene_text(), "default")
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise SceneError(f"cannot read scene {str(path)!r}: {exc.strerror}") from None
    return parse_scene(text, path.stem)


def parse_scene(text: str, name: str) -> Scene:
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
    try:
        params = load_parameters(_string(reducer, "reducer", "preset", "raba118"), overrides=overrides)
    except ParameterError as exc:
        raise SceneError(f"[reducer]: {exc}") from None

    parameter = _string(study, "study", "parameter", "c_ru")
    numeric = [f for f in field_names() if f != "theta"]
    if parameter not in numeric:
        raise SceneError(f"[study] parameter = {parameter!r}; allowed: {', '.join(numeric)}")
    values = study.get("values")
    if not isinstance(values, list) or not values or not all(
        isinstance(v, (int, float)) and not isinstance(v, bool) for v in values
    ):
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
    folder = Path(_string(output, "output", "folder", "hubvib-out"))
    return Scene(name, params, parameter, tuple(float(v) for v in values), float(threshold),
                 method, folder, plots, data)


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
