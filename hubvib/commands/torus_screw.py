"""``hubvib torus-screw``: forces and efficiency of the planetary torus screw gear (seed 002)."""
from __future__ import annotations

import json
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
    p.add_argument("--finger-spacing", type=float, default=None, metavar="S4",
                   help="S4, height of the spherical finger's contact part [m], > 0 (default "
                        "0.010 = 2 r4, back-solved from the paper's spherical N3); with "
                        "--fingers spherical or both")
    for flag, _, default, text in _GEAR_OPTIONS:
        p.add_argument(flag, type=float, default=default, help=f"{text} (paper: {default:g})")
    p.add_argument("--input-speed-rpm", type=float, default=0.0,
                   help="input speed n1 [min^-1] for the centrifugal force Phi4 (default 0)")
    p.add_argument("--inertia-moment", type=float, default=0.0,
                   help="inertia moment M_U of the roller [N m] (default 0, quasi-static)")
    p.add_argument("--out", type=Path, metavar="DIR",
                   help="write the results (CSV) and, for a sweep, eta against phi2 (PNG)")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.companion.torus_screw.gear import TorusScrewGear
    from hubvib.companion.torus_screw.gear import PAPER_FINGER_SPACING_M
    from hubvib.companion.torus_screw.run import run_torus_screw

    from ._applies import refuse_ignored, value

    gear = TorusScrewGear(**{field: getattr(args, flag[2:].replace("-", "_"))
                             for flag, field, _, _ in _GEAR_OPTIONS})
    refuse_ignored(args, (("--finger-spacing", args.fingers != "cylindrical",
                           "to spherical fingers (--fingers spherical or both)"),))
    spacing = value(args, "--finger-spacing", PAPER_FINGER_SPACING_M)
    result = run_torus_screw(gear, args.fingers, spacing, args.input_speed_rpm,
                             args.inertia_moment,
                             (args.alpha1_deg, args.alpha3_deg, args.phi2_deg),
                             args.lift_table, args.out)
    print(json.dumps(result.data, indent=2, allow_nan=False) if args.json else result.text)
    return 0
