"""Named designs: the one registry of presets (``PRESETS``).

Every Raba 118/76 constant lives here and nowhere else.  A new preset is one entry:
a function returning a ``ReducerDesign`` and a ``register_preset(name, factory)`` line
(here or in any module imported before use).  The CLI's choices (``design check``,
``spectrum``, ``mesh``, ``stiffness``, ``shift``, ...), their help texts, scene validation
(``preset = ...``) and the lumped presets (``hubvib.reducer.lumped_preset``) all read it.
"""
from __future__ import annotations

import math
from typing import Callable

from .involute import involute
from .model import (BearingSpec, DesignError, GearSpec, MaterialSpec, ReducerDesign, RimSpec,
                    SupportSpec)

#: name -> factory of the design, in registration order
PRESETS: dict[str, Callable[[], ReducerDesign]] = {}

RABA_WORKING_PRESSURE_ANGLE = math.radians(25.28)  # [rad] from the paper


def raba118() -> ReducerDesign:
    """Raba 118/76 wheel-hub stage (Yaglinsky, Gutyrya, Chanchin): the reference case.

    From the paper: base diameters (sun 79.404, planet 58.026, ring 195.45 mm), the
    working pressure angle 25.28 deg of both meshes, the ring mass 6.8 kg, and the
    lumped table (masses, reduced masses, the carrier's d_c = 157.5 mm, stiffnesses).
    Derived: with alpha = 20 deg the base diameters give z = 26 / 19 / 64 and
    m = 3.25 mm; both pairs share one centre distance, so x_s + x_p = x_r - x_p, and
    that sum follows from the working angle.
    """
    alpha, teeth = math.radians(20.0), {"sun": 26, "planet": 19, "ring": 64}
    shift_sum = (float(involute(RABA_WORKING_PRESSURE_ANGLE)) - float(involute(alpha))) * (
        teeth["sun"] + teeth["planet"]) / (2 * math.tan(alpha))
    planet_shift = 0.4  # ASSUMED
    return ReducerDesign(
        name="raba118", n_planets=3, module=3.25e-3, pressure_angle=alpha, face_width=40e-3,
        sun=GearSpec(teeth["sun"], shift_sum - planet_shift, bore=30e-3),
        planet=GearSpec(teeth["planet"], planet_shift, bore=36e-3),
        ring=GearSpec(teeth["ring"], shift_sum + planet_shift),
        rim=RimSpec(mass=6.8),
        supports=SupportSpec(count=6, arc=math.radians(20.0), first=0.0),
        material=MaterialSpec(210e9, 0.3, 7850.0),
        sun_torque=1000.0,
        planet_bearing=BearingSpec(rollers=16, roller_length=30e-3),
        carrier_bearing=BearingSpec(rollers=40, roller_length=20e-3, load=25e3),
        lumped=dict(m_s=1.9, m_c=13.8, m_r=6.8, m_p=0.85, mu_s=1.16, mu_c=13.88, mu_r=5.36,
                    mu_p=0.52, d_c=157.5e-3, c_sp=3.0e8, c_rp=3.0e8, c_p=1e8, c_c=1e8,
                    c_r=1e8, c_su=1e6, c_cu=1e6, c_ru=1e6),
        notes=(
            "masses, reduced masses, d_c and every stiffness of the lumped model: the paper's "
            "table (c_su = c_cu = 1e6 N/m fitted to its two lowest frequencies)",
            "ASSUMED: planet shift 0.4 (sun and planet tips equally thick), ISO 53 profile A "
            "rack (h_a* 1, h_f* 1.25, rho_fP* 0.38), ring cut by a 25-tooth shaper cutter",
            "ASSUMED: face width 40 mm; steel 210 GPa, 0.3, 7850 kg/m^3; bores sun 30 mm, "
            "planet 36 mm",
            "ASSUMED: six clamped support pads of 20 deg on the ring's outer surface",
            "ASSUMED: sun torque 1000 N m; planet needle bearing 16 x 30 mm; carrier (wheel-hub) "
            "bearing 40 rollers x 20 mm under 25 kN",
        ))


def hub4() -> ReducerDesign:
    """An illustrative four-planet hub stage with a thin rim (not a product; all ASSUMED).

    It contrasts with Raba 118/76: four planets, a rim 8 mm below the root circle
    (Raba: 24.5 mm), eight narrow support pads.  The lumped fields not given by the
    geometry: the ring mounting (c_ru 5e7, c_r 5e8 N/m) and the sun and carrier
    shafts (c_su = c_cu = 5e7 N/m).
    """
    return ReducerDesign(
        name="hub4", n_planets=4, module=2.5e-3, pressure_angle=math.radians(20.0),
        face_width=30e-3,
        sun=GearSpec(24, 0.2, bore=28e-3), planet=GearSpec(28, 0.2, bore=34e-3),
        ring=GearSpec(80, 0.6), rim=RimSpec(thickness=8e-3),
        supports=SupportSpec(count=8, arc=math.radians(15.0), first=0.0),
        sun_torque=500.0,
        planet_bearing=BearingSpec(rollers=14, roller_length=22e-3),
        carrier_bearing=BearingSpec(rollers=36, roller_length=18e-3, load=15e3),
        lumped=dict(c_ru=5e7, c_r=5e8, c_su=5e7, c_cu=5e7),
        notes=("every value ASSUMED: an illustrative four-planet stage, not a product",
               "the carrier: a steel disc over the planet-centre circle, face-width thick"))


def register_preset(name: str, factory: Callable[[], ReducerDesign]) -> None:
    """Add a named design (``factory()`` returns it); a name is registered once."""
    if not isinstance(name, str) or not name.isidentifier():
        raise DesignError(f"preset name {name!r}; allowed: a Python identifier")
    if name in PRESETS and PRESETS[name] is not factory:
        raise DesignError(f"preset {name!r} is already registered")
    PRESETS[name] = factory


def preset_names() -> tuple[str, ...]:
    """The registered preset names, in registration order (the CLI's choices)."""
    return tuple(PRESETS)


register_preset("raba118", raba118)
register_preset("hub4", hub4)


def preset_design(name: str) -> ReducerDesign:
    """The named design (see ``PRESETS``)."""
    if name not in PRESETS:
        raise DesignError(f"unknown design preset {name!r}; allowed: {', '.join(PRESETS)}")
    return PRESETS[name]()
