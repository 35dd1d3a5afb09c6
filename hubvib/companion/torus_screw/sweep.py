"""Torus screw gear forces and efficiency against the roller angle phi2 (seed 002, Fig. 4).

The lift angles alpha1, alpha3 change with phi2, but the paper does not print the spiral radii
r, R its eqs. (1)-(5) need; so a sweep takes them as a table ``phi2_deg, alpha1_deg,
alpha3_deg`` (CSV with that header, one operating point per line) and solves eq. (19) at each
row.
"""
from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

from hubvib.foundation.files import read_text

from hubvib.companion.torus_screw.gear import (PAPER_FINGER_SPACING_M, OperatingPoint, RollerForces, TorusScrewGear,
                          roller_forces)

LIFT_TABLE_COLUMNS = ("phi2_deg", "alpha1_deg", "alpha3_deg")


@dataclass(frozen=True)
class SweepRow:
    """Solutions for each finger shape at one operating point."""

    point: OperatingPoint
    forces: tuple[RollerForces, ...]

    def to_dict(self) -> dict:
        return {**self.point.to_dict(), "fingers": [f.to_dict() for f in self.forces]}


def read_lift_table(path: Path) -> tuple[tuple[float, float, float], ...]:
    """Rows ``(phi2, alpha1, alpha3)`` [deg] of a CSV lift table.

    Raises
    ------
    ValueError
        Missing file or columns, a non-numeric or non-finite cell, or no rows.
    """
    path = Path(path)
    text = read_text(path, "lift table (--lift-table)", ValueError, kind="CSV")
    with io.StringIO(text, newline="") as handle:
        reader = csv.DictReader(handle)
        missing = [c for c in LIFT_TABLE_COLUMNS if c not in (reader.fieldnames or [])]
        if missing:
            raise ValueError(f"lift table (--lift-table) {path}: needs the columns "
                             f"{', '.join(LIFT_TABLE_COLUMNS)}; missing {', '.join(missing)}")
        rows = []
        for line, record in enumerate(reader, start=2):
            try:
                values = tuple(float(record[c]) for c in LIFT_TABLE_COLUMNS)
            except (TypeError, ValueError):
                raise ValueError(f"lift table (--lift-table) {path} line {line}: every cell "
                                 f"must be a number, got {dict(record)}") from None
            if not all(math.isfinite(v) for v in values):
                raise ValueError(f"lift table (--lift-table) {path} line {line}: "
                                 f"cells must be finite, got {values}")
            rows.append(values)
    if not rows:
        raise ValueError(f"lift table (--lift-table) {path}: no rows")
    return tuple(rows)


def sweep(gear: TorusScrewGear, table, fingers=("cylindrical", "spherical"),
          finger_spacing_m: float = PAPER_FINGER_SPACING_M, centrifugal_force_n: float = 0.0,
          inertia_moment_n_m: float = 0.0) -> tuple[SweepRow, ...]:
    """Solve eq. (19) at each ``(phi2, alpha1, alpha3)`` [deg] row for each finger shape."""
    out = []
    for phi2, alpha1, alpha3 in table:
        point = OperatingPoint(math.radians(alpha1), math.radians(alpha3), math.radians(phi2),
                               centrifugal_force_n, inertia_moment_n_m)
        out.append(SweepRow(point, tuple(roller_forces(gear, point, kind, finger_spacing_m)
                                         for kind in fingers)))
    return tuple(out)


def eta_figure(rows: tuple[SweepRow, ...]):
    """eta against phi2 for each finger shape (the paper's Fig. 4); matplotlib, Agg."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    phi2 = [math.degrees(r.point.phi2_rad) for r in rows]
    for k, forces in enumerate(rows[0].forces):
        eta = [math.nan if r.forces[k].eta is None else r.forces[k].eta for r in rows]
        ax.plot(phi2, eta, marker="o", label=f"{forces.fingers} fingers")
    ax.set_xlabel("roller angle phi2 [deg]")
    ax.set_ylabel("efficiency eta = M2 / (M1 u) [-]")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return fig
