"""Where the probability of detection crosses the required value: the bracket a sweep
resolves, and the depth to add next to narrow it (SI; one rule for every ring model).

The crossing lies between the deepest computed depth whose POD stays below the required
probability under the first depth that reaches it (``low``, ``high``).  A sweep resolves
it when ``high - low <= RESOLUTION`` or when ``high`` is the shallowest depth worth adding
(``FLOOR``: "below 0.5 mm").  :func:`next_depth` bisects the bracket, never below
``FLOOR``; the study adds a bounded number of depths (``MAX_ADDED`` per record length).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["RESOLUTION", "FLOOR", "MAX_ADDED", "Bracket", "bracket", "next_depth"]

#: width of a resolved bracket [m]
RESOLUTION = 0.5e-3
#: shallowest depth a sweep adds [m]: a crack detectable there is "below 0.5 mm"
FLOOR = 0.5e-3
#: depths a study adds per record length at most [-]
MAX_ADDED = 4


@dataclass(frozen=True)
class Bracket:
    """The POD crossing of one record length.

    Attributes
    ----------
    low : float
        Deepest computed depth below ``high`` whose POD stays below the required
        probability [m] (0: the intact reducer).
    high : float or None
        Smallest computed depth whose POD reaches it [m] (None: none of the sweep).
    deepest : float
        The sweep's deepest depth [m].
    """

    low: float
    high: float | None
    deepest: float

    @property
    def found(self) -> bool:
        return self.high is not None

    @property
    def resolved(self) -> bool:
        """The crossing is known to ``RESOLUTION``, or lies at or below ``FLOOR``, or is not
        within the sweep (nothing to narrow)."""
        if self.high is None:
            return True
        return self.high - self.low <= RESOLUTION * (1 + 1e-9) or self.high <= FLOOR * (1 + 1e-9)

    def words(self) -> str:
        """``between 1.5 and 2 mm``, ``below 0.5 mm``, ``below 3 mm`` (a bracket from the
        intact reducer) or ``not within the sweep (up to 21 mm)``."""
        if self.high is None:
            return f"not within the sweep (up to {1e3 * self.deepest:.3g} mm)"
        if self.low == 0.0:
            return f"below {1e3 * self.high:.3g} mm"
        return f"between {1e3 * self.low:.3g} and {1e3 * self.high:.3g} mm"

    def to_dict(self) -> dict:
        out = {"low_mm": 1e3 * self.low,
               "high_mm": None if self.high is None else 1e3 * self.high,
               "resolved": self.resolved, "words": self.words()}
        if self.high is None:
            out["high_mm_reason"] = self.words()
        return out


def bracket(depths, pod, probability: float) -> Bracket:
    """The bracket of the crossing of ``pod`` (per depth of ``depths`` [m], ascending, the
    first 0) with ``probability`` [-]."""
    depths = np.asarray(depths, dtype=float)
    pod = np.asarray(pod, dtype=float)
    if depths.shape != pod.shape:
        raise ValueError(f"depths has shape {depths.shape}, pod {pod.shape}: one POD per depth")
    hits = np.flatnonzero((depths > 0) & (pod >= probability))
    if hits.size == 0:
        return Bracket(float(depths[int(np.argmax(depths))]) if depths.size else 0.0, None,
                       float(depths.max()))
    high = int(hits[0])
    below = np.flatnonzero((depths < depths[high]) & ~(pod >= probability))
    low = float(depths[below].max()) if below.size else 0.0
    return Bracket(low, float(depths[high]), float(depths.max()))


def next_depth(b: Bracket) -> float | None:
    """The depth [m] that halves ``b`` (at least ``FLOOR``), or None when it is resolved."""
    if b.resolved:
        return None
    middle = 0.5 * (b.low + b.high)
    depth = max(middle, FLOOR)
    depth = round(depth, 7)  # to 0.1 um: a plain number in the case cache and the tables
    return None if math.isclose(depth, b.high) or depth >= b.high else float(depth)
