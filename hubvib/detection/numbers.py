"""Numbers for reports: round-off prints as 0, everything else with its significant digits.

An 18-DOF eigenproblem solved to ~1e-15 relative leaves sensitivities of
1e-31 and shifts of 1e-13 % where the exact value is 0 (a mode the change does
not touch).  Printed as ``6.7e-31`` or ``-0.000`` they read as a result; they
are printed as ``0``.
"""
from __future__ import annotations

import math

from hubvib.lumped.shift import ROUND_OFF



def number(value, digits: int = 3, zero: float = 0.0, sign: bool = False) -> str:
    """``value`` with ``digits`` significant digits, or ``"0"`` when ``|value| <= zero``.

    Parameters
    ----------
    value : float or None
        ``None`` and NaN print as ``"-"``.
    digits : int
        Significant digits.
    zero : float
        Magnitude at or below which the value is round-off (same unit as ``value``).
    sign : bool
        Print ``+`` for positive values.
    """
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if value == 0 or abs(value) <= zero:
        return "0"
    text = f"{value:{'+' if sign else ''}.{digits}g}"
    return text


def percent(value, digits: int = 3) -> str:
    """A relative change in percent; below :data:`ROUND_OFF` (relative) it prints 0."""
    return number(value, digits, zero=100 * ROUND_OFF, sign=True)


def shift_hz(value, frequency_hz: float, digits: int = 3) -> str:
    """A frequency shift [Hz] of a mode at ``frequency_hz``; round-off prints 0."""
    return number(value, digits, zero=ROUND_OFF * abs(frequency_hz), sign=True)


def sensitivity(value, digits: int = 3) -> str:
    """A relative sensitivity (d omega / omega) / (dk / k); round-off prints 0."""
    return number(value, digits, zero=ROUND_OFF)


def depth_mm(depth_m) -> str:
    """A depth [m] in mm, ``"-"`` when there is none."""
    if depth_m is None or (isinstance(depth_m, float) and math.isnan(depth_m)):
        return "-"
    return f"{1e3 * depth_m:.3g}"
