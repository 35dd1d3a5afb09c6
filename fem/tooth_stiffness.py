"""Mesh stiffnesses c_sp (sun-planet) and c_rp (ring-planet) from FE tooth compliance (SI).

Each gear's tooth compliance is computed by FE (``tooth_fe``) at Chebyshev
radii spanning its contact radii and interpolated in radius; Hertzian contact
is added analytically; the pairs in contact share the load (``mesh_cycle``).
The mean over a mesh cycle feeds the lumped model; min and max are the
variation.  A root crack on ring tooth 0 raises that tooth's compliance, and
``c_rp`` is also reported over the engagement of the cracked tooth.

Every FE number comes with its counterpart by the analytical potential-energy
method (``tooth_beam``) and by ISO 6336-1 (``iso6336``).
"""
from __future__ import annotations

import functools
import time
from dataclasses import dataclass, field

import numpy as np
from numpy.polynomial import chebyshev

from hubvib.meshing.ring_gear import ToothedBody
from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh

from .iso6336 import iso_stiffness
from .material import Material
from .mesh_cycle import GearPair, MeshCycle, mesh_cycle
from .tooth_beam import beam_compliance, hertz_compliance
from .tooth_fe import fe_tooth_compliance

NODES = 9  # Chebyshev radii per tooth


def chebyshev_radii(low: float, high: float, n: int = NODES) -> np.ndarray:
    k = np.arange(n)
    return 0.5 * (low + high) + 0.5 * (high - low) * np.cos((2 * k + 1) * np.pi / (2 * n))[::-1]


@dataclass(frozen=True)
class ToothCurve:
    """Tooth compliance [m/N] as a function of the contact radius [m] (interpolated)."""

    radii: np.ndarray
    compliance: np.ndarray
    dofs: int = 0
    seconds: dict = field(default_factory=dict)

    @functools.cached_property
    def _interpolant(self):
        return chebyshev.Chebyshev.fit(self.radii, self.compliance, len(self.radii) - 1,
                                       domain=[self.radii.min(), self.radii.max()])

    def __call__(self, r):
        low, high = self.radii.min(), self.radii.max()
        span = high - low
        r = np.asarray(r, dtype=float)
        if np.any((r < low - 0.05 * span) | (r > high + 0.05 * span)):
            raise ValueError(f"contact radius outside the computed range {low:.6g}..{high:.6g} m")
        return self._interpolant(r)


def contact_radii(body: ToothedBody, pairs: list[GearPair]) -> tuple[float, float]:
    """Smallest and largest contact radius of ``body`` over the pairs it belongs to [m]."""
    radii = []
    for pair in pairs:
        r1, r2 = pair.radii(np.array(pair.path))
        radii.extend(r1 if pair.first is body else r2)
    return float(min(radii)), float(max(radii))


def fe_curve(body: ToothedBody, radii_range, material: Material, options, crack=None,
             mesher=None, tooth: int = 0) -> ToothCurve:
    """FE tooth compliance of ``tooth`` at Chebyshev radii of ``radii_range``;
    ``mesher(body, crack, options)`` replaces ``ring_mesh`` (to share meshes)."""
    radii = chebyshev_radii(*radii_range)
    started = time.perf_counter()
    mesh = (mesher or ring_mesh)(body, crack, options)
    meshed = time.perf_counter() - started
    result = fe_tooth_compliance(body, mesh, radii, material, tooth)
    seconds = {"mesh": meshed, "assembly": result.seconds["assembly"],
               "solve": result.seconds["solve"] + result.seconds["measure"]}
    return ToothCurve(radii, result.compliance, result.dofs, seconds)


def beam_curve(body: ToothedBody, radii_range, material: Material) -> ToothCurve:
    radii = chebyshev_radii(*radii_range)
    return ToothCurve(radii, np.array([beam_compliance(body, r, material).total for r in radii]))


@dataclass(frozen=True)
class PairStiffness:
    """Mesh stiffness of one pair [N/m] by FE, by the analytical method and by ISO 6336-1.

    ``cracked`` (when a cracked ring tooth was given) is the cycle over that
    tooth's engagement, ``cracked_reference`` the same window intact.
    """

    pair: GearPair
    fe: MeshCycle
    analytic: MeshCycle
    iso_single: float
    iso_mesh: float
    iso_in_range: bool
    cracked: MeshCycle | None = None
    cracked_reference: MeshCycle | None = None
    seconds: dict = field(default_factory=dict)
    dofs: int = 0

    @property
    def value(self) -> float:
        """Mean FE mesh stiffness over the cycle: the lumped model's c_sp / c_rp [N/m]."""
        return self.fe.mean


