"""Printed bounds that their own checks accept.

An error line that says ``allowed: >= 0.0836`` invites pasting 0.0836 back; rounded to
nearest, the printed number can lie just outside the range (0.08364 printed as 0.0836).
These format a bound rounded towards the allowed side instead: a lower bound up, an upper
bound down, and a strict bound one unit of its last digit further in when the rounding
lands on it.  The decimal rounding is exact, so the printed number, read back as a float,
is inside the range.
"""
from __future__ import annotations

import math
from decimal import ROUND_CEILING, ROUND_FLOOR, Context, Decimal


def lower_bound(value: float, digits: int = 6, strict: bool = False) -> str:
    """``value`` to ``digits`` significant digits, rounded up (``strict``: the printed number
    is above ``value``)."""
    return _directed(value, digits, up=True, strict=strict)


def upper_bound(value: float, digits: int = 6, strict: bool = False) -> str:
    """``value`` to ``digits`` significant digits, rounded down (``strict``: the printed
    number is below ``value``)."""
    return _directed(value, digits, up=False, strict=strict)


def lower_bound_fixed(value: float, decimals: int) -> str:
    """``value`` with ``decimals`` digits after the point, rounded up."""
    exact = Decimal(value).quantize(Decimal(1).scaleb(-decimals), rounding=ROUND_CEILING)
    return f"{exact:.{decimals}f}"


def _directed(value: float, digits: int, up: bool, strict: bool) -> str:
    if not math.isfinite(value):
        return f"{value:g}"
    exact = Decimal(value)
    rounded = Context(prec=digits, rounding=ROUND_CEILING if up else ROUND_FLOOR).plus(exact)
    if strict and rounded == exact:
        unit = Decimal(1).scaleb(rounded.adjusted() - digits + 1)
        rounded = Context(prec=digits, rounding=ROUND_CEILING if up else ROUND_FLOOR).plus(
            rounded + unit if up else rounded - unit)
    return f"{float(rounded):.{digits}g}"
