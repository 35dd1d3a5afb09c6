"""``hubvib harmonics``: kinematic-error harmonics of a ball/roller planetary gear (seed 000)."""
from __future__ import annotations

import sys
from pathlib import Path


def add_parser(sub) -> None:
    p = sub.add_parser("harmonics", help="kinematic error of an output encoder record and its "
                                         "labelled harmonics (seed 000)")
    p.add_argument("--periods", type=Path, required=True, metavar="FILE.csv",
                   help="pulse periods [s], one per line (or timestamps under a header "
                        "'timestamp_s')")
    p.add_argument("--pulses-per-rev", type=int, required=True, metavar="N",
                   help="encoder pulses per output revolution, >= 4")
    p.add_argument("--z1", type=int, default=1, help="periods of the driving track, >= 1")
    p.add_argument("--z2", type=int, required=True, help="periods of the fixed track, >= 1")
    p.add_argument("--stages", type=int, default=1, help="equal stages, >= 1")
    p.add_argument("--unit", choices=["deg", "arcmin"], default="deg",
                   help="unit of the kinematic error (default deg)")
    p.add_argument("--top", type=int, default=10, help="harmonics listed, >= 1 (default 10)")
    p.add_argument("--max-order", type=int, metavar="K",
                   help="highest output order considered (capped at the Nyquist order N/2)")
    p.add_argument("--out", type=Path, metavar="DIR",
                   help="write error.csv, spectrum.csv, harmonics.csv and harmonics.png here")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.companion import harmonics as h
    from hubvib.foundation.output import json_text, output_set, write_csv, save_figure

    train = h.GearTrain(args.z1, args.z2, args.stages)
    analysis = h.analyse(h.read_periods(args.periods), args.pulses_per_rev, train, args.top,
                         args.max_order)
    data = h.to_dict(analysis, args.unit)
    files = []
    if args.out:
        with output_set(args.out) as stage:
            written = [write_csv(stage / "error.csv", h.error_rows(analysis, args.unit)),
                       write_csv(stage / "spectrum.csv", h.spectrum_rows(analysis, args.unit)),
                       write_csv(stage / "harmonics.csv",
                                 [line.to_dict() for line in analysis.lines])]
            written.append(save_figure(h.figure(analysis, args.unit), stage / "harmonics.png"))
        files = [str(args.out / p.relative_to(stage)) for p in written]
    data["files"] = files
    for warning in analysis.warnings:
        print(f"hubvib: warning: {warning}", file=sys.stderr)
    if args.json:
        print(json_text(data))
        return 0
    u = args.unit
    print(f"ratio i = {data['ratio']:g} ({train.stages} stage(s) of ({train.z1} + {train.z2}) / "
          f"{train.z1}), {data['revolutions']} output revolutions at {data['pulses_per_rev']} "
          f"pulses, n_m = {data['mean_output_speed_rpm']:.4g} min^-1")
    print(f"kinematic error: peak-to-peak {data['peak_to_peak']:.4f} {u}")
    print(f"{'order':>6} {'c_k [' + u + ']':>14} {'phase [deg]':>12}  label")
    for line in data["harmonics"]:
        phase = round(line["phase_deg"], 2) + 0.0  # no "-0.00"
        print(f"{line['order']:>6g} {line['amplitude']:>14.6f} {phase:>12.2f}  "
              f"{line['label']}" + (f" = {', '.join(line['also'])}" if line["also"] else "")
              + (f"  ({line['meaning']})" if line["meaning"] else ""))
    for f in files:
        print(f"wrote {f}")
    return 0
