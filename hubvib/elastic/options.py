"""How the elastic ring is built: its mesh, mounting, modal cut-off and rest spring (SI)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from hubvib.foundation.errors import InputError
from hubvib.foundation.schema import Field, Schema
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


RING_MODELS = ("rigid", "elastic", "both")
CRACK_LOADS = ("working", "open")


@dataclass(frozen=True)
class ElasticScene:
    """A crack scene's ``[elastic]`` table: which ring model(s) the study runs on and how.

    ``ring``: ``"rigid"`` (the 9 + 3N model only), ``"elastic"`` or ``"both"`` (the report
    gives both answers side by side); ``sensor_angle``: the accelerometer on the ring's
    outer surface, from the cracked tooth's centre line [rad]; ``options``: the model;
    ``map``: also the elastic ring's detectability against the foundation stiffness
    (``hubvib.detection.elastic_map``; one reduced ring per crack depth); ``crack_load``:
    ``"working"`` (the crack's faces opening and closing under the design's sun torque as
    the planets pass, and the spectrum a record sees of it) or ``"open"`` (the faces free
    at every moment, planet 1 half a planet pitch away: an upper bound of the change);
    ``pad_variant``: also the answer with the crack at the tooth of the other relation to
    the support pads (between pads for a crack on one, and the reverse;
    ``hubvib.detection.pad_variant``), on the sweep's depths.
    """

    ring: str = "rigid"
    sensor_angle: float = math.pi / 2
    options: ElasticOptions = field(default_factory=lambda: ElasticOptions(mesh=study_mesh(),
                                                                           cutoff_factor=2.0))
    map: bool = False
    crack_load: str = "working"
    pad_variant: bool = False

    @property
    def elastic(self) -> bool:
        return self.ring in ("elastic", "both")


def study_mesh() -> MeshOptions:
    """The ring mesh of the crack study's elastic ring: the modal mesh's sizes x2 and a crack
    tip six times coarser (a crack's change of a coupled mode is the difference of two such
    meshes; on the Raba ring its changes of the coupled modes at 9 mm are within 1 Hz of
    the modal mesh's; docs/elastic_ring.md gives them on two finer levels)."""
    return MeshOptions(size=8e-3, tooth_size=2.5e-3, load_size=0.6e-3, tip_size=0.3e-3,
                       grading=0.5)


#: the ``[elastic]`` keys
SCHEMA = Schema("elastic", (
    Field("ring", "choice", choices=RING_MODELS, default="rigid",
          doc="the ring model(s) of the crack study: rigid (9 + 3N), elastic (the FE ring "
          "coupled), both", message="{label} = {value}; allowed: {allowed}"),
    Field("mounting", "choice", choices=MOUNTINGS, default="foundation",
          doc="the ring on its support arcs", message="{label} = {value}; allowed: {allowed}"),
    Field("foundation_k_n_N_m2", "number", 0.0, 1e18, True, False, default=None,
          unit="N/m^2", doc="normal foundation stiffness per unit arc length (absent: "
          "sized to the design's c_r and c_ru)", attr="foundation_k_n"),
    Field("foundation_k_t_N_m2", "number", 0.0, 1e18, False, False, default=None,
          unit="N/m^2", doc="tangential ... (give both or neither)", attr="foundation_k_t"),
    Field("band_hz", "number", 1.0, 1e6, False, False, default=10e3, unit="Hz",
          doc="coupled modes up to this frequency"),
    Field("sensor_angle_deg", "number", -360.0, 360.0, False, False, default=90.0,
          unit="deg", doc="accelerometer on the ring's outer surface, from the cracked "
          "tooth", attr="sensor_angle", scale=math.pi / 180),
    Field("crack_load", "choice", choices=CRACK_LOADS, default="working",
          doc="working: the crack under the design's sun torque over a planet pitch (faces "
          "apart or pressed) and the spectrum a record sees; open: faces free at every "
          "moment (an upper bound)", message="{label} = {value}; allowed: {allowed}"),
    Field("map", "bool", default=False,
          doc="also the elastic ring's smallest detectable depth against the foundation "
          "stiffness (x 0.1 .. 100; needs mounting foundation)"),
    Field("pad_variant", "bool", default=False,
          doc="also the smallest detectable depth with the crack moved to the middle of the "
          "gap beside its support pad (or, between pads, to the middle of the nearest pad), "
          "on the sweep's depths (needs a ring on pads)"),
))


def parse_elastic_table(table: dict) -> ElasticScene:
    """Validate an ``[elastic]`` table; raise SceneError naming the key and range."""
    from hubvib.foundation.errors import SceneError

    values = SCHEMA.parse(table, defaults=True)
    try:
        options = ElasticOptions(
            mesh=study_mesh(), cutoff_factor=2.0, mounting=values["mounting"],
            foundation_k_n=values["foundation_k_n"], foundation_k_t=values["foundation_k_t"],
            band_hz=values["band_hz"])
    except ElasticOptionsError as error:
        raise SceneError(f"[elastic] {error}") from None
    if values["map"] and options.mounting != "foundation":
        raise SceneError(f"[elastic] map = true scales the foundation: it needs mounting = "
                         f"foundation (not {options.mounting})")
    return ElasticScene(values["ring"], values["sensor_angle"], options, values["map"],
                        values["crack_load"], values["pad_variant"])