def pair_result(pair: GearPair, first: ToothCurve, second: ToothCurve,
                   first_beam: ToothCurve, second_beam: ToothCurve, material: Material,
                   cracked_second: ToothCurve | None = None) -> PairStiffness:
    b = min(pair.first.gear.face_width, pair.second.gear.face_width)
    q_h = hertz_compliance(b, material)
    fe = mesh_cycle(pair, first, second, q_h)
    analytic = mesh_cycle(pair, first_beam, second_beam, q_h)
    cracked = reference = None
    if cracked_second is not None:
        cracked = mesh_cycle(pair, first, second, q_h, marked_pair_compliance=cracked_second)
        reference = mesh_cycle(pair, first, second, q_h, marked_pair_compliance=second)
    gears = sorted((pair.first.gear, pair.second.gear), key=lambda g: (g.internal, g.teeth))
    iso = iso_stiffness(gears[0], gears[1], pair.contact_ratio)
    single, mesh = iso.per_face_width(b)
    curves = [first, second] + ([cracked_second] if cracked_second is not None else [])
    seconds = {k: sum(c.seconds.get(k, 0.0) for c in curves) for k in ("mesh", "assembly", "solve")}
    return PairStiffness(pair, fe, analytic, single, mesh, iso.in_range, cracked, reference,
                         seconds, sum(c.dofs for c in curves))


@dataclass(frozen=True)
class EngagedMesh:
    """Ring-planet mesh over the engagement of a cracked ring tooth, cracked and intact."""

    cracked: MeshCycle
    intact: MeshCycle
    #: roll lengths [m] where the cracked tooth is in contact (the cycles run one base pitch
    #: further on each side, where cracked and intact coincide)
    engagement: tuple[float, float]

    @property
    def mean_ratio(self) -> float:
        """Cracked / intact mean stiffness while the cracked tooth is in contact [-]: the
        ratio that holds for the engaged fraction ``N eps_alpha / z_r`` of the time.  (Over
        the cycles' whole span, eps_alpha + 2 pitches, the mean would dilute the change by
        eps_alpha / (eps_alpha + 2), about 0.41 for the Raba ring, and the detection model
        applies the ratio for the contact time only.)"""
        inside = self._window
        return float(self.cracked.stiffness[inside].mean() / self.intact.stiffness[inside].mean())

    @property
    def _window(self) -> np.ndarray:
        return (self.cracked.s >= self.engagement[0]) & (self.cracked.s <= self.engagement[1])

    @property
    def intact_window_mean(self) -> float:
        """Intact mean stiffness while the cracked tooth is in contact [N/m], the
        denominator of ``mean_ratio``: the crack's extra compliance over the window is
        ``(1 / mean_ratio - 1) / intact_window_mean`` [m/N] exactly."""
        return float(self.intact.stiffness[self._window].mean())

    @property
    def min_ratio(self) -> float:
        return float(self.cracked.stiffness.min() / self.intact.stiffness.min())


#: where the intact curves come from beside this process's memory (``set_intact_store``)
_INTACT_STORE = None


def set_intact_store(store) -> None:
    """Let ``store(compute, body, span, material, options, tooth)`` give the intact curves
    (None: compute them here): it returns the ``ToothCurve`` that ``compute()`` returns,
    e.g. computed once by one of several worker processes and shared on disk."""
    global _INTACT_STORE
    _INTACT_STORE = store


#: intact curves this process measured on a model it solved anyway (``offer_intact_curve``)
_OFFERED: dict = {}


@functools.lru_cache(maxsize=8)
def _intact_curve(body, span, material, options, tooth: int = 0) -> ToothCurve:
    def compute() -> ToothCurve:
        offered = _OFFERED.get((body, span, material, options, tooth))
        return offered if offered is not None else fe_curve(body, span, material, options,
                                                            tooth=tooth)

    store = _INTACT_STORE
    return compute() if store is None else store(compute, body, span, material, options, tooth)


def offer_intact_curve(body: ToothedBody, span, material: Material, options, tooth: int,
                       curve: ToothCurve) -> None:
    """Give ``intact_curve`` the curve ``fe_curve(body, span, material, options,
    tooth=tooth)`` would compute, measured elsewhere on the same model (e.g. the intact
    crack case's mesh, ``crack_level.ring_and_tooth``): kept here and handed to the
    store (``set_intact_store``) for the other processes, so that no one computes it."""
    key = (body, tuple(float(r) for r in span), material, options, tooth)
    _OFFERED[key] = curve
    if _INTACT_STORE is not None:
        _INTACT_STORE(lambda: curve, *key)


