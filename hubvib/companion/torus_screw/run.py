"""One run of the torus screw gear model (seed 002), what ``hubvib torus-screw`` prints:
an operating point (the paper's by default) with the paper comparison and claims, or a
sweep over a lift table; its ``data`` is the ``--json`` object, its ``text`` the report.
SI units inside (N, m, N m, rad); angles in degrees only at the edges."""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import hubvib.companion.torus_screw.report as report
from hubvib.companion.torus_screw.nx_scatter import PAPER_NX
from hubvib.companion.torus_screw.gear import (FINGER_KINDS, OperatingPoint, PAPER_ALPHA1_DEG,
                                          PAPER_ALPHA3_DEG, PAPER_PHI2_DEG, TorusScrewGear,
                                          finger_angle, roller_forces)
from hubvib.companion.torus_screw.paper import claims, compare, is_paper_input, paper_forces
from hubvib.companion.torus_screw.sweep import eta_figure, read_lift_table, sweep
from hubvib.foundation.output import save_figure, write_csv, written_line


@dataclass(frozen=True)
class TorusScrewRun:
    """``data``: the ``--json`` object; ``text``: the printed report; ``files`` written."""

    data: dict
    text: str
    files: tuple[Path, ...]


def run_torus_screw(gear: TorusScrewGear, fingers: str = "both", finger_spacing: float = 0.010,
                    input_speed_rpm: float = 0.0, inertia_moment: float = 0.0,
                    angles_deg=(None, None, None), lift_table: Path | None = None,
                    out: Path | None = None) -> TorusScrewRun:
    """Solve the gear at one operating point (``angles_deg`` = alpha1, alpha3, phi2 [deg];
    None: the paper's) or over a lift table, for ``fingers`` ("cylindrical", "spherical"
    or "both"); write the CSV (and for a sweep the eta plot) into ``out`` if given.

    ``ValueError`` names the option: a finger that does not fit, or a lift table given with
    angles."""
    kinds = FINGER_KINDS if fingers == "both" else (fingers,)
    for kind in kinds:
        finger_angle(kind, gear, finger_spacing)
    phi4 = gear.centrifugal_force_n(input_speed_rpm)
    if lift_table is not None:
        if any(a is not None for a in angles_deg):
            raise ValueError("--lift-table gives the angles; drop --alpha1-deg, --alpha3-deg "
                             "and --phi2-deg")
        rows = sweep(gear, read_lift_table(lift_table), kinds, finger_spacing, phi4,
                     inertia_moment)
        files = _write_sweep(out, rows) if out else []
        data = {"source": report.SOURCE, "gear": gear.to_dict(),
                "finger_spacing_m": finger_spacing, "sweep": [r.to_dict() for r in rows],
                "files": [str(f) for f in files]}
        text = [report.format_header(gear, rows[0].point), report.format_sweep(rows)]
        return TorusScrewRun(data, "\n".join(text + _files_text(files)), tuple(files))

    defaults = (PAPER_ALPHA1_DEG, PAPER_ALPHA3_DEG, PAPER_PHI2_DEG)
    a1, a3, phi2 = (d if a is None else a for a, d in zip(angles_deg, defaults))
    point = OperatingPoint(math.radians(a1), math.radians(a3), math.radians(phi2), phi4,
                           inertia_moment)
    results = tuple(roller_forces(gear, point, kind, finger_spacing) for kind in kinds)
    paper = is_paper_input(gear, point, finger_spacing)
    cells = {r.fingers: compare(r) for r in results} if paper else None
    printed = _printed_variant(gear, point)
    reference = paper_forces()
    checked = claims(reference["cylindrical"], reference["spherical"])
    files = [write_csv(out / "torus_screw_forces.csv", [r.to_dict() for r in results])] \
        if out else []
    data = {
        "source": report.SOURCE, "gear": gear.to_dict(), "roller_load_n": gear.roller_load_n,
        "operating_point": point.to_dict(), "finger_spacing_m": finger_spacing,
        "results": [r.to_dict() for r in results], "paper_inputs": paper,
        "paper_comparison": None if cells is None
        else [c.to_dict() for group in cells.values() for c in group],
        "printed_sign_variant_cylindrical": printed and printed.to_dict(),
        "claims": [c.to_dict() for c in checked],
        "nx": [f.to_dict() for f in PAPER_NX], "files": [str(f) for f in files]}
    text = [report.format_header(gear, point), report.format_point(point), "",
            report.format_comparison(results, cells, finger_spacing)]
    if printed is not None:
        text.append(f"with the print's signs, cylindrical S2'' = {printed.s2pp_n:.2f} N and "
                    f"N1 = {printed.n1_n:.2f} N (fixed signs: see above)")
    text.append("")
    text.append(report.format_claims(checked) if paper else
                "(paper comparison and claims apply to the paper's inputs only: run without "
                "overriding options to see them)")
    text += ["", report.format_nx()]
    return TorusScrewRun(data, "\n".join(text + _files_text(files)), tuple(files))


def _printed_variant(gear, point):
    """The cylindrical case with the print's sign slips, or None if that system is singular."""
    try:
        return roller_forces(gear, point, "cylindrical", printed_signs=True)
    except ValueError:
        return None


def _files_text(files) -> list[str]:
    return ["\n" + written_line(files)] if files else []


def _write_sweep(out: Path, rows) -> list[Path]:
    flat = [{**r.point.to_dict(), **f.to_dict()} for r in rows for f in r.forces]
    return [write_csv(out / "torus_screw_sweep.csv", flat),
            save_figure(eta_figure(rows), out / "torus_screw_eta_phi2.png")]
