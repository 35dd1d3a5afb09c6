"""Named parameter sets: the lumped model of each design preset (``hubvib.design``)."""
from __future__ import annotations

from functools import lru_cache

from .parameters import ParameterError, PlanetaryParameters


def raba118() -> PlanetaryParameters:
    """Raba 118/76 wheel-hub stage (Yaglinsky, Gutyrya, Chanchin, table).

    The paper's masses, reduced masses, d_c and stiffnesses; base diameters and the
    working angles (25.28 deg for both meshes) from the gear geometry of the design
    (``hubvib.design.presets.raba118``).  All three torsional springs are 1e6 N/m:
    the paper's table gives only ``c_ru``; ``c_su = c_cu = 1e6`` is what reproduces
    its two lowest frequencies (337 and 537 rad/s).  Floating sun (``c_s = 0``),
    three equally spaced planets.
    """
    return preset("raba118")


def hub4() -> PlanetaryParameters:
    """The illustrative four-planet, thin-rim stage (``hubvib.design.presets.hub4``)."""
    return preset("hub4")


PRESETS = {"raba118": raba118, "hub4": hub4}


def preset(name: str) -> PlanetaryParameters:
    """Parameters of a named preset (see ``PRESETS``)."""
    if name not in PRESETS:
        raise ParameterError(f"unknown preset {name!r}; available: {sorted(PRESETS)}")
    return _from_design(name)


@lru_cache(maxsize=None)
def _from_design(name: str) -> PlanetaryParameters:
    """The lumped model of the named design preset (built once; parameters are frozen)."""
    from hubvib.design.build import lumped_parameters
    from hubvib.design.presets import preset_design

    return lumped_parameters(preset_design(name))
