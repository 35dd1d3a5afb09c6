"""The paper's table of optimal geometry (seed 001), recomputed and compared cell by cell.

The computed table comes from the equations only (:func:`gear_design` per ratio);
``PUBLISHED`` holds the printed table of Kapitonov 2024 ("Table. Geometrics providing the
greatest efficiency of planetary ball and roller gears", d_c = 15 mm balls, 10 mm rollers) for
the comparison. One printed cell is a slip: alpha2 at i = 15 reads "14", the value of z2 beside
it; eq. (11) gives 36.2678 deg.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from hubvib.companion.efficiency.core import Friction
from hubvib.companion.efficiency.design import GearDesign, gear_design
from hubvib.companion.efficiency.track_geometry import SATELLITE_DIAMETER_M

#: Ratios of the paper's table and Figs. 7-9.
PAPER_RATIOS = (5, 10, 15, 20, 25, 30)

#: The printed table, quantity -> values for PAPER_RATIOS (angles [deg], lengths [mm]).
PUBLISHED = {
    "alpha1_deg": (9, 5, 3, 3, 2, 2),
    "alpha2_deg": (32.3558, 38.2168, 14, 44.8779, 39.9663, 45.3616),
    "z2": (4, 9, 14, 19, 24, 29),
    "R_ball_mm": (14.92564, 40.69789, 60.10152, 102.8505, 114.5504, 159.0755),
    "A_ball_mm": (2.334885, 3.547055, 3.14547, 5.382782, 3.997752, 5.551653),
    "R_roller_mm": (9.950427, 27.13193, 40.06768, 68.56703, 76.36695, 106.0503),
    "A_roller_mm": (1.55659, 2.364703, 2.09698, 3.588521, 2.665168, 3.701102),
}

#: The paper's headline (text and Fig. 9): the highest efficiency, 85.3 % at i = 5.
PUBLISHED_ETA_PERCENT = {5: 85.3}

#: Printed cells known to be slips, (quantity, ratio) -> explanation.
PRINT_SLIPS = {("alpha2_deg", 15): "the paper prints 14, the z2 beside it"}

#: Agreement tolerances: relative for R and A (seed reference: 1e-5), absolute otherwise
#: (half a unit of the last printed digit).
TOLERANCE = {"alpha1_deg": ("abs", 0.0), "alpha2_deg": ("abs", 5e-5), "z2": ("abs", 0.0),
             "R_ball_mm": ("rel", 1e-5), "A_ball_mm": ("rel", 1e-5),
             "R_roller_mm": ("rel", 1e-5), "A_roller_mm": ("rel", 1e-5),
             "eta_percent": ("abs", 0.05)}


@dataclass(frozen=True)
class TableCell:
    """One computed cell beside the printed one.

    Attributes
    ----------
    quantity : str
        Row name with its unit, e.g. ``"R_ball_mm"``.
    ratio : int
        Column (gear ratio).
    computed, published : float
        Value from the equations and as printed (``published`` is None when not printed).
    kind, tolerance : str, float
        ``"rel"`` or ``"abs"`` and the agreement tolerance.
    slip : str
        Explanation when the printed cell is a known print slip, else ``""``.
    """

    quantity: str
    ratio: int
    computed: float
    published: float | None
    kind: str
    tolerance: float
    slip: str = ""

    @property
    def deviation(self) -> float | None:
        """Computed minus printed: relative for ``kind == "rel"``, else absolute."""
        if self.published is None:
            return None
        diff = self.computed - self.published
        return diff / abs(self.published) if self.kind == "rel" else diff

    @property
    def agrees(self) -> bool | None:
        """Within the tolerance (None when nothing is printed)."""
        if self.published is None:
            return None
        return abs(self.deviation) <= self.tolerance * (1 + 1e-9) + 1e-12

    def to_dict(self) -> dict:
        return {"quantity": self.quantity, "ratio": self.ratio, "computed": self.computed,
                "published": self.published, "deviation": self.deviation,
                "deviation_kind": self.kind, "tolerance": self.tolerance,
                "agrees": self.agrees, "print_slip": self.slip or None}


@dataclass(frozen=True)
class PaperTable:
    """Designs for the paper's ratios and each cell against the printed table."""

    designs: tuple[GearDesign, ...]
    cells: tuple[TableCell, ...]

    def disagreements(self) -> tuple[TableCell, ...]:
        """Cells outside their tolerance (the known print slip among them)."""
        return tuple(c for c in self.cells if c.agrees is False)

    def to_dict(self) -> dict:
        return {"designs": [d.to_dict() for d in self.designs],
                "cells": [c.to_dict() for c in self.cells]}


def table_values(design: GearDesign) -> dict[str, float]:
    """The table's quantities for one design, in the paper's units (deg, mm, %)."""
    values = {"alpha1_deg": math.degrees(design.at.alpha1_rad),
              "alpha2_deg": math.degrees(design.at.alpha2_rad), "z2": float(design.at.z2)}
    for track in design.tracks:
        values[f"R_{track.satellite}_mm"] = track.mean_radius_m * 1e3
        values[f"A_{track.satellite}_mm"] = track.amplitude_m * 1e3
    values["eta_percent"] = design.at.eta * 100.0
    return values


def paper_table(ratios=PAPER_RATIOS, friction: Friction = Friction(),
                satellites: dict[str, float] | None = None) -> PaperTable:
    """Recompute the table for ``ratios`` at each whole-degree optimum and compare it.

    The printed values are set beside the computed ones only for the paper's friction
    coefficients, ratios and satellite diameters; otherwise ``published`` is None.
    """
    chosen = SATELLITE_DIAMETER_M if satellites is None else satellites
    designs = tuple(gear_design(i, friction, None, chosen) for i in ratios)
    comparable = friction == Friction()
    cells = []
    for design in designs:
        for quantity, value in table_values(design).items():
            satellite = quantity.split("_")[1] if quantity[:2] in ("R_", "A_") else None
            same = satellite is None or chosen[satellite] == SATELLITE_DIAMETER_M.get(satellite)
            published = _published(quantity, design.ratio) if comparable and same else None
            kind, tol = TOLERANCE.get(quantity, ("rel", 1e-5))
            cells.append(TableCell(quantity, design.ratio, value,
                                   None if published is None else float(published), kind, tol,
                                   PRINT_SLIPS.get((quantity, design.ratio), "")))
    return PaperTable(designs, tuple(cells))


def _published(quantity: str, ratio: int) -> float | None:
    if quantity == "eta_percent":
        return PUBLISHED_ETA_PERCENT.get(ratio)
    if quantity in PUBLISHED and ratio in PAPER_RATIOS:
        return PUBLISHED[quantity][PAPER_RATIOS.index(ratio)]
    return None
