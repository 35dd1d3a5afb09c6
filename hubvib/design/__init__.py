"""The reducer design: one source for geometry, FE and the lumped model.

``load_design(path)`` reads a design file, ``preset_design(name)`` gives a shipped
design, ``check_assembly`` holds every assembly rule, ``hubvib.design.build``
turns a design into what each stage needs.
"""
from .assembly import check_assembly, summary
from .model import (BearingSpec, DesignError, GearSpec, MaterialSpec, ReducerDesign, RimSpec,
                    SupportSpec)
from .parse import load_design, parse_design
from .presets import PRESETS, preset_design

__all__ = ["BearingSpec", "DesignError", "GearSpec", "MaterialSpec", "PRESETS", "ReducerDesign",
           "RimSpec", "SupportSpec", "check_assembly", "load_design", "parse_design",
           "preset_design", "summary"]
