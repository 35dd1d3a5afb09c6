"""The band in which the rigid-ring (9 + 3N) model holds, computed against the elastic ring.

For one design and mounting the coupled elastic-ring spectrum is compared mode by mode
with ``rigid_equivalent``: the 9 + 3N model of the same system with the ring rigid (its
mass and mounting from the FE ring's rigid motions, the planets at the same angles, each
ring-planet spring the rest of the pair in series with the ring's statically condensed
compliance at its contact), so the two share every static stiffness and differ only by
the ring's inertia beyond its rigid motions: its own elastic modes.

Pairing is by shape, not by frequency order: below the first ring mode the two spectra
have the same count, but the elastic ring lowers some modes past others (a ring-dominated
mode can fall between two lumped ones and every later index would shift), so the order
alone would pair wrong modes.  Each coupled mode is described in the 9 + 3N coordinates:
the lumped bodies' DOFs as they are and the ring's rigid part (its mass-weighted
least-squares rigid motion ``x_r, y_r, u_r = r_b phi``), every coordinate weighted by the
square root of its mass.  A repeated rigid-model frequency is one subspace (its pair
rotates freely), so a coupled mode matches it by the share of its descriptor inside that
subspace, as :mod:`.tracking` does; the pairing maximises the summed match (Hungarian).

A coupled mode is *ring-dominated* when the ring's deformation (its kinetic energy less
that of its rigid part) holds at least ``RING_DOMINATED`` of the mode's kinetic energy, or
when no rigid-model mode matches it by ``MIN_MATCH``.  The band's top is the lowest
frequency where a coupled mode is ring-dominated or where a paired mode's frequencies
differ by more than ``rtol`` (default 1 %, of the rigid model's frequency); below it every
coupled mode has a rigid-model counterpart within ``rtol``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from hubvib.foundation.output import explained, finite_or_none

from .content import PAIR_RTOL, diameter_content, frequency_groups
from .model import elastic_ring, elastic_spectrum, lowest_ring_mode, lumped_equivalent
from .options import ElasticOptions

#: share of a coupled mode's kinetic energy in the ring's deformation from which it is a
#: mode of the ring (the rigid model has no counterpart) [-]
RING_DOMINATED = 0.5
#: subspace match below which a coupled mode has no rigid-model counterpart [-]
MIN_MATCH = 0.8
#: default tolerance on a paired mode's relative frequency difference [-]
RTOL = 0.01

__all__ = ["PairedMode", "ValidityBand", "validity_band", "compare_spectra", "rigid_equivalent",
           "local_contact_compliance",
           "RING_DOMINATED", "MIN_MATCH", "RTOL"]


@dataclass(frozen=True)
class PairedMode:
    """One mode of the rigid-ring model and the coupled mode it pairs with.

    ``rigid_hz`` [Hz]; ``elastic_hz`` [Hz] (NaN: no coupled mode in the band pairs with it);
    ``relative_difference`` (elastic - rigid) / rigid [-]; ``match`` the subspace match
    [0, 1]; ``ring_share``, ``deformation_share``: the coupled mode's kinetic energy in the
    ring and in the ring's deformation [-]; ``nodal_diameter`` the ring's dominant n."""

    mode: int
    rigid_hz: float
    elastic_hz: float
    relative_difference: float
    match: float
    ring_share: float
    deformation_share: float
    nodal_diameter: int | None


@dataclass(frozen=True)
class RingMode:
    """A coupled mode with no rigid-ring counterpart: ``frequency_hz`` [Hz], its shares
    [-], the ring's dominant nodal diameters and the best match to a rigid mode [-]."""

    frequency_hz: float
    deformation_share: float
    match: float
    nodal_diameter: int


