"""A design's elastic-ring planetary model and its spectrum at a carrier position (SI).

``elastic_ring`` builds the mounted FE ring of a design (intact, or cracked with the faces
open or tied), its reduced basis for the carrier positions asked, and the rest spring;
``elastic_spectrum`` couples it to the lumped sun, carrier and planets with planet 1 on a
given ring tooth and classes every mode below the band's top.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from hubvib.reducer.stages import lumped_parameters, material, ring_gear
from hubvib.fem.ring_basis import RingBasis, ring_basis
from hubvib.fem.ring_body import Foundation, RingBody, ring_body
from hubvib.lumped.elastic_ring import CoupledModes, RingOperators, coupled_modes, engagement
from hubvib.lumped.parameters import PlanetaryParameters
from hubvib.meshing.crack import Crack
from hubvib.meshing.ring_mesh import ring_mesh

from .content import mode_content, pair_classes, pair_multiplicities, symmetry_pairs
from .options import ElasticOptions
from .rest import rest_stiffness


@dataclass(frozen=True, eq=False)
class ElasticRing:
    """The coupled model's parts for one ring (one crack state).

    ``carrier_teeth``: the positions (planet 1's tooth) the basis serves; ``k_rest`` the
    ring-planet spring without the ring body [N/m]; ``seconds`` per step; ``contact``: the
    crack faces' condensed contact (``crack_state.CrackContact``) when asked for;
    ``positions``: the reduced ring for every position of ``more_positions``
    (``fem.ring_positions``, with the crack pairs' responses when paired);
    ``tooth_compliance``: per tooth of those positions ``b^T K^-1 b`` [m/N] (``b`` its
    contact functional) of a mounted ring, from the basis's factorisation (empty when
    none was kept or the ring is free).
    """

    params: PlanetaryParameters
    body: RingBody
    basis: RingBasis
    operators: RingOperators
    k_rest: float
    foundation: Foundation | None
    crack: Crack | None
    closed: bool
    options: ElasticOptions
    carrier_teeth: tuple
    seconds: dict = field(default_factory=dict)
    contact: object = None  # crack_state.CrackContact when the crack's faces are paired
    positions: object = None  # fem.ring_positions.RingPositions for more carrier positions
    tooth_compliance: dict = field(default_factory=dict)

    @property
    def label(self) -> str:
        if self.crack is None:
            return "intact"
        faces = "closed" if self.closed else "open"
        return f"{self.crack.start} crack {1e3 * self.crack.depth:.3g} mm, faces {faces}"


@dataclass(frozen=True, eq=False)
class ElasticSpectrum:
    """Coupled modes at one carrier position with each mode's content; ``pair_partner``:
    per mode its partner's index in a pair by symmetry, or None (``content.symmetry_pairs``;
    empty when not computed)."""

    modes: CoupledModes
    content: tuple
    multiplicity: tuple
    carrier_tooth: int
    ring: ElasticRing | None  # None once dropped for pickling
    pair_partner: tuple = ()

    @property
    def frequency_hz(self) -> np.ndarray:
        return self.modes.frequency_hz

    def rows(self) -> list[dict]:
        """One dict per mode, for tables and JSON."""
        out = []
        f_all = self.frequency_hz
        for i, (f, c, m) in enumerate(zip(f_all, self.content, self.multiplicity)):
            row = {"mode": i + 1, "frequency_hz": float(f), "multiplicity": m,
                   "class": c.kind, "nodal_diameter": c.nodal_diameter,
                   "harmonic_index": c.harmonic_index, "ring_share": c.ring_share,
                   "harmonic_share": c.harmonic_share}
            if self.pair_partner:
                j = self.pair_partner[i]
                row["pair_mode"] = None if j is None else j + 1
                row["pair_split_hz"] = None if j is None else float(abs(f_all[j] - f))
            out.append(row)
        return out


def out_of_contact_tooth(teeth: int, n_planets: int) -> int:
    """Planet 1's tooth half a planet pitch from tooth 0: no planet on tooth 0."""
    return int(round(teeth / (2 * n_planets))) % teeth


