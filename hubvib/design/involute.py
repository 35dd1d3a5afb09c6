"""The involute function and its inverse (ISO 21771), the pure gear geometry a design's
presets and the meshing stage share."""
from __future__ import annotations

import math

import numpy as np


def involute(angle):
    """inv(a) = tan(a) - a [rad]."""
    return np.tan(angle) - angle


def inverse_involute(value: float) -> float:
    """Pressure angle a in [0, pi/2) with inv(a) = value (Newton, to machine precision)."""
    if not value >= 0:
        raise ValueError(f"inverse_involute({value!r}): the involute function is >= 0")
    a = (3 * value) ** (1 / 3) if value < 1 else math.atan(value + 1)
    for _ in range(60):
        step = (math.tan(a) - a - value) / math.tan(a) ** 2 if a > 0 else 0.0
        a -= step
        if abs(step) <= 1e-16 * max(a, 1e-300):
            break
    return a
