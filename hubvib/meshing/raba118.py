"""Raba 118/76 gears and bodies, built from its design (``hubvib.design.presets.raba118``,
where every Raba constant and assumption is stated)."""
from __future__ import annotations

from functools import lru_cache


@lru_cache(maxsize=1)
def design():
    from hubvib.design.presets import raba118

    return raba118()


def sun():
    from hubvib.design.build import spur_gears

    return spur_gears(design())[0]


def planet():
    from hubvib.design.build import spur_gears

    return spur_gears(design())[1]


def ring():
    from hubvib.design.build import spur_gears

    return spur_gears(design())[2]


def ring_gear(supports=None, fillet: str = "trochoid"):
    """The ring with its rim (outer diameter from the paper's 6.8 kg) and supports."""
    from hubvib.design.build import ring_gear as build

    return build(design(), supports, fillet)


def gear_body(name: str):
    """Sun or planet body on its bore (``name`` = ``"sun"`` or ``"planet"``)."""
    from hubvib.design.build import gear_body as build

    return build(design(), name)
