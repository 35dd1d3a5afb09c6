"""``hubvib validate raba118``: the published spectrum reproduced and explained."""
from __future__ import annotations

import json
from pathlib import Path


def add_parser(sub) -> None:
    p = sub.add_parser("validate", help="scripted validation against published data")
    p.add_argument("case", choices=["raba118"])
    p.add_argument("--out", type=Path, default=Path("hubvib-out/validate-raba118"))
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.validation import raba118

    result = raba118.write_report(raba118.validate(), args.out)
    if args.json:
        print(json.dumps({**result.summary(), "files": [str(f) for f in result.files]}, indent=2))
    else:
        print(raba118.format_report(result))
        print(f"\nwritten: {', '.join(str(f) for f in result.files)}")
    return 0 if result.passed else 1
