"""One FE crack case, typed: the estimate with the crack it belongs to and its wall time (SI).

``PlaneCase`` (a crack through the face width, ``fem.estimate.CrackCaseEstimate``) and
``SolidCase`` (a semi-elliptic crack in the solid ring, ``fem.estimate.RingEstimate``) are
what the case runner (``hubvib.cases.runner``) gives its callers; ``to_dict`` and
``from_dict`` are the dict form the FE cache and the JSON output hold, used only there.
"""
from __future__ import annotations

from dataclasses import dataclass

from hubvib.fem.estimate import CrackCaseEstimate, RingEstimate

#: keys a solid case must hold although ``RingEstimate`` has defaults for them
SOLID_REQUIRED = ("min_quality", "poor_cells")


@dataclass(frozen=True)
class PlaneCase:
    """One plane crack case as the FE cache and the JSON output hold it: the estimate
    (``fem.estimate.CrackCaseEstimate``), the crack depth [m] and the wall time of the whole
    case [s].  ``to_dict`` gives the keys of the cache entry and of ``results.json``."""

    estimate: CrackCaseEstimate
    depth: float
    seconds_total: float

    def to_dict(self) -> dict:
        return dict(self.estimate.to_dict(), depth_m=self.depth,
                    seconds_total=self.seconds_total)

    @classmethod
    def from_dict(cls, data: dict) -> PlaneCase:
        """The inverse of ``to_dict``; ``ValueError`` names a missing or wrong key."""
        estimate = CrackCaseEstimate.from_dict(data)
        return cls(estimate, _number(data, "depth_m"), _number(data, "seconds_total"))


@dataclass(frozen=True)
class SolidCase:
    """One solid crack case: the ring estimate (``fem.estimate.RingEstimate``), the crack
    depth and half-length [m] and the wall time of the whole case [s]."""

    estimate: RingEstimate
    depth: float
    half_length: float
    seconds_total: float

    def to_dict(self) -> dict:
        return dict(self.estimate.to_dict(), depth_m=self.depth, half_length_m=self.half_length,
                    seconds_total=self.seconds_total)

    @classmethod
    def from_dict(cls, data: dict) -> SolidCase:
        """The inverse of ``to_dict``; ``ValueError`` names a missing or wrong key (the
        mesh quality, optional in a ``RingEstimate``, is required: the 3D report reads it)."""
        missing = [k for k in SOLID_REQUIRED if k not in data]
        if missing:
            raise ValueError(f"lacks {', '.join(missing)}")
        estimate = RingEstimate.from_dict(data)
        return cls(estimate, _number(data, "depth_m"), _number(data, "half_length_m"),
                   _number(data, "seconds_total"))


def _number(data: dict, key: str) -> float:
    value = data.get(key)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"lacks {key}" if key not in data else f"{key} = {value!r}; allowed: "
                         "a number")
    return float(value)


def read_case(data: dict) -> PlaneCase | SolidCase:
    """A case from its dict form (a cache entry, a JSON row): a ``SolidCase`` when it names
    a half-length, else a ``PlaneCase``; ``ValueError`` names a missing or wrong key."""
    return (SolidCase if "half_length_m" in data else PlaneCase).from_dict(data)


def typed_case(case) -> PlaneCase | SolidCase:
    """``case`` typed: a ``PlaneCase`` or ``SolidCase`` as it is, its dict form (rows read
    from a file, or written by hand in a test) read once with ``read_case``."""
    return read_case(case) if isinstance(case, dict) else case
