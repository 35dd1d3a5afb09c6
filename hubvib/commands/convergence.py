"""``hubvib convergence QUANTITY --out DIR``: error against run time (CSV + log-log plot)."""
from __future__ import annotations

import csv
import math
import sys
from pathlib import Path

from hubvib.foundation.output import json_text, locked_folder


def add_parser(sub) -> None:
    from hubvib.validation.convergence import QUANTITIES

    p = sub.add_parser("convergence", help="error vs run time of one FE quantity over mesh levels")
    p.add_argument("quantity", choices=QUANTITIES,
                   help="c_ru, c_r, c_sp, c_rp of the Raba reducer (root-land readings), "
                        "the work-conjugate c_ru_work, c_r_work and the rim part c_ru_rim "
                        "(nested levels), the same c_ru, c_r from one tooth pitch "
                        "(c_ru_sector, c_r_sector: nested pitch levels), or an exact "
                        "benchmark")
    p.add_argument("--out", type=Path, required=True, metavar="DIR",
                   help="output folder for the table (CSV) and the plot (PNG)")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.reducer import raba118
    from hubvib.validation.convergence import GEAR_QUANTITIES, Gears, run_study, study_note

    # checked and locked before any level is computed; the study writes its own files
    # there as it goes (each finished level is kept, so a killed study resumes)
    with locked_folder(args.out):
        gears = (Gears(raba118.ring_gear(), raba118.gear_body("sun"), raba118.gear_body("planet"))
                 if args.quantity in GEAR_QUANTITIES else None)
        table = run_study(args.quantity, args.out, gears,
                          progress=lambda line: print(line, file=sys.stderr, flush=True))
    plot = table.with_suffix(".png")
    note = study_note(args.quantity, table)
    if args.json:
        with open(table, newline="", encoding="utf-8") as handle:
            levels = [{k: _number(v) for k, v in row.items()} for row in csv.DictReader(handle)]
        print(json_text({"quantity": args.quantity, "files": [str(table), str(plot)],
                         "levels": levels, "note": note.splitlines()}))
        return 0
    print(table.read_text(), end="")
    print(note)
    print(f"written: {table} and {plot.name}")
    return 0


def _number(text: str) -> float | None:
    """A CSV cell as a number; empty or not finite (no reference) as ``None``."""
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None
