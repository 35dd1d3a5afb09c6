"""What a study kind is, the registry of kinds, and the scene that carries one.

A scene is a tagged union: the common part (reducer and design, ``[study]`` threshold and
eigensolver, ``[output]``, the optional sections of ``hubvib.studies.sections``:
``[detection]``, ``[signal]``, ``[execution]``, ``[elastic]``) and exactly one study kind,
named by ``Scene.kind``, whose parsed tables are ``Scene.study``.  Each kind declares the
scene tables that select it and parses them itself; ``select_study`` asks the registry which
kind a scene's tables select.  A new study kind is its module and one ``register_study``
call (``hubvib.studies.kinds`` registers the shipped ones).  Library code: nothing here
prints.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from hubvib.foundation.errors import SceneError
from hubvib.lumped import PlanetaryParameters
from hubvib.cases.sweep import CrackSweep
from hubvib.studies.sections import section_of


def _always(data: dict) -> bool:
    return True


@dataclass(frozen=True)
class Study:
    """One study kind.

    ``tables`` are the scene tables that select it (and that it owns; none: the scene
    has no other kind's table); ``selects(data)`` narrows the choice among kinds with the
    same tables from the raw TOML (``selection`` says how, for the error messages).
    ``parse(data, design, params)`` checks its tables (``SceneError`` naming the key and
    the allowed range) and returns its frozen options, ``Scene.study``.
    ``run(scene, staged)`` computes and writes every file into the staged folder and
    returns the result (its ``files`` are the paths written); ``summary(scene, result,
    folder, files)`` is the ``hubvib run --json`` object; ``lines(scene, result, folder)``
    are the printed lines.  ``fe``: the study runs the FE stage on the scene's design (it
    needs the FE extra and a writable stiffness cache, and the lumped parameters must
    agree with the design); ``renders``: it can render (``[output] renders``).
    """

    kind: str
    run: Callable[[Any, Path], Any]
    summary: Callable[[Any, Any, Path, list], dict]
    lines: Callable[[Any, Any, Path], list]
    parse: Callable[[dict, Any, PlanetaryParameters], Any]
    tables: frozenset = frozenset()
    selects: Callable[[dict], bool] = _always
    selection: str = ""
    fe: bool = False
    renders: bool = False

    def describe(self) -> str:
        """How a scene selects this kind, e.g. ``crack ([crack] with model = "plane")``."""
        where = self.selection or (" + ".join(f"[{t}]" for t in sorted(self.tables))
                                   or "no study table")
        return f"{self.kind} ({where})"


#: the registered study kinds: kind -> Study (``register_study`` adds one)
STUDIES: dict[str, Study] = {}


def register_study(study: Study) -> Study:
    """Add a study kind to the registry; a kind name or a table set + selection taken by
    another kind is refused (``ValueError``)."""
    if study.kind in STUDIES:
        raise ValueError(f"study kind {study.kind!r} is registered already")
    STUDIES[study.kind] = study
    return study


def study_tables() -> set[str]:
    """Every scene table that selects a registered study kind."""
    return {table for study in STUDIES.values() for table in study.tables}


def select_study(data: dict) -> Study:
    """The one registered kind the scene's tables select; ``SceneError`` naming the tables
    when none or several do."""
    present = frozenset(key for key in data if key in study_tables())
    matches = [s for s in STUDIES.values() if s.tables == present and s.selects(data)]
    if len(matches) == 1:
        return matches[0]
    names = " + ".join(f"[{t}]" for t in sorted(present)) or "no study table"
    kinds = "; ".join(s.describe() for s in STUDIES.values())
    if not matches:
        raise SceneError(f"no study kind is selected by {names}; allowed: one of {kinds}")
    raise SceneError(f"{names} select several study kinds "
                     f"({', '.join(s.kind for s in matches)}); registered: {kinds}")


def study_of(scene: Scene) -> Study:
    """The registered study of the scene's kind."""
    return STUDIES[scene.kind]


