"""The build layer: from a design (``hubvib.design``, pure data) to each stage's objects.

It sits above the stages (``hubvib.meshing``, ``hubvib.fem``, ``hubvib.lumped``) and below
validation and the app, so that neither a design nor a stage imports the other's
builder.  ``load_design`` and ``parse_design`` are the checked entry points: the
design's keys and ranges (``hubvib.design.parse``), then the assembly rules
(``hubvib.reducer.assembly``), which need the gear geometry of the meshing stage and the
path of contact of the FE stage.  ``lumped_preset(name)`` is the lumped model of a
registered design preset.
"""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from hubvib.reducer.assembly import check_assembly, summary
from hubvib.reducer.stages import (MOUNTING_FIELDS, bearing_stiffness, centre_distances,
                                 derived_lumped_fields, gear_body, lumped_parameters,
                                 mass_properties, material, mesh_force, ring_gear, spur_gears,
                                 working_angles)
from hubvib.design import ReducerDesign, preset_design, read_design, table_design
from hubvib.lumped.parameters import PlanetaryParameters


def load_design(path: Path) -> ReducerDesign:
    """Read a design file and check its keys, ranges and assembly rules."""
    design = read_design(path)
    check_assembly(design)
    return design


def parse_design(table, default_name: str = "design") -> ReducerDesign:
    """A ``[design]`` table (dict) into a checked ``ReducerDesign`` (keys, ranges, then the
    assembly rules of ``hubvib.reducer.assembly``)."""
    design = table_design(table, default_name)
    check_assembly(design)
    return design


@lru_cache(maxsize=None)
def lumped_preset(name: str) -> PlanetaryParameters:
    """The lumped model of a registered design preset (``hubvib.design.PRESETS``), built
    once (parameters are frozen)."""
    return lumped_parameters(preset_design(name))


__all__ = ["MOUNTING_FIELDS", "bearing_stiffness", "centre_distances", "check_assembly",
           "derived_lumped_fields", "gear_body", "load_design", "lumped_parameters",
           "lumped_preset", "mass_properties", "material", "mesh_force", "parse_design",
           "ring_gear", "spur_gears", "summary", "working_angles"]
