"""The reducer design: pure data at the bottom of the layers (it imports no stage).

``read_design(path)`` reads a design file and ``table_design(table)`` a ``[design]``
table (keys, types and ranges checked); ``preset_design(name)`` gives a registered
design (``PRESETS``, ``register_preset``).  The assembly rules and everything built from
a design (gears, bodies, materials, the lumped parameters) live one layer up, in
``hubvib.reducer`` (``hubvib.reducer.load_design`` = read + assembly rules).
"""
from .model import (BearingSpec, DesignError, GearSpec, MaterialSpec, ReducerDesign, RimSpec,
                    SupportSpec)
from .parse import read_design, table_design
from .presets import PRESETS, preset_design, preset_names, register_preset

__all__ = ["BearingSpec", "DesignError", "GearSpec", "MaterialSpec", "PRESETS", "ReducerDesign",
           "RimSpec", "SupportSpec", "preset_design", "preset_names", "read_design",
           "register_preset", "table_design"]
