"""``hubvib torus-screw``: forces and efficiency of the planetary torus screw gear (seed 002)."""
from __future__ import annotations

import json
import math
from pathlib import Path

_GEAR_OPTIONS = (  # flag, field, default, help
    ("--torque", "output_torque_n_m", 150.0, "output torque M2 [N m], > 0"),
    ("--rollers", "rollers", 7.0, "number of composite rollers n_p, whole number >= 1"),
    ("--ratio", "ratio", 48.0, "gear ratio u, > 0"),
    ("--carrier-radius", "carrier_radius_m", 0.025, "R2 [m], > 0"),
    ("--roller-length", "roller_length_m", 0.028, "l4 [m], > 0"),
    ("--finger-radius", "finger_radius_m", 0.005, "r4, finger contact radius [m], > 0"),
    ("--finger-journal-radius", "finger_journal_radius_m", 0.0035, "r0 [m], > 0"),
    ("--roller-journal-radius", "roller_journal_radius_m", 0.005, "r42 [m], > 0"),
    ("--roller-mass", "roller_mass_kg", 0.075, "m4 [kg], >= 0"),
    ("--rolling-friction", "rolling_friction", 0.002, "delta_r, [0, 1)"),
    ("--sliding-friction", "sliding_friction", 0.05, "delta_c, [0, 1)"),
)


