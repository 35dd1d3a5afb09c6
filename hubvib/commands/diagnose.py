"""``hubvib diagnose --scene SCENE (--measured FILE.csv | --record FILE --baseline-record FILE)``:
crack depth from measured frequencies or from two accelerometer records."""
from __future__ import annotations

import json
from pathlib import Path


def add_parser(sub) -> None:
    p = sub.add_parser("diagnose", help="estimate the ring crack depth from identified natural "
                       "frequencies (CSV: frequency_hz, optional mode, baseline_hz, "
                       "damping_ratio, record_s or sigma_hz)")
    p.add_argument("--scene", required=True, help="scene TOML file with a [crack] study, or "
                   "the name of a shipped scene (hubvib scenes lists them)")
    p.add_argument("--measured", type=Path,
                   help="CSV of identified natural frequencies: header frequency_hz, optional "
                   "columns mode (model mode, 1 = lowest), baseline_hz (same mode, intact), "
                   "damping_ratio and record_s (or sigma_hz) of the identification")
    p.add_argument("--record", type=Path, help="accelerometer record of the reducer now: "
                   "CSV time_s,acceleration_m_s2, WAV or UFF 58 (instead of --measured)")
    p.add_argument("--baseline-record", type=Path,
                   help="record of the same reducer intact (with --record)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.detection.diagnosis import diagnose_scene
    from hubvib.detection.from_records import diagnose_records
    from hubvib.detection.measured import read_measured
    from hubvib.studies.scene import load_scene

    if (args.measured is None) == (args.record is None):
        raise ValueError("give either --measured FILE.csv or --record FILE with "
                         "--baseline-record FILE")
    if (args.record is None) != (args.baseline_record is None):
        raise ValueError("--record and --baseline-record go together: the record now and "
                         "the record of the same reducer intact")
    scene = load_scene(args.scene)
    found = None
    if args.record is not None:
        result, ref, found = diagnose_records(scene, args.record, args.baseline_record,
                                              progress=not args.json)
        measured = found.measured
    else:
        measured = read_measured(args.measured)
        result, ref = diagnose_scene(scene, measured, progress=not args.json)
    if args.json:
        extra = {} if found is None else {"skipped_modes": {
            str(i + 1): why for i, why in sorted(found.now.skipped.items())}}
        print(json.dumps({"scene": scene.name, **result.to_dict(), **ref.mesh_stiffness,
                          **extra}, indent=2,
                         allow_nan=False))
        return 0
    if found is not None:
        print(f"identified from the records (Bayesian FFT, damping "
              f"{100 * found.now.modes[0].damping_ratio:.3g} % in the first band): modes "
              f"{', '.join(str(i + 1) for i in found.now.index)}; skipped: "
              + ("; ".join(f"{i + 1} ({why})" for i, why in sorted(found.now.skipped.items()))
                 or "none"))
    nominal = ref.nominal_hz[0]
    print(f"scene {scene.name!r}: {len(result.modes)} measured mode(s), baseline: "
          f"{'the measured intact frequencies' if result.baseline == 'measured' else 'the model intact spectrum'}")
    print(f"{'mode':>4} {'model intact [Hz]':>17} {'measured [Hz]':>13} {'shift [Hz]':>10} "
          f"{'sigma [Hz]':>10}  informative")
    for mode, f, shift, sigma, useful in zip(result.modes, measured.frequency_hz,
                                             result.shift_hz, result.sigma_hz,
                                             result.informative):
        print(f"{mode:>4} {nominal[mode - 1]:>17.3f} {f:>13.3f} {shift:>+10.3f} {sigma:>10.3f}  "
              f"{'yes' if useful else 'no'}")
    print(f"(shift: measured minus baseline, both record-averaged; sigma: standard deviation "
          f"of one identified frequency; fit p-value {result.fit_p_value:.3g} at "
          f"{1e3 * result.fit_depth:.3g} mm)")
    if result.verdict == "not explained by a ring crack":
        print(f"verdict: {result.verdict} (fit statistic {result.fit_statistic:.3g}, p = "
              f"{result.fit_p_value:.2g} < {ref.fit_false_alarm_rate:g}): "
              f"{result.explanation()}")
    elif result.depth is None:
        print(f"verdict: {result.verdict} (no measured mode tells the deepest crack of the "
              f"sweep, {1e3 * ref.depths[-1]:.3g} mm, from an intact reducer)")
    elif result.verdict == "crack indicated":
        print(f"verdict: {result.verdict}: depth {1e3 * result.depth:.3g} mm, "
              f"{100 * result.confidence:g} % interval {1e3 * result.depth_low:.3g} .. "
              f"{1e3 * result.depth_high:.3g} mm")
    else:
        print(f"verdict: {result.verdict}: depth below {1e3 * result.depth_high:.3g} mm "
              f"at {100 * result.confidence:g} %")
    return 0
