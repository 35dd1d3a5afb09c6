"""``hubvib validate raba118``: the published spectrum against the printed matrix and the
energy-consistent model, explained."""
from __future__ import annotations

from pathlib import Path

from hubvib.foundation.output import json_text, output_set, written_line


def add_parser(sub) -> None:
    p = sub.add_parser("validate", help="scripted validation against published data")
    p.add_argument("case", choices=["raba118"], help="the published case to compare with")
    p.add_argument("--out", type=Path, default=Path("hubvib-out/validate-raba118"),
                   metavar="DIR", help="output folder (default hubvib-out/validate-raba118)")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.reducer import lumped_preset
    from hubvib.validation import raba118

    with output_set(args.out) as staged:  # checked and locked before the work
        result = raba118.write_report(raba118.validate(lumped_preset("raba118")), staged)
    files = [args.out / Path(f).relative_to(staged) for f in result.files]
    if args.json:
        print(json_text({**result.summary(), "files": [str(f) for f in files]}))
    else:
        print(raba118.format_report(result))
        print("\n" + written_line(files))
    return 0 if result.passed else 1
