"""The optional scene sections beside the study kind: ``[detection]``, ``[execution]``,
``[signal]`` and ``[elastic]``, each parsed by the module that uses it.

A section is its table's name, its parser (the table, a dict, to a frozen options object,
raising ``SceneError`` that names the key and the allowed range) and its one default, the
options a scene without the table runs with.  ``Scene.section(name)`` (or the properties
``Scene.detection``, ``.execution``, ``.signal``, ``.elastic``) gives the parsed table or
that default.  A new section is its parser and one ``register_section`` line below.
Library code: nothing here prints.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

from hubvib.detection.options import DetectionOptions, parse_detection_table
from hubvib.elastic.options import ElasticScene, parse_elastic_table
from hubvib.runtime.engines import Execution, parse_execution_table
from hubvib.signal.options import SignalOptions, parse_signal_table

__all__ = ["SECTIONS", "SceneSection", "register_section", "section_of"]


@dataclass(frozen=True)
class SceneSection:
    """One optional scene table: ``name`` (its TOML key), ``parse(table)`` (the checked,
    frozen options) and ``default`` (the options when the scene has no such table)."""

    name: str
    parse: Callable[[dict], Any]
    default: Any


#: the registered scene sections: name -> SceneSection (``register_section`` adds one)
SECTIONS: dict[str, SceneSection] = {}


def register_section(section: SceneSection) -> SceneSection:
    """Add a scene section; a name registered already is refused (``ValueError``)."""
    if section.name in SECTIONS:
        raise ValueError(f"scene section {section.name!r} is registered already")
    SECTIONS[section.name] = section
    return section


def section_of(name: str) -> SceneSection:
    """The registered section ``name``; ``ValueError`` naming the registered ones."""
    try:
        return SECTIONS[name]
    except KeyError:
        raise ValueError(f"unknown scene section {name!r}; registered: "
                         f"{', '.join(sorted(SECTIONS))}") from None


register_section(SceneSection("signal", parse_signal_table, SignalOptions()))
register_section(SceneSection("detection", parse_detection_table, DetectionOptions()))
register_section(SceneSection("execution", parse_execution_table, Execution()))
register_section(SceneSection("elastic", parse_elastic_table, ElasticScene()))