@dataclass(frozen=True)
class ValidityBand:
    """Where the rigid-ring model holds for one design and mounting.

    Attributes
    ----------
    paired : tuple of PairedMode
        Every rigid-model (9 + 3N) mode, in its frequency order.
    ring_modes : tuple of RingMode
        Coupled modes below the band's cut-off without a rigid counterpart (ring-dominated).
    band_top_hz : float
        The rigid model holds below this frequency [Hz] (``inf``: over the whole compared
        band ``compared_to_hz``).
    limited_by : str
        What sets the top: ``"ring mode"``, ``"difference"`` or ``"none"``.
    rtol : float
        The tolerance on paired frequencies [-].
    lowest_ring_mode_hz : float or None
        The mounted ring's lowest elastic mode of its own (no planets) [Hz].
    lowest_ring_mode_n : int or None
        Its nodal diameters.
    compared_to_hz : float
        Top of the coupled spectrum compared [Hz].
    mounting : str
    foundation : tuple or None
        ``(k_n, k_t)`` [N/m^2].
    carrier_tooth : int
    """

    paired: tuple
    ring_modes: tuple
    band_top_hz: float
    limited_by: str
    rtol: float
    lowest_ring_mode_hz: float | None
    lowest_ring_mode_n: int | None
    compared_to_hz: float
    mounting: str
    foundation: tuple | None
    carrier_tooth: int

    @property
    def rigid_top_hz(self) -> float:
        """The highest rigid-model (9 + 3N) mode [Hz]."""
        return max(p.rigid_hz for p in self.paired)

    def holds_for(self, frequency_hz: float) -> bool:
        """Whether a mode at ``frequency_hz`` [Hz] lies inside the band."""
        return frequency_hz < self.band_top_hz

    def rows(self) -> list[dict]:
        """One dict per rigid-model mode (JSON-ready; NaN as None)."""
        rows = []
        for p in self.paired:
            why = (f"no coupled mode pairs with rigid mode {p.mode}: none is assigned to it "
                   f"that matches it by shape (subspace match >= {MIN_MATCH:g}) without the "
                   f"ring's own deformation dominating it (its best match to any coupled "
                   f"mode: {p.match:.2f})")
            rows.append(explained(
                {"mode": p.mode, "rigid_hz": p.rigid_hz,
                 "elastic_hz": finite_or_none(p.elastic_hz),
                 "relative_difference": finite_or_none(p.relative_difference), "match": p.match,
                 "ring_share": finite_or_none(p.ring_share),
                 "deformation_share": finite_or_none(p.deformation_share),
                 "nodal_diameter": p.nodal_diameter,
                 "inside_band": bool(p.rigid_hz < self.band_top_hz)},
                elastic_hz=why, relative_difference=why, ring_share=why,
                deformation_share=why, nodal_diameter=why))
        return rows


def rigid_fit(er) -> np.ndarray:
    """(3, basis size): the mass-weighted least-squares rigid motion (x [m], y [m],
    rotation [rad]) of the ring displacement of each reduced coordinate."""
    body = er.body
    MR = body.M @ body.rigid
    return np.linalg.solve(body.rigid_mass(), np.asarray(MR.T @ er.basis.V))


def coupled_descriptors(er, modes) -> tuple[np.ndarray, np.ndarray]:
    """The coupled modes in the 9 + 3N coordinates, mass-weighted (dofs, modes), and each
    mode's kinetic energy in the ring's deformation [-]."""
    from hubvib.lumped.elastic_ring import RING_DOFS

    fit = rigid_fit(er) @ modes.ring  # x, y [m], phi [rad] per mode
    rigid_mass = er.body.rigid_mass()
    rigid_energy = np.einsum("im,ij,jm->m", fit, rigid_mass, fit)
    r_b = er.body.base_radius
    ring_coords = np.vstack([fit[0], fit[1], r_b * fit[2]])
    ring_weights = np.sqrt([rigid_mass[0, 0], rigid_mass[1, 1], rigid_mass[2, 2] / r_b ** 2])
    n = modes.lumped.shape[0] + 3
    out = np.zeros((n, modes.omega.size))
    lumped_rows = [i for i in range(n) if i not in RING_DOFS]
    out[lumped_rows] = np.sqrt(modes.lumped_mass)[:, None] * modes.lumped
    out[list(RING_DOFS)] = ring_weights[:, None] * ring_coords
    deformation = np.clip(modes.ring_kinetic - rigid_energy, 0.0, 1.0)
    return out, deformation


