"""The error bar of an FE value from three mesh levels: Richardson's estimate with the
observed order where the levels are in the asymptotic range, else the larger of the two
level differences (any unit: the value's).

With element size ``h`` on the fine level, ``r_fine h`` on the medium and
``r_coarse r_fine h`` on the coarse one, and an error ``C h^p``, the differences
``d_coarse = medium - coarse`` and ``d_fine = fine - medium`` satisfy

    d_coarse / d_fine = r_fine^p (r_coarse^p - 1) / (r_fine^p - 1)   (= r^p for one ratio r),

which gives the observed order ``p``; the limit is ``fine + d_fine / (r_fine^p - 1)`` and
the error of the fine level its distance from it.  The levels count as asymptotic when
both differences have one sign and ``ORDER_RANGE`` holds ``p`` (above 4 is beyond the
energy-norm rate of P2 elements, below 0.5 slower than any singular corner: either is a
chance cancellation or the pre-asymptotic range); otherwise the error is the larger of
the two differences and the estimate is the fine value.
"""
from __future__ import annotations

import math
from typing import NamedTuple

#: observed orders [-] that count as the asymptotic range
ORDER_RANGE = (0.5, 4.0)
#: the two ways of taking the error
RULES = ("richardson", "larger_difference")


class ThreeLevelError(NamedTuple):
    """One value's three-level error.

    Attributes
    ----------
    estimate : float
        Richardson's limit (``"richardson"``) or the fine value [the value's unit].
    error : float
        The error bar of the fine value, >= 0 [the value's unit].
    order : float
        Observed order [-] (NaN where the differences give none).
    rule : str
        ``"richardson"`` or ``"larger_difference"`` (``RULES``).
    """

    estimate: float
    error: float
    order: float
    rule: str


def _ratio_of_differences(p: float, r_fine: float, r_coarse: float) -> float:
    """``d_coarse / d_fine`` of an error ``C h^p`` (module docstring)."""
    return r_fine ** p * (r_coarse ** p - 1) / (r_fine ** p - 1)


def observed_order(d_coarse: float, d_fine: float, r_fine: float = 2.0,
                   r_coarse: float | None = None) -> float:
    """The order ``p`` [-] with ``d_coarse / d_fine`` as an error ``C h^p`` gives it
    (bisection; the ratio grows with ``p``); NaN where the differences differ in sign or
    one is 0, or no ``p`` in 1e-3..64 gives the ratio."""
    r_coarse = r_fine if r_coarse is None else r_coarse
    if d_fine == 0 or d_coarse == 0 or (d_fine > 0) != (d_coarse > 0):
        return math.nan
    target = d_coarse / d_fine
    if r_coarse == r_fine:
        return math.log(target) / math.log(r_fine)
    low, high = 1e-3, 64.0
    if not _ratio_of_differences(low, r_fine, r_coarse) <= target <= _ratio_of_differences(
            high, r_fine, r_coarse):
        return math.nan
    for _ in range(200):
        middle = 0.5 * (low + high)
        if _ratio_of_differences(middle, r_fine, r_coarse) < target:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)


def three_level_error(coarse: float, medium: float, fine: float, r_fine: float = 2.0,
                      r_coarse: float | None = None) -> ThreeLevelError:
    """The error bar of ``fine`` from ``coarse``, ``medium`` and ``fine``, the same value on
    three meshes (module docstring).  ``r_fine``: element size of the medium level over the
    fine one's [-]; ``r_coarse``: the coarse level's over the medium's (default
    ``r_fine``).  Both ratios must exceed 1."""
    r_coarse = r_fine if r_coarse is None else r_coarse
    if not (r_fine > 1 and r_coarse > 1):
        raise ValueError(f"refinement ratios r_fine = {r_fine!r}, r_coarse = {r_coarse!r}; "
                         "allowed: > 1")
    values = (float(coarse), float(medium), float(fine))
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"levels {values!r}; allowed: finite numbers")
    coarse, medium, fine = values
    d_coarse, d_fine = medium - coarse, fine - medium
    order = observed_order(d_coarse, d_fine, r_fine, r_coarse)
    if ORDER_RANGE[0] <= order <= ORDER_RANGE[1]:
        correction = d_fine / (r_fine ** order - 1)
        return ThreeLevelError(fine + correction, abs(correction), order, "richardson")
    return ThreeLevelError(fine, max(abs(d_coarse), abs(d_fine)), order, "larger_difference")
