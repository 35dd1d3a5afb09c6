"""The lumped model of a registered design preset, kept here as the convenience the
README's worked example uses (``lumped.raba118()``, ``lumped.preset("hub4")``).

The model is built from the design one layer up (``hubvib.build.lumped_preset``); this
module is the one import from a stage to the build layer, named as the exception in the
import-linter contracts (pyproject.toml) and imported only when called.
"""
from __future__ import annotations

from hubvib.design.presets import PRESETS

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


def preset(name: str) -> PlanetaryParameters:
    """Parameters of a registered design preset (``hubvib.design.PRESETS``)."""
    if name not in PRESETS:
        raise ParameterError(f"unknown preset {name!r}; available: {sorted(PRESETS)}")
    from hubvib.build import lumped_preset  # the build layer sits above this stage

    return lumped_preset(name)