def compare_spectra(er, spectrum, rigid_spectrum, rtol: float = RTOL,
                    band_hz: float = math.inf):
    """Pair the coupled modes of ``spectrum`` (``ElasticSpectrum`` of ``er``) with the
    rigid-ring model's ``rigid_spectrum`` (``lumped.Spectrum``); ``band_hz``: the top of
    the coupled spectrum [Hz] (a rigid mode without partner below it limits the band);
    returns (paired, ring modes, band top [Hz], what limits it)."""
    if not (math.isfinite(rtol) and 0 < rtol < 1):
        raise ValueError(f"rtol = {rtol!r}, allowed 0 < rtol < 1")
    modes = spectrum.modes
    b, deformation = coupled_descriptors(er, modes)
    a = np.sqrt(rigid_spectrum.mass)[:, None] * rigid_spectrum.shapes
    f_rigid, f = rigid_spectrum.frequency_hz, spectrum.frequency_hz
    b_norm = np.linalg.norm(b, axis=0)
    score = np.zeros((a.shape[1], b.shape[1]))
    for group in frequency_groups(f_rigid, PAIR_RTOL):
        q, _ = np.linalg.qr(a[:, group])
        score[group] = (np.linalg.norm(q.T @ b, axis=0) / np.where(b_norm > 0, b_norm, 1)) ** 2
    # a coupled mode of the ring's own cannot stand in for a rigid-model mode
    usable = np.where(deformation[None, :] < RING_DOMINATED, score, 0.0)
    rows, cols = linear_sum_assignment(-usable)
    partner = np.full(a.shape[1], -1)
    for r, c in zip(rows, cols):
        if usable[r, c] >= MIN_MATCH:
            partner[r] = c
    paired = []
    for i in range(a.shape[1]):
        j = partner[i]
        if j < 0:
            paired.append(PairedMode(i + 1, float(f_rigid[i]), math.nan, math.nan,
                                     float(score[i].max(initial=0.0)), math.nan, math.nan,
                                     None))
            continue
        paired.append(PairedMode(
            i + 1, float(f_rigid[i]), float(f[j]), float((f[j] - f_rigid[i]) / f_rigid[i]),
            float(score[i, j]), float(modes.ring_kinetic[j]), float(deformation[j]),
            int(np.argmax(diameter_content(modes.probe[:, j])))))
    taken = set(int(j) for j in partner if j >= 0)
    ring_modes = tuple(
        RingMode(float(f[j]), float(deformation[j]), float(score[:, j].max(initial=0.0)),
                 int(np.argmax(diameter_content(modes.probe[:, j]))))
        for j in range(f.size) if j not in taken)
    limits = [(m.frequency_hz, "ring mode") for m in ring_modes]
    limits += [(min(p.rigid_hz, p.elastic_hz), "difference") for p in paired
               if math.isfinite(p.elastic_hz) and abs(p.relative_difference) > rtol]
    # a rigid mode inside the compared band left without partner: the ring took its place
    limits += [(p.rigid_hz, "ring mode") for p in paired
               if not math.isfinite(p.elastic_hz) and p.rigid_hz * (1 + rtol) < band_hz]
    top, by = min(limits, default=(math.inf, "none"))
    return tuple(paired), ring_modes, float(top), by


def local_contact_compliance(er, teeth) -> np.ndarray:
    """Compliance of the ring at each tooth's contact beyond its rigid motion on the
    mounting [m/N]: ``b^T K^-1 b - b^T R (R^T K R)^-1 R^T b`` (``b`` the contact functional,
    ``R`` the ring's rigid motions): the ring tooth and the rim under one planet's load,
    statically condensed.  ``b^T K^-1 b`` comes from the basis's factorisation where the
    ring kept it (``ElasticRing.tooth_compliance``), else from a factorisation of K.
    Raises ``ValueError`` for a free ring (no mounting: ``K`` is singular)."""
    body = er.body
    if er.options.mounting == "free":
        raise ValueError("mounting = 'free': the ring has no mounting, so its contact "
                         "compliance is not defined; use 'foundation' or 'clamped'")
    teeth = [int(k) for k in teeth]
    B = body.contact[:, teeth]
    B = B.toarray() if hasattr(B, "toarray") else np.asarray(B)
    kept = er.tooth_compliance
    if all(k in kept for k in teeth):
        full = np.array([kept[k] for k in teeth], dtype=float)
    else:
        import scipy.sparse.linalg as spla

        full = np.einsum("ij,ij->j", B, spla.splu(body.K.tocsc()).solve(B))
    RB = body.rigid.T @ B
    rigid = np.einsum("ij,ij->j", RB, np.linalg.solve(body.rigid_stiffness(), RB))
    return full - rigid


