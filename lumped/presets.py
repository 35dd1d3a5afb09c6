"""Named parameter sets."""
from __future__ import annotations

import math

from .parameters import ParameterError, PlanetaryParameters, equally_spaced_angles


def raba118() -> PlanetaryParameters:
    """Raba 118/76 wheel-hub stage (Yaglinsky, Gutyrya, Chanchin, table).

    All three torsional springs are 1e6 N/m: the paper's table gives only
    ``c_ru``; ``c_su = c_cu = 1e6`` is what reproduces its two lowest
    frequencies (337 and 537 rad/s).  Floating sun (``c_s = 0``), three equally
    spaced planets, one working angle 25.28 deg for both meshes.
    """
    alpha_w = math.radians(25.28)
    return PlanetaryParameters(
        m_s=1.9, m_c=13.8, m_r=6.8, m_p=0.85,
        mu_s=1.16, mu_c=13.88, mu_r=5.36, mu_p=0.52,
        d_s=79.404e-3, d_c=157.5e-3, d_r=195.45e-3, d_p=58.026e-3,
        c_sp=3.0e8, c_rp=3.0e8, c_p=1e8, c_c=1e8, c_r=1e8,
        c_su=1e6, c_cu=1e6, c_ru=1e6,
        alpha_s=alpha_w, alpha_r=alpha_w,
        theta=equally_spaced_angles(3),
    )


PRESETS = {"raba118": raba118}


def preset(name: str) -> PlanetaryParameters:
    """Parameters of a named preset (see ``PRESETS``)."""
    try:
        return PRESETS[name]()
    except KeyError:
        raise ParameterError(f"unknown preset {name!r}; available: {sorted(PRESETS)}") from None