def elastic_ring(design, crack: Crack | None = None, closed: bool = False,
                 options: ElasticOptions = ElasticOptions(), carrier_teeth=None,
                 params: PlanetaryParameters | None = None, k_rest: float | None = None,
                 more_positions=(), crack_faces: bool = False) -> ElasticRing:
    """The elastic ring of ``design``; ``carrier_teeth`` (planet 1's ring tooth at each
    carrier position the spectrum is wanted at) defaults to the cracked tooth (0 when
    intact) and the position half a planet pitch away.  ``params``: the lumped model to
    couple to (default: the design's); ``k_rest``: the ring-planet spring without the ring
    body [N/m] (default ``rest_stiffness(design, options.rest)``).

    ``more_positions``: further carrier positions, each to get its own reduced ring
    (``ElasticRing.positions``) from the same factorisation; ``crack_faces`` (an open
    crack only): pair the crack's faces, add their static responses to every position's
    ring and condense their contact (``ElasticRing.contact``)."""
    seconds = {}
    started = time.perf_counter()
    params = lumped_parameters(design) if params is None else params
    ring, mat = ring_gear(design), material(design)
    if crack is not None and crack.depth == 0:
        crack = None
    mesh = ring_mesh(ring, crack, options.mesh)
    seconds["mesh"] = time.perf_counter() - started
    foundation = sized_to = None
    if options.mounting == "foundation":
        if options.foundation_k_n is not None:
            foundation = Foundation(options.foundation_k_n, options.foundation_k_t)
        else:
            sized_to = (params.c_r, params.c_ru)
    body = ring_body(ring, mesh, mat, options.mounting, foundation,
                     tie_crack=closed and crack is not None, sized_to=sized_to)
    foundation = body.foundation
    seconds["body"] = time.perf_counter() - started - seconds["mesh"]
    tooth = 0 if crack is None else crack.tooth
    if carrier_teeth is None:
        carrier_teeth = (tooth, (tooth + out_of_contact_tooth(ring.teeth, params.n_planets))
                         % ring.teeth)
    carrier_teeth = tuple(int(k) for k in carrier_teeth)
    sign = -np.sign(body.rigid[:, 2] @ body.contact)
    probe_ops = RingOperators(body.K, body.M, body.contact, np.asarray(sign).ravel(),
                              body.patch_angles, body.directions, body.probe)
    engaged = sorted({k for c in carrier_teeth
                      for k in engagement(params, probe_ops, c).teeth})
    more = sorted({k for c in more_positions
                   for k in engagement(params, probe_ops, int(c)).teeth} - set(engaged))
    pairs = None
    if crack_faces and crack is not None and not closed:
        from hubvib.fem.crack_pairs import crack_pairs

        pairs = crack_pairs(body)
    t = time.perf_counter()
    functionals = pairs.functionals if pairs is not None else (
        np.zeros((body.ndofs, 0)) if len(more_positions) else None)  # responses kept
    basis = ring_basis(body, engaged, options.cutoff_hz, more_teeth=more,
                       functionals=functionals)
    seconds["basis"] = time.perf_counter() - t
    contact = positions = None
    compliance = {}
    if basis.responses is not None:
        from hubvib.fem.ring_positions import ring_positions

        positions = ring_positions(body, basis, None if pairs is None else pairs.functionals)
        if pairs is not None:
            from .crack_state import crack_contact

            contact = crack_contact(body, pairs, basis.responses.functional)
        if body.mounting != "free":  # the factor was K's (no shift): first = K^-1 b
            loads = body.contact[:, list(basis.responses.teeth)]
            loads = loads.toarray() if hasattr(loads, "toarray") else np.asarray(loads)
            compliance = dict(zip(basis.responses.teeth,
                                  np.einsum("ij,ij->j", loads, basis.responses.first)))
        basis = replace(basis, responses=None)  # (dofs, many): not kept
    seconds["positions"] = time.perf_counter() - t - seconds["basis"]
    operators = basis_operators(body, basis, probe_ops.moment_sign)
    t = time.perf_counter()
    k_rest = rest_stiffness(design, options.rest) if k_rest is None else float(k_rest)
    seconds["rest"] = time.perf_counter() - t
    return ElasticRing(params, body, basis, operators, k_rest, foundation, crack,
                       bool(closed and crack is not None), options, carrier_teeth, seconds,
                       contact, positions, compliance)


def basis_operators(body: RingBody, basis: RingBasis, moment_sign: np.ndarray
                    ) -> RingOperators:
    """The reduced ring of ``basis`` as the coupled model sees it (M = I)."""
    V = basis.V
    return RingOperators(basis.K, np.eye(basis.size), np.asarray(body.contact.T @ V).T,
                         moment_sign, body.patch_angles, body.directions,
                         np.asarray(body.probe @ V))


def lowest_ring_mode(er: ElasticRing) -> tuple[float, int] | None:
    """The mounted ring's lowest elastic mode of its own (no planets): frequency [Hz] and
    nodal diameters; None when none lies below the basis's cut-off."""
    from .content import diameter_content, is_elastic_ring_shape

    phi = er.basis.V[:, :er.basis.mode_hz.size]
    probe = np.asarray(er.body.probe @ phi)
    for j, f in enumerate(er.basis.mode_hz):
        if is_elastic_ring_shape(probe[:, j]):
            return float(f), int(np.argmax(diameter_content(probe[:, j])))
    return None


def full_operators(er: ElasticRing) -> RingOperators:
    """The same ring unreduced (sparse): for checks of the reduction."""
    b = er.body
    return RingOperators(b.K, b.M, b.contact, er.operators.moment_sign, b.patch_angles,
                         b.directions, b.probe)


def elastic_spectrum(er: ElasticRing, carrier_tooth: int | None = None) -> ElasticSpectrum:
    """Coupled modes up to the band's top with planet 1 on ``carrier_tooth`` (default the
    first of ``er.carrier_teeth``), each with its content and multiplicity."""
    tooth = er.carrier_teeth[0] if carrier_tooth is None else int(carrier_tooth)
    needed = engagement(er.params, er.operators, tooth).teeth
    missing = sorted(set(needed) - set(er.basis.teeth))
    if missing:
        raise ValueError(f"carrier_tooth = {tooth}: the ring's basis has no contact response "
                         f"for teeth {missing}; build it with this carrier position")
    modes = coupled_modes(er.params, er.operators, tooth, er.k_rest, max_hz=er.options.band_hz)
    spaced = er.params.equally_spaced(1e-9)
    content = tuple(mode_content(modes, j, er.params.n_planets, spaced)
                    for j in range(modes.omega.size))
    partner = symmetry_pairs(modes, modes.engagement.theta, spaced)
    return ElasticSpectrum(modes, pair_classes(content, partner), pair_multiplicities(partner),
                           tooth, er, partner)


def lumped_equivalent(er: ElasticRing, carrier_tooth: int) -> PlanetaryParameters:
    """The 9 + 3N model of the same system with the ring rigid (its mass and mounting from
    the FE ring's rigid motions, ``c_rp = k_rest``, planets at the engaged angles)."""
    from hubvib.lumped.elastic_ring import rigid_ring_parameters

    eng = engagement(er.params, er.operators, carrier_tooth)
    return rigid_ring_parameters(er.params, er.body.rigid_mass(), er.body.rigid_stiffness(),
                                 er.body.base_radius, er.k_rest, eng)