def rigid_equivalent(er, carrier_tooth: int):
    """The 9 + 3N model the elastic ring reduces to when its inertia beyond the rigid
    motions is dropped: ``lumped_equivalent`` (ring mass and mounting from the FE ring's
    rigid motions) with each planet's ring mesh spring ``k_rest`` in series with the ring's
    local contact compliance at its tooth (``local_contact_compliance``).  Every stiffness
    is then the elastic ring's static one, so where the two spectra differ, the ring's own
    inertia (its elastic modes) is the cause."""
    from hubvib.lumped.elastic_ring import engagement

    params = lumped_equivalent(er, carrier_tooth)
    teeth = engagement(er.params, er.operators, carrier_tooth).teeth
    c_rp = 1.0 / (1.0 / er.k_rest + local_contact_compliance(er, teeth))
    mean = float(np.mean(c_rp))
    return params.replace(c_rp=mean, c_rp_factors=tuple(float(c / mean) for c in c_rp))


def validity_band(design, options: ElasticOptions = ElasticOptions(), rtol: float = RTOL,
                  carrier_tooth: int = 0, er=None) -> ValidityBand:
    """The rigid-ring model's band for ``design`` on the mounting of ``options``: the
    intact coupled spectrum (planet 1 on ``carrier_tooth``, up to ``options.band_hz``;
    rigid-model modes above it are not compared) against
    ``rigid_equivalent``; ``er``: an intact ``ElasticRing`` built with ``carrier_tooth``
    (else built here)."""
    from hubvib.lumped import natural_modes

    if er is None:
        er = elastic_ring(design, options=options, carrier_teeth=(carrier_tooth,))
    rigid = natural_modes(rigid_equivalent(er, carrier_tooth))
    spectrum = elastic_spectrum(er, carrier_tooth)
    paired, ring_modes, top, by = compare_spectra(er, spectrum, rigid, rtol,
                                                 er.options.band_hz)
    lowest = lowest_ring_mode(er)
    return ValidityBand(
        paired, ring_modes, top, by, float(rtol), None if lowest is None else lowest[0],
        None if lowest is None else lowest[1], float(er.options.band_hz), er.options.mounting,
        None if er.foundation is None else (er.foundation.k_n, er.foundation.k_t),
        int(carrier_tooth))


# ------------------------------------------------------------------ words for report and docs

def _top(band_top_hz: float, compared_to_hz: float) -> str:
    return (f"{band_top_hz:.0f} Hz" if math.isfinite(band_top_hz)
            else f"the top of the compared band, {compared_to_hz:.0f} Hz")


def _reason(band: ValidityBand) -> str:
    if band.limited_by == "ring mode":
        ring = min(band.ring_modes, key=lambda m: m.frequency_hz, default=None)
        if ring is not None and math.isclose(ring.frequency_hz, band.band_top_hz):
            return (f"a coupled mode of the ring's own ({ring.frequency_hz:.0f} Hz, n = "
                    f"{ring.nodal_diameter}, {100 * ring.deformation_share:.0f} % of its kinetic "
                    "energy in the ring's deformation) has no rigid-ring counterpart")
        return "a rigid-ring mode has no coupled counterpart (the ring's own modes took its place)"
    if band.limited_by == "difference":
        worst = min((p for p in band.paired if math.isfinite(p.relative_difference)
                     and abs(p.relative_difference) > band.rtol),
                    key=lambda p: (min(p.rigid_hz, p.elastic_hz), p.mode))
        return (f"rigid-ring mode {worst.mode} ({worst.rigid_hz:.1f} Hz) and its coupled "
                f"counterpart ({worst.elastic_hz:.1f} Hz) differ by "
                f"{100 * worst.relative_difference:+.2f} % (tolerance {100 * band.rtol:g} %)")
    return f"every mode compared agrees within {100 * band.rtol:g} %"


def validity_record(band: ValidityBand) -> dict:
    """The band as JSON (``survey`` data; NaN and inf as None).  ``rigid_ring_holds_below_hz``
    keeps the key the docs' table reads."""
    top = finite_or_none(band.band_top_hz)
    return {"lowest_ring_mode_hz": band.lowest_ring_mode_hz,
            "lowest_ring_mode_n": band.lowest_ring_mode_n,
            "rigid_top_hz": band.rigid_top_hz, "band_top_hz": top,
            "rigid_ring_holds_below_hz": top, "limited_by": band.limited_by,
            "reason": _reason(band), "rtol": band.rtol,
            "compared_to_hz": band.compared_to_hz, "mounting": band.mounting,
            "foundation_N_m2": None if band.foundation is None else list(band.foundation),
            "modes": band.rows(),
            "ring_modes": [{"frequency_hz": m.frequency_hz, "nodal_diameter": m.nodal_diameter,
                            "deformation_share": m.deformation_share, "match": m.match}
                           for m in band.ring_modes]}