def provide_intact_curve(body: ToothedBody, span, material: Material, options, tooth: int,
                         compute) -> None:
    """Make ``compute()`` the source of ``intact_curve(body, span, material, options,
    tooth)`` unless this process has that curve already: computed here (or read from the
    store, ``set_intact_store``, when another process computed it) and kept."""
    key = (body, tuple(float(r) for r in span), material, options, tooth)
    if key in _OFFERED:
        return
    _OFFERED[key] = compute() if _INTACT_STORE is None else _INTACT_STORE(compute, *key)


def intact_curve(body: ToothedBody, span, material: Material, options, tooth: int = 0
                 ) -> ToothCurve:
    """The intact FE curve of ``tooth`` over the contact radii ``span`` [m], kept between
    calls (the one ``engaged_mesh`` uses)."""
    return _intact_curve(body, tuple(float(r) for r in span), material, options, tooth)


def engaged_ring_mesh(planet: ToothedBody, ring: ToothedBody, crack, options=None,
                      material: Material = Material(), mesher=None) -> EngagedMesh:
    """c_rp over the engagement of ring tooth 0 carrying ``crack`` (depth > 0).

    The intact tooth curves are kept between calls (a crack sweep reuses them);
    ``mesher`` meshes the cracked ring (see ``fe_curve``).
    """
    options = MeshOptions() if options is None else options
    span = contact_radii(ring, [GearPair(planet, ring)])
    cracked = fe_curve(ring, span, material, options, crack, mesher)
    return engaged_mesh(planet, ring, cracked, options, material)


def engaged_mesh(planet: ToothedBody, ring: ToothedBody, cracked: ToothCurve | None, options,
                 material: Material = Material(), tooth: int = 0) -> EngagedMesh:
    """c_rp over the engagement of ring tooth ``tooth`` whose compliance is ``cracked``
    (at the Chebyshev radii of the ring's contact span), against the same tooth intact;
    ``cracked = None``: the tooth intact (both cycles the intact one).

    The intact curves (planet; ring tooth ``tooth``, meshed with ``options``) are kept
    between calls."""
    pair = GearPair(planet, ring)
    planet_curve = _intact_curve(planet, contact_radii(planet, [pair]), material, options)
    ring_curve = _intact_curve(ring, contact_radii(ring, [pair]), material, options, tooth)
    cracked = ring_curve if cracked is None else cracked
    q_h = hertz_compliance(min(planet.gear.face_width, ring.gear.face_width), material)
    return EngagedMesh(
        mesh_cycle(pair, planet_curve, ring_curve, q_h, marked_pair_compliance=cracked),
        mesh_cycle(pair, planet_curve, ring_curve, q_h, marked_pair_compliance=ring_curve),
        pair.path)


def reducer_mesh_stiffness(sun: ToothedBody, planet: ToothedBody, ring: ToothedBody,
                           options=None, crack=None, material: Material = Material(),
                           ) -> dict[str, PairStiffness]:
    """``{"c_sp": ..., "c_rp": ...}`` of a planetary stage; ``crack`` on ring tooth 0."""
    options = MeshOptions() if options is None else options
    if crack is not None and crack.tooth != 0:
        raise ValueError(f"crack.tooth = {crack.tooth}: the tooth-stiffness model loads tooth 0")
    sun_pair, ring_pair = GearPair(planet, sun), GearPair(planet, ring)
    pairs = {"sun": [sun_pair], "planet": [sun_pair, ring_pair], "ring": [ring_pair]}
    bodies = {"sun": sun, "planet": planet, "ring": ring}
    fe, beam = {}, {}
    for name, body in bodies.items():
        span = contact_radii(body, pairs[name])
        fe[name] = fe_curve(body, span, material, options)
        beam[name] = beam_curve(body, span, material)
    cracked = None
    if crack is not None and crack.depth > 0:
        span = contact_radii(ring, [ring_pair])
        cracked = fe_curve(ring, span, material, options, crack)
    return {
        "c_sp": pair_result(sun_pair, fe["planet"], fe["sun"], beam["planet"], beam["sun"],
                               material),
        "c_rp": pair_result(ring_pair, fe["planet"], fe["ring"], beam["planet"], beam["ring"],
                               material, cracked),
    }
