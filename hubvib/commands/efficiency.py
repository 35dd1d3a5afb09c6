"""``hubvib efficiency``: efficiency and optimal geometry of ball/roller planetary gears."""
from __future__ import annotations

import json
import math
from pathlib import Path

from hubvib.foundation.output import written_line


#: the paper's satellite diameters [mm], the defaults of --ball-diameter-mm, --roller-diameter-mm
PAPER_DIAMETER_MM = {"ball": 15.0, "roller": 10.0}
#: the paper's input power [W], the default of --input-power-w
PAPER_INPUT_POWER_W = 1500.0


def add_parser(sub) -> None:
    p = sub.add_parser("efficiency", help="efficiency-optimal lift angle, R and A of "
                                          "ball/roller planetary gears (seed 001)")
    p.add_argument("--ratio", type=float, nargs="+", metavar="I",
                   help="gear ratio(s) i = z2 + 1, whole numbers >= 2")
    p.add_argument("--alpha1-deg", type=float, metavar="A",
                   help="evaluate at this driving-track lift angle, in (0, 90) deg "
                        "(default: the whole-degree optimum)")
    p.add_argument("--satellite", choices=["ball", "roller", "both"], default="both",
                   help="satellite type(s) whose R and A are reported (default both)")
    p.add_argument("--ball-diameter-mm", type=float, default=None, metavar="MM",
                   help="ball diameter d_c [mm], > 0 (paper: 15); with --satellite ball or both")
    p.add_argument("--roller-diameter-mm", type=float, default=None, metavar="MM",
                   help="roller diameter d_c [mm], > 0 (paper: 10); with --satellite roller "
                        "or both")
    p.add_argument("--f1", type=float, default=0.004,
                   help="friction, rolling on the driving track, [0, 1) (paper: 0.004)")
    p.add_argument("--f2", type=float, default=0.05,
                   help="friction, rolling with sliding on the fixed track, [0, 1) (paper: 0.05)")
    p.add_argument("--f3", type=float, default=0.1,
                   help="friction, sliding in the carrier slots, [0, 1) (paper: 0.1)")
    p.add_argument("--input-power-w", type=float, default=None, metavar="W",
                   help="input power W1 for the link losses [W] (paper: 1500); with --table "
                        "only for --json or --out (the printed table has no link losses)")
    p.add_argument("--table", action="store_true",
                   help="recompute the paper's table for i = 5..30 and compare it")
    p.add_argument("--curve", action="store_true", default=None,
                   help="also print the loss terms against alpha1 = 1..30 deg (not with "
                        "--table or --json: the JSON holds the curves anyway)")
    p.add_argument("--out", type=Path, metavar="DIR",
                   help="write plots (PNG) and the alpha1 curves (CSV) here")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    import hubvib.companion.efficiency.report as report
    from hubvib.companion.efficiency.core import Friction
    from hubvib.companion.efficiency.design import gear_design
    from hubvib.companion.efficiency.table import PAPER_RATIOS, paper_table
    from hubvib.companion.efficiency.track_geometry import check_alpha1, check_diameter
    from hubvib.companion.efficiency.output import design_with_curve, write_efficiency_files

    from ._applies import refuse_ignored, value

    refuse_ignored(args, (
        ("--ball-diameter-mm", args.satellite in ("ball", "both"),
         "to ball satellites (--satellite ball or both)"),
        ("--roller-diameter-mm", args.satellite in ("roller", "both"),
         "to roller satellites (--satellite roller or both)"),
        ("--curve", not args.table and not args.json,
         "to the printed report of one or more ratios (not --table; --json holds the curves)"),
        ("--input-power-w", not args.table or args.json or args.out is not None,
         "to the designs' link losses: without --table, or with --json or --out")))
    input_power = value(args, "--input-power-w", PAPER_INPUT_POWER_W)
    friction = Friction(args.f1, args.f2, args.f3)
    satellites = {name: check_diameter(name, value(args, f"--{name}-diameter-mm",
                                                   PAPER_DIAMETER_MM[name]) * 1e-3)
                  for name in ("ball", "roller") if args.satellite in (name, "both")}
    if args.table and args.alpha1_deg is not None:
        raise ValueError("--alpha1-deg cannot be combined with --table (the table is at the "
                         "optimal alpha1)")
    if not args.table and not args.ratio:
        raise ValueError("--ratio is required (whole numbers >= 2) unless --table is given")
    ratios = tuple(args.ratio) if args.ratio else PAPER_RATIOS
    alpha1 = None if args.alpha1_deg is None else check_alpha1(math.radians(args.alpha1_deg))
    if args.table:
        table = paper_table(ratios, friction, satellites)
        designs = tuple(gear_design(i, friction, None, satellites, input_power)
                        for i in ratios)
    else:
        designs = tuple(gear_design(i, friction, alpha1, satellites, input_power)
                        for i in ratios)
    files = write_efficiency_files(args.out, designs) if args.out else []
    if args.json:
        data = {"source": report.SOURCE, "designs": [design_with_curve(d) for d in designs]}
        if args.table:
            data["table"] = [c.to_dict() for c in table.cells]
        data["files"] = [str(f) for f in files]
        print(json.dumps(data, indent=2, allow_nan=False))
        return 0
    if args.table:
        print(report.format_table(table))
    elif len(designs) == 1:
        print(report.format_design(designs[0], curve=args.curve))
    else:
        print(report.format_designs(designs))
        if args.curve:
            for d in designs:
                print("\n" + report.format_curve(d))
    if files:
        print("\n" + written_line(files))
    return 0

