"""``hubvib stability``: stiff and extreme cases against a 50-digit reference, with run time."""
from __future__ import annotations

import json


def add_parser(sub) -> None:
    p = sub.add_parser("stability", help="stiff/extreme cases: error vs 50-digit reference and time")
    p.add_argument("--repeats", type=int, default=20)
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.validation import stability

    if args.repeats < 1:
        raise ValueError(f"--repeats = {args.repeats}, but it must be >= 1")
    rows = stability.run(repeats=args.repeats)
    default = [r for r in rows if r.method == "jacobi"]
    passed = all(r.max_error <= stability.TARGET for r in default)
    if args.json:
        print(json.dumps({"target": stability.TARGET, "passed": passed,
                          "rows": [r.as_dict() for r in rows]}, indent=2))
    else:
        print(stability.format_table(rows))
        print(f"\ndefault method (jacobi) within {stability.TARGET:g} of the 50-digit "
              f"reference on every case: {'yes' if passed else 'NO'}")
    return 0 if passed else 1