def add_parser(sub) -> None:
    p = sub.add_parser("torus-screw", help="forces on a composite roller and efficiency of the "
                                           "planetary torus screw gear (seed 002)")
    p.add_argument("--fingers", choices=["cylindrical", "spherical", "both"], default="both",
                   help="finger shape(s) to solve (default both, side by side)")
    p.add_argument("--alpha1-deg", type=float, metavar="A",
                   help="lift angle of the driving spiral, (0, 90) deg (default 6.804, "
                        "back-solved from the paper's cylindrical case)")
    p.add_argument("--alpha3-deg", type=float, metavar="B",
                   help="lift angle of the fixed grooves, (0, 90) deg (default 81.945)")
    p.add_argument("--phi2-deg", type=float, metavar="P",
                   help="roller angle phi2 [deg] (default 54)")
    p.add_argument("--lift-table", type=Path, metavar="FILE.csv",
                   help="sweep: CSV with columns phi2_deg, alpha1_deg, alpha3_deg")
    p.add_argument("--finger-spacing", type=float, default=0.010, metavar="S4",
                   help="S4, height of the spherical finger's contact part [m], > 0 (default "
                        "0.010 = 2 r4, back-solved from the paper's spherical N3)")
    for flag, _, default, text in _GEAR_OPTIONS:
        p.add_argument(flag, type=float, default=default, help=f"{text} (paper: {default:g})")
    p.add_argument("--input-speed-rpm", type=float, default=0.0,
                   help="input speed n1 [min^-1] for the centrifugal force Phi4 (default 0)")
    p.add_argument("--inertia-moment", type=float, default=0.0,
                   help="inertia moment M_U of the roller [N m] (default 0, quasi-static)")
    p.add_argument("--out", type=Path, metavar="DIR",
                   help="write the results (CSV) and, for a sweep, eta against phi2 (PNG)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.companion import torus_screw_report as report
    from hubvib.companion.nx_scatter import PAPER_NX
    from hubvib.companion.torus_screw import (FINGER_KINDS, PAPER_ALPHA1_DEG, PAPER_ALPHA3_DEG,
                                              PAPER_PHI2_DEG, OperatingPoint, TorusScrewGear,
                                              finger_angle, roller_forces)
    from hubvib.companion.torus_screw_paper import claims, compare, is_paper_input, paper_forces
    from hubvib.companion.torus_screw_sweep import read_lift_table, sweep

    gear = TorusScrewGear(**{field: getattr(args, flag[2:].replace("-", "_"))
                             for flag, field, _, _ in _GEAR_OPTIONS})
    kinds = FINGER_KINDS if args.fingers == "both" else (args.fingers,)
    for kind in kinds:
        finger_angle(kind, gear, args.finger_spacing)
    phi4 = gear.centrifugal_force_n(args.input_speed_rpm)
    angles = (args.alpha1_deg, args.alpha3_deg, args.phi2_deg)
    if args.lift_table is not None:
        if any(a is not None for a in angles):
            raise ValueError("--lift-table gives the angles; drop --alpha1-deg, --alpha3-deg "
                             "and --phi2-deg")
        rows = sweep(gear, read_lift_table(args.lift_table), kinds, args.finger_spacing, phi4,
                     args.inertia_moment)
        files = _write_sweep(args.out, rows) if args.out else []
        if args.json:
            _print_json({"source": report.SOURCE, "gear": gear.to_dict(),
                         "finger_spacing_m": args.finger_spacing,
                         "sweep": [r.to_dict() for r in rows], "files": [str(f) for f in files]})
            return 0
        print(report.format_header(gear, rows[0].point))
        print(report.format_sweep(rows))
        _print_files(files)
        return 0

    a1, a3, phi2 = (PAPER_ALPHA1_DEG if angles[0] is None else angles[0],
                    PAPER_ALPHA3_DEG if angles[1] is None else angles[1],
                    PAPER_PHI2_DEG if angles[2] is None else angles[2])
    point = OperatingPoint(math.radians(a1), math.radians(a3), math.radians(phi2), phi4,
                           args.inertia_moment)
    results = tuple(roller_forces(gear, point, kind, args.finger_spacing) for kind in kinds)
    paper = is_paper_input(gear, point, args.finger_spacing)
    cells = {r.fingers: compare(r) for r in results} if paper else None
    printed = _printed_variant(gear, point)
    reference = paper_forces()
    checked = claims(reference["cylindrical"], reference["spherical"])
    files = _write_point(args.out, results) if args.out else []
    if args.json:
        _print_json({
            "source": report.SOURCE, "gear": gear.to_dict(), "roller_load_n": gear.roller_load_n,
            "operating_point": point.to_dict(), "finger_spacing_m": args.finger_spacing,
            "results": [r.to_dict() for r in results], "paper_inputs": paper,
            "paper_comparison": None if cells is None
            else [c.to_dict() for group in cells.values() for c in group],
            "printed_sign_variant_cylindrical": printed and printed.to_dict(),
            "claims": [c.to_dict() for c in checked],
            "nx": [f.to_dict() for f in PAPER_NX], "files": [str(f) for f in files]})
        return 0
    print(report.format_header(gear, point))
    print(report.format_point(point))
    print()
    print(report.format_comparison(results, cells, args.finger_spacing))
    if printed is not None:
        print(f"with the print's signs, cylindrical S2'' = {printed.s2pp_n:.2f} N and N1 = "
              f"{printed.n1_n:.2f} N (fixed signs: see above)")
    print()
    if paper:
        print(report.format_claims(checked))
    else:
        print("(paper comparison and claims apply to the paper's inputs only: run without "
              "overriding options to see them)")
    print()
    print(report.format_nx())
    _print_files(files)
    return 0


def _printed_variant(gear, point):
    """The cylindrical case with the print's sign slips, or None if that system is singular."""
    from hubvib.companion.torus_screw import roller_forces

    try:
        return roller_forces(gear, point, "cylindrical", printed_signs=True)
    except ValueError:
        return None


def _print_json(data: dict) -> None:
    print(json.dumps(data, indent=2, allow_nan=False))


def _print_files(files) -> None:
    if files:
        print(f"\nwritten: {', '.join(str(f) for f in files)}")


def _write_point(out: Path, results) -> list[Path]:
    from hubvib.foundation.output import write_csv

    return [write_csv(out / "torus_screw_forces.csv", [r.to_dict() for r in results])]


def _write_sweep(out: Path, rows) -> list[Path]:
    from hubvib.companion.torus_screw_sweep import eta_figure
    from hubvib.foundation.output import save_figure, write_csv

    flat = [{**r.point.to_dict(), **f.to_dict()} for r in rows for f in r.forces]
    return [write_csv(out / "torus_screw_sweep.csv", flat),
            save_figure(eta_figure(rows), out / "torus_screw_eta_phi2.png")]
