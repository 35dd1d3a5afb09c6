"""``hubvib convergence QUANTITY --out DIR``: error against run time (CSV + log-log plot)."""
from __future__ import annotations

from pathlib import Path


def add_parser(sub) -> None:
    from hubvib.validation.convergence import QUANTITIES

    p = sub.add_parser("convergence", help="error vs run time of one FE quantity over mesh levels")
    p.add_argument("quantity", choices=QUANTITIES,
                   help="c_ru, c_r, c_sp, c_rp of the Raba reducer, or an exact benchmark")
    p.add_argument("--out", type=Path, required=True, metavar="DIR")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.validation.convergence import run_study

    table = run_study(args.quantity, args.out)
    print(table.read_text(), end="")
    print(f"written: {table} and {table.with_suffix('.png').name}")
    return 0
