"""Why the two ring models' spectra differ: the rigid-ring (9 + 3N) model's table values
against the FE ring's, and the band in which the rigid model holds (SI).

The rigid-ring model takes the ring's mass, rotational inertia and mounting from the
design's lumped table; the elastic model's FE ring has its own (its geometry's mass and
inertia, a foundation sized to the table's c_r and c_ru).  The validity band
(:mod:`.validity`) compares the elastic model with a rigid ring of the FE ring's mass and
mounting, so a table that differs from the FE ring moves the rigid model's modes even
inside that band: :func:`model_differences` puts the numbers side by side.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .options import ElasticOptions

__all__ = ["ModelDifferences", "model_differences", "cached_model_differences"]


@dataclass(frozen=True)
class ModelDifferences:
    """The rigid-ring model's table against the FE ring, one design and mounting.

    ``*_table``: the design's lumped table (what ``--ring rigid`` uses); ``*_fe``: the FE
    ring's rigid motions.  Masses [kg]; inertia [kg m^2] about the ring's centre;
    ``mu_r`` = inertia / r_b^2 [kg] (the lumped model's reduced mass, r_b the ring's base
    radius [m]); ``c_r`` [N/m] the mounting against translation (mean of x and y),
    ``c_ru`` [N/m] against rotation reduced to r_b.  ``mode1_*`` [Hz]: the lowest mode of
    the table's rigid model, of the rigid model with the FE ring's mass and mounting (the
    validity band's, NaN without a band) and of the elastic model.  ``band_top_hz``: the
    rigid model holds below it (inf: over the compared band; NaN: no band, ``band_reason``
    says why)."""

    design: str
    mounting: str
    base_radius: float
    ring_mass_table: float
    ring_mass_fe: float
    mu_r_table: float
    mu_r_fe: float
    c_r_table: float
    c_r_fe: float
    c_ru_table: float
    c_ru_fe: float
    mode1_table_hz: float
    mode1_fe_rigid_hz: float
    mode1_elastic_hz: float
    band_top_hz: float
    band_reason: str
    compared_to_hz: float
    carrier_tooth: int

    @property
    def inertia_table(self) -> float:
        """[kg m^2]"""
        return self.mu_r_table * self.base_radius ** 2

    @property
    def inertia_fe(self) -> float:
        """[kg m^2]"""
        return self.mu_r_fe * self.base_radius ** 2

    def to_dict(self) -> dict:
        """JSON-ready (SI; NaN and inf as None)."""
        from hubvib.foundation.output import finite_or_none

        def pair(table, fe) -> dict:
            return {"rigid_ring_table": finite_or_none(table), "fe_ring": finite_or_none(fe)}

        return {
            "mounting": self.mounting, "ring_base_radius_m": self.base_radius,
            "ring_mass_kg": pair(self.ring_mass_table, self.ring_mass_fe),
            "ring_inertia_kg_m2": pair(self.inertia_table, self.inertia_fe),
            "ring_mu_r_kg": pair(self.mu_r_table, self.mu_r_fe),
            "c_r_N_m": pair(self.c_r_table, self.c_r_fe),
            "c_ru_N_m": pair(self.c_ru_table, self.c_ru_fe),
            "mode_1_hz": {"rigid_ring_table": finite_or_none(self.mode1_table_hz),
                          "rigid_ring_fe_mass_and_mounting": finite_or_none(self.mode1_fe_rigid_hz),
                          "elastic_ring": finite_or_none(self.mode1_elastic_hz)},
            "validity_band": {"rigid_ring_holds_below_hz": finite_or_none(self.band_top_hz),
                              "compared_to_hz": self.compared_to_hz,
                              "carrier_tooth": self.carrier_tooth, "reason": self.band_reason}}

    def lines(self) -> list[str]:
        """The comparison as printed beside a spectrum (plain text)."""
        def row(name, table, fe, unit="", fmt="{}") -> str:
            return (f"  {name:<34} {(fmt.format(table) + ' ' + unit).strip():>18} "
                    f"{(fmt.format(fe) + ' ' + unit).strip():>18}")

        where = {"foundation": "foundation totals", "clamped": "clamped arcs",
                 "free": "free"}.get(self.mounting, self.mounting)
        out = [f"why the two ring models differ ({self.design}):",
               row("", "rigid ring table", "FE ring"),
               row("ring mass m_r", self.ring_mass_table, self.ring_mass_fe, "kg", "{:.3f}"),
               row("ring inertia I", self.inertia_table, self.inertia_fe, "kg m^2", "{:.4f}"),
               row("  as mu_r = I / r_b^2", self.mu_r_table, self.mu_r_fe, "kg", "{:.2f}"),
               row(f"mounting c_r ({where})", self.c_r_table, self.c_r_fe, "N/m", "{:.4g}"),
               row(f"mounting c_ru ({where})", self.c_ru_table, self.c_ru_fe, "N/m", "{:.4g}")]
        fe_rigid = ("" if not math.isfinite(self.mode1_fe_rigid_hz) else
                    f", {self.mode1_fe_rigid_hz:.1f} Hz with the FE ring's mass and mounting")
        out.append(f"  mode 1: {self.mode1_table_hz:.1f} Hz rigid with the table's ring"
                   f"{fe_rigid}, {self.mode1_elastic_hz:.1f} Hz elastic")
        if math.isnan(self.band_top_hz):
            out.append(f"  validity band: {self.band_reason}")
        else:
            top = (f"{self.band_top_hz:.0f} Hz" if math.isfinite(self.band_top_hz) else
                   f"the top of the compared band, {self.compared_to_hz:.0f} Hz")
            out.append(f"  the rigid-ring model (with the FE ring's mass and mounting) holds "
                       f"below {top}: there {self.band_reason}")
        return out


def model_differences(design, options: ElasticOptions = ElasticOptions(),
                      carrier_tooth: int | None = None, er=None) -> ModelDifferences:
    """The comparison for ``design`` on the mounting of ``options``; ``carrier_tooth``:
    planet 1's ring tooth for the band and the elastic mode 1 (default half a planet
    pitch from tooth 0, the crack study's intact position); ``er``: the intact
    ``ElasticRing`` of ``design`` on ``options`` coupled to its lumped table, its basis
    built with ``carrier_tooth`` (else built here)."""
    from hubvib.lumped import natural_modes
    from hubvib.reducer.stages import lumped_parameters

    from .model import elastic_ring, elastic_spectrum, out_of_contact_tooth
    from .validity import validity_band, validity_record

    table = lumped_parameters(design)
    if carrier_tooth is None:
        from hubvib.reducer.stages import ring_gear

        carrier_tooth = out_of_contact_tooth(ring_gear(design).teeth, design.n_planets)
    if er is None:
        er = elastic_ring(design, options=options, carrier_teeth=(carrier_tooth,),
                          params=table)
    body, r_b = er.body, er.body.base_radius
    mass, stiffness = body.rigid_mass(), body.rigid_stiffness()
    if options.mounting == "free":
        stiffness = 0.0 * stiffness  # no mounting: round-off of K's rigid-motion null space
    elastic_hz = float(elastic_spectrum(er, carrier_tooth).frequency_hz[0])
    fe_rigid_hz, top, reason = math.nan, math.nan, ""
    if options.mounting == "free":
        reason = ("not computed on a free ring (no mounting: the rigid model's ring would "
                  "float); use --mounting foundation or clamped")
    else:
        band = validity_band(design, options, carrier_tooth=carrier_tooth, er=er)
        first = band.paired[0]
        fe_rigid_hz, top = first.rigid_hz, band.band_top_hz
        reason = validity_record(band)["reason"]
        if math.isfinite(first.elastic_hz):  # the coupled mode paired with it by shape
            elastic_hz = first.elastic_hz
    return ModelDifferences(
        design.name, options.mounting, float(r_b),
        float(table.m_r), float(0.5 * (mass[0, 0] + mass[1, 1])),
        float(table.mu_r), float(mass[2, 2] / r_b ** 2),
        float(table.c_r), float(0.5 * (stiffness[0, 0] + stiffness[1, 1])),
        float(table.c_ru), float(stiffness[2, 2] / r_b ** 2),
        float(natural_modes(table).frequency_hz[0]), float(fe_rigid_hz), elastic_hz,
        float(top), reason, float(options.band_hz), int(carrier_tooth))


def cached_model_differences(design, options: ElasticOptions = ElasticOptions()
                             ) -> ModelDifferences:
    """:func:`model_differences` through the result cache (design, options, source)."""
    from hubvib.runtime.result_cache import cached_result

    return cached_result("model-differences", (design.fingerprint(), options), (__name__,),
                         lambda: model_differences(design, options), ModelDifferences)
