"""How the elastic ring is built: its mesh, mounting, modal cut-off and rest spring (SI)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from hubvib.foundation.errors import InputError
from hubvib.meshing.ring_mesh import MeshOptions

MOUNTINGS = ("foundation", "clamped", "free")
REST_METHODS = ("fe", "beam")


def modal_mesh() -> MeshOptions:
    """The ring mesh for its vibration: coarser than the stiffness cases' (the modes are
    rim bending; the load patches only need their mean displacement)."""
    return MeshOptions(size=4e-3, tooth_size=1.5e-3, load_size=0.3e-3)


class ElasticOptionsError(InputError):
    """An elastic-ring option out of range; the message names it."""


@dataclass(frozen=True)
class ElasticOptions:
    """Options of the elastic-ring model.

    Parameters
    ----------
    mesh : MeshOptions
        The ring's plane mesh (P2 by default).
    mounting : str
        ``"foundation"`` (Winkler springs on the support arcs, sized to the design's
        lumped ``c_r`` and ``c_ru`` unless ``foundation_k_n``/``foundation_k_t`` are
        given), ``"clamped"`` (the arcs held) or ``"free"``.
    foundation_k_n, foundation_k_t : float or None
        Normal and tangential foundation stiffness per unit arc length [N/m^2].
    band_hz : float
        Top of the band whose coupled modes are reported [Hz].
    cutoff_factor : float
        The ring's own modes are kept up to ``cutoff_factor * band_hz``.
    rest : str
        The ring-planet spring without the ring body: ``"fe"`` (FE planet tooth and
        Hertzian contact over the mesh cycle) or ``"beam"`` (the analytical planet tooth).
    """

    mesh: MeshOptions = field(default_factory=modal_mesh)
    mounting: str = "foundation"
    foundation_k_n: float | None = None
    foundation_k_t: float | None = None
    band_hz: float = 10e3
    cutoff_factor: float = 2.5
    rest: str = "fe"

    def __post_init__(self):
        if self.mounting not in MOUNTINGS:
            raise ElasticOptionsError(f"mounting = {self.mounting!r}; allowed: "
                                      f"{', '.join(MOUNTINGS)}")
        if self.rest not in REST_METHODS:
            raise ElasticOptionsError(f"rest = {self.rest!r}; allowed: {', '.join(REST_METHODS)}")
        given = (self.foundation_k_n is not None, self.foundation_k_t is not None)
        if any(given) and not all(given):
            raise ElasticOptionsError("foundation_k_n and foundation_k_t: give both or neither")
        if any(given) and self.mounting != "foundation":
            raise ElasticOptionsError("foundation_k_n, foundation_k_t: only with mounting "
                                      "'foundation'")
        for name, low, high in (("band_hz", 1.0, 1e6), ("cutoff_factor", 1.5, 10.0)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                    math.isfinite(value) and low <= value <= high):
                raise ElasticOptionsError(f"{name} = {value!r}, allowed {low:g}..{high:g}")

    @property
    def cutoff_hz(self) -> float:
        return self.band_hz * self.cutoff_factor