@dataclass(frozen=True)
class Scene:
    """A parsed scene: what is common to every kind, and ``study``, the options of its
    kind (``kind``) as that kind's ``parse`` returned them."""

    name: str
    params: PlanetaryParameters
    threshold_percent: float
    method: str
    folder: Path
    plots: bool
    kind: str
    study: Any
    source: dict = field(repr=False, compare=False, default_factory=dict)
    renders: bool = False
    gif: bool = False
    vtm: bool = False
    design: object = None
    tables: dict = field(default_factory=dict, compare=False)

    def section(self, name: str):
        """The scene's parsed ``[name]`` section, or that section's default when the scene
        has no such table (``hubvib.studies.sections``); an unknown name is refused
        (``ValueError``)."""
        default = section_of(name).default
        value = self.tables.get(name)
        value = default if value is None else value
        if name == "signal" and self.design is not None:
            # one working torque: the design's (the loaded crack, the records, the bearings)
            from dataclasses import replace

            value = replace(value, sun_torque_N_m=float(self.design.sun_torque))
        return value

    def given(self, name: str):
        """The scene's parsed ``[name]`` section, or ``None`` when the scene has no such
        table (for what runs only on a given table)."""
        section_of(name)
        return self.tables.get(name)

    @property
    def detection(self):
        """The ``[detection]`` options (``hubvib.detection.options.DetectionOptions``)."""
        return self.section("detection")

    @property
    def execution(self):
        """The ``[execution]`` options (``hubvib.runtime.engines.Execution``)."""
        return self.section("execution")

    @property
    def signal(self):
        """The ``[signal]`` options (``hubvib.signal.options.SignalOptions``)."""
        return self.section("signal")

    @property
    def elastic(self):
        """The ``[elastic]`` options (``hubvib.elastic.options.ElasticScene``)."""
        return self.section("elastic")

    @property
    def crack(self) -> CrackSweep | None:
        """The FE crack sweep of a crack study (its ``[crack]`` table), else ``None`` (what
        the detection and signal modules read)."""
        return self.study if isinstance(self.study, CrackSweep) else None

    def lumped_source(self, key: str) -> str:
        """Where the lumped model's ``key`` comes from, as a report names it: the scene's
        ``[reducer.parameters]``, the ``[design]``'s lumped table (or its geometry), or the
        ``[reducer]`` preset's table."""
        overrides = self.source.get("reducer", {}).get("parameters", {})
        if key in overrides:
            return "the scene's [reducer.parameters]"
        name = getattr(self.design, "name", None)
        if "design" in self.source:
            given = self.design is not None and key in self.design.lumped_fields
            return f"the {'lumped table' if given else 'geometry'} of design {name!r}"
        preset = self.source.get("reducer", {}).get("preset", name)
        return f"the {preset} preset's table"

    @property
    def c_rp_given(self) -> bool:
        """Whether the lumped c_rp is a given value: a ``[reducer]`` preset's table, a
        design's ``lumped.c_rp`` or a ``[reducer.parameters]`` override.  Otherwise (a
        design-derived c_rp, ISO 6336-1 by default) a crack study uses the FE intact c_rp."""
        if "design" not in self.source or self.design is None:
            return True
        overrides = self.source.get("reducer", {}).get("parameters", {})
        return "c_rp" in self.design.lumped_fields or "c_rp" in overrides


def check_keys(table: dict, where: str, allowed) -> None:
    """Refuse keys of a scene table (``where``: its name, "" the top level) not in
    ``allowed``."""
    unknown = set(table) - set(allowed)
    if unknown:
        place = f"[{where}]" if where else "top level"
        raise SceneError(f"unknown key(s) {sorted(unknown)} at {place}; allowed: {sorted(allowed)}")


def string_key(table: dict, where: str, key: str, default: str) -> str:
    """``table[key]`` (``default`` when absent), refused unless a string."""
    value = table.get(key, default)
    if not isinstance(value, str):
        raise SceneError(f"[{where}] {key} = {value!r}, but it must be a string")
    return value
