"""``hubvib stability``: stiff and extreme cases against a 50-digit reference, with run time."""
from __future__ import annotations

import math

from hubvib.foundation.output import json_text

#: most timed repeats: 1000 repeats of every case and method take minutes
MAX_REPEATS = 1000


def add_parser(sub) -> None:
    p = sub.add_parser("stability", help="stiff/extreme cases: error vs 50-digit reference and time")
    p.add_argument("--repeats", type=int, default=20,
                   help=f"timed calls per case and method, 1..{MAX_REPEATS} (default 20)")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.reducer import lumped_preset
    from hubvib.runtime.progress import progress
    from hubvib.validation import stability

    if not 1 <= args.repeats <= MAX_REPEATS:
        raise ValueError(f"--repeats = {args.repeats}, but it must be 1..{MAX_REPEATS}")
    raba = lumped_preset("raba118")
    with progress(len(stability.cases(raba)), "stability cases", "case") as bar:
        rows = stability.run(raba, repeats=args.repeats, on_case=lambda name: bar.update(1, name))
    default = [r for r in rows if r.method == "jacobi"]
    passed = all(r.max_error <= stability.TARGET for r in default)
    if args.json:
        print(json_text({"target": stability.TARGET, "passed": passed,
                         "rows": [_standard(r.as_dict()) for r in rows]}))
    else:
        print(stability.format_table(rows))
        print(f"\ndefault method (jacobi) within {stability.TARGET:g} of the 50-digit "
              f"reference on every case: {'yes' if passed else 'NO'}")
    return 0 if passed else 1


def _standard(row: dict) -> dict:
    """NaN (no error or time: the printed matrix has no real frequencies) as JSON null."""
    return {k: None if isinstance(v, float) and not math.isfinite(v) else v
            for k, v in row.items()}