def validity_lines(band: ValidityBand) -> list[str]:
    """The report's paragraph and table on the rigid-ring model's band (Markdown lines):
    replaces the convention "half the lowest ring mode"."""
    lowest = ("the mounted ring has no elastic mode of its own below the basis's cut-off"
              if band.lowest_ring_mode_hz is None else
              f"the mounted ring's lowest elastic mode of its own is "
              f"{band.lowest_ring_mode_hz:.1f} Hz (n = {band.lowest_ring_mode_n})")
    inside = [p for p in band.paired if p.rigid_hz < band.band_top_hz]
    lines = [
        f"Validity band (computed): {lowest}. Compared mode by mode with the 9 + 3N model of "
        "the same system with the ring rigid (its mass and mounting from the FE ring's rigid "
        "motions; each ring-planet spring the rest of the pair in series with the ring's "
        "statically condensed compliance at its contact, so every stiffness is the elastic "
        "ring's static one; modes paired by shape on the lumped bodies' coordinates and the "
        "ring's rigid part), the rigid-ring model holds below "
        f"{_top(band.band_top_hz, band.compared_to_hz)} ({len(inside)} of its "
        f"{len(band.paired)} modes): there {_reason(band)}.", "",
        "| mode | rigid ring [Hz] | elastic ring [Hz] | difference [%] | ring deformation "
        "[%] | inside |", "|---:|---:|---:|---:|---:|---|"]
    for p in band.paired:
        if not math.isfinite(p.elastic_hz):
            lines.append(f"| {p.mode} | {p.rigid_hz:.1f} | - | - | - | "
                         f"{'yes' if p.rigid_hz < band.band_top_hz else 'no'} |")
            continue
        lines.append(f"| {p.mode} | {p.rigid_hz:.1f} | {p.elastic_hz:.1f} | "
                     f"{100 * p.relative_difference:+.2f} | {100 * p.deformation_share:.1f} | "
                     f"{'yes' if p.rigid_hz < band.band_top_hz else 'no'} |")
    lines += ["", f"'-': no coupled mode below {band.compared_to_hz:.0f} Hz pairs with it "
              f"(subspace match >= {MIN_MATCH:g}). Coupled modes of the ring's own "
              f"(>= {100 * RING_DOMINATED:.0f} % of the kinetic energy in the ring's "
              "deformation, or no rigid counterpart): "
              + (", ".join(f"{m.frequency_hz:.0f} Hz (n {m.nodal_diameter})"
                           for m in band.ring_modes) or "none") + ".", ""]
    return lines


def validity_table(records: dict) -> str:
    """The docs' table of the band per design from ``validity_record`` dicts
    (``{design name: record}``), with its explanation (Markdown)."""
    head = ("| design | lowest ring mode [Hz] | n | rigid ring holds below [Hz] | set by |\n"
            "|---|---:|---:|---:|---|")
    rows = []
    for name, r in records.items():
        top = r["band_top_hz"]
        rows.append(f"| {name} | {r['lowest_ring_mode_hz']:.1f} | {r['lowest_ring_mode_n']} | "
                    + (f"{top:.0f}" if top is not None else f"> {r['compared_to_hz']:.0f}")
                    + f" | {r['reason']} |")
    tol = {r["rtol"] for r in records.values()}
    return "\n".join([head, *rows]) + (
        "\n\nComputed, not a rule of thumb: the intact coupled spectrum is compared mode by "
        "mode with the 9 + 3N model of the same system with the ring rigid (its mass and "
        "mounting from the FE ring's rigid motions; each ring-planet spring the rest of the "
        "pair in series with the ring's statically condensed compliance at its contact, "
        "``rigid_equivalent``: the two models share every static stiffness, so a difference "
        "is the ring's own inertia), the modes "
        "paired by shape on the lumped bodies' coordinates and the ring's rigid part "
        "(a repeated frequency as one subspace). The band ends at the lowest frequency where "
        f"a coupled mode is the ring's own (>= {100 * RING_DOMINATED:.0f} % of its kinetic "
        "energy in the ring's deformation, or no rigid-model mode matches it) or where a "
        "pair's frequencies differ by more than "
        + ", ".join(f"{100 * t:g} %" for t in sorted(tol)) + ".")
