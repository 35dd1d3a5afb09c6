"""Raba 118/76 gears and bodies, built from its design (``hubvib.design.presets.raba118``,
where every Raba constant and assumption is stated)."""
from __future__ import annotations

from functools import lru_cache

from hubvib.reducer import stages
from hubvib.design.presets import preset_design


@lru_cache(maxsize=1)
def design():
    """The Raba 118/76 design (``hubvib.design.presets``)."""
    return preset_design("raba118")


def sun():
    return stages.spur_gears(design())[0]


def planet():
    return stages.spur_gears(design())[1]


def ring():
    return stages.spur_gears(design())[2]


def ring_gear(supports=None, fillet: str = "trochoid"):
    """The ring with its rim (outer diameter from the paper's 6.8 kg) and supports."""
    return stages.ring_gear(design(), supports, fillet)


def gear_body(name: str):
    """Sun or planet body on its bore (``name`` = ``"sun"`` or ``"planet"``)."""
    return stages.gear_body(design(), name)
