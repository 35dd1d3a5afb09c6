"""The ring's support: its mounting in series with the FE ring body (SI).

A torque on the ring passes through the ring body and then the mounting, so
their compliances add: ``1/c = 1/c_mount + 1/c_body``.  A crack softens only
the body.  With a mounting far softer than the body (the paper's
``c_ru = 1e6 N/m`` against 1.66e10 N/m of steel ring) the mounting holds
almost all the compliance and a crack barely changes the total; with a rigid
mounting the total is the body itself (``apply = "direct"``).
"""
from __future__ import annotations

import numpy as np

#: how FE enters the lumped model (hubvib.cases.sweep.APPLY)
SERIES, RATIO, DIRECT = "series", "ratio", "direct"


def series(mount, body):
    """Stiffness of two springs in series [N/m]; an infinite one drops out.

    Parameters
    ----------
    mount, body : float or ndarray
        Stiffnesses [N/m], > 0 (``inf`` allowed), broadcast together.
    """
    mount, body = np.asarray(mount, dtype=float), np.asarray(body, dtype=float)
    with np.errstate(divide="ignore"):
        return 1.0 / (1.0 / mount + 1.0 / body)


def identify_mount(total: float, body: float, name: str = "c_ru") -> float:
    """The mounting [N/m] that gives ``total`` in series with ``body`` [N/m].

    Raises ValueError when ``total >= body``: no mounting makes a series pair
    stiffer than either spring.
    """
    if not 0 < total < body:
        raise ValueError(f"{name} = {total:.6g} N/m cannot be the series total of a mounting "
                         f"and the FE ring body {body:.6g} N/m: it must lie in (0, {body:.6g}); "
                         f"give [crack] {name}_mount or use apply = \"direct\"")
    return 1.0 / (1.0 / total - 1.0 / body)


def ring_support(apply: str, body, body_intact, preset, mount=None):
    """The lumped model's ring stiffness (``c_ru`` or ``c_r``) [N/m].

    Parameters
    ----------
    apply : str
        ``"series"``: ``mount`` in series with ``body``; ``"ratio"``: ``preset`` times
        ``body / body_intact`` (the paper's hypothesis, an upper bound of the effect);
        ``"direct"``: ``body``.
    body, body_intact : float or ndarray
        FE ring body at the crack depth and intact [N/m].
    preset : float or ndarray
        The preset's value [N/m] (used by ``"ratio"``).
    mount : float or ndarray, optional
        Mounting [N/m] (``"series"``).
    """
    if apply == SERIES:
        return series(mount, body)
    if apply == RATIO:
        return np.asarray(preset, dtype=float) * np.asarray(body) / np.asarray(body_intact)
    if apply == DIRECT:
        return np.asarray(body, dtype=float)
    raise ValueError(f"apply = {apply!r}; allowed: {SERIES}, {RATIO}, {DIRECT}")
