"""``hubvib diagnose --scene SCENE (--measured FILE.csv | --record FILE --baseline-record FILE)``:
crack depth from measured frequencies or from two accelerometer records."""
from __future__ import annotations

import json
import textwrap
from pathlib import Path

#: width the explanations are wrapped to
WIDTH = 96


def _say(text: str) -> None:
    """Print ``text`` wrapped to WIDTH, continuation lines indented."""
    print(textwrap.fill(text, WIDTH, subsequent_indent="    "))


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


def _print_skipped(found) -> None:
    """Why each model mode is not identified in both records, a short line per mode (the
    degenerate pairs on one)."""
    from hubvib.detection.from_records import skipped_lines

    lines = skipped_lines(found.skipped())
    if lines:
        print("not identified:")
        for line in lines:
            print(textwrap.fill(line, WIDTH, initial_indent="  ", subsequent_indent="    "))


def _print_not_identified(scene, answer) -> None:
    _say(f"scene {scene.name!r}: records of {answer.record_s:.3g} s (now) and "
          f"{answer.baseline_s:.3g} s (baseline), modal damping assumed "
          f"{100 * answer.damping_ratio:.3g} % (the scene's [detection] damping_ratio)")
    _say(f"verdict: {answer.verdict}: no mode of the model is identified in both records")
    print("what would help:")
    for line in answer.helps:
        print(textwrap.fill(line, WIDTH, initial_indent="  - ", subsequent_indent="    "))


def run(args) -> int:
    from hubvib.detection.diagnosis import diagnose_scene
    from hubvib.detection.from_records import NotIdentified, diagnose_records
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
        if isinstance(result, NotIdentified):
            if args.json:
                print(json.dumps({"scene": scene.name, **result.to_dict(),
                                  **ref.mesh_stiffness}, indent=2, allow_nan=False))
            else:
                _print_skipped(found)
                _print_not_identified(scene, result)
            return 0
        measured = found.measured
    else:
        measured = read_measured(args.measured)
        result, ref = diagnose_scene(scene, measured, progress=not args.json)
    if args.json:
        extra = {} if found is None else {"skipped_modes": {
            str(mode): why for mode, why in found.skipped().items()}}
        print(json.dumps({"scene": scene.name, **result.to_dict(), **ref.mesh_stiffness,
                          **extra}, indent=2,
                         allow_nan=False))
        return 0
    if found is not None:
        damping = ", ".join(f"{100 * m.damping_ratio:.3g} % (mode {i + 1})"
                            for i, m in zip(found.now.index, found.now.modes)
                            if i + 1 in result.modes)
        _say(f"identified in both records (Bayesian FFT, one mode per band): modes "
              f"{', '.join(str(m) for m in result.modes)}; their damping identified in the "
              f"record now: {damping}")
        _print_skipped(found)
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
    for line in explain(result, ref):
        print(textwrap.fill(line, WIDTH, initial_indent="  ", subsequent_indent="    "))
    if result.verdict == "not explained by a ring crack":
        _say(f"verdict: {result.verdict} (fit statistic {result.fit_statistic:.3g}, p = "
              f"{result.fit_p_value:.2g} < {ref.fit_false_alarm_rate:g}): "
              f"{result.explanation()}")
    elif result.depth is None:
        _say(f"verdict: {result.verdict} (no measured mode tells the deepest crack of the "
              f"sweep, {1e3 * ref.depths[-1]:.3g} mm, from an intact reducer)")
    elif result.verdict == "crack indicated":
        _say(f"verdict: {result.verdict}: depth {1e3 * result.depth:.3g} mm (posterior "
              f"median), {100 * result.confidence:g} % interval {1e3 * result.depth_low:.3g} "
              f".. {1e3 * result.depth_high:.3g} mm (it holds the depth with probability "
              f"{result.confidence:g} under the model)")
    else:
        _say(f"verdict: {result.verdict}: depth below {1e3 * result.depth_high:.3g} mm "
              f"at {100 * result.confidence:g} %")
    return 0


def explain(result, ref) -> list[str]:
    """What the columns of the table and the fit figures mean, in words."""
    baseline = ("the intact record's frequency" if result.baseline == "measured"
                else "the model's intact frequency")
    return [
        f"shift: measured minus baseline ({baseline}), both averaged over the record; "
        "sigma: standard deviation of one identified frequency; informative: whether the "
        "deepest crack of the sweep moves the mode by more than one standard deviation of an "
        "intact measurement.",
        f"fit: the crack depth that explains these shifts best is "
        f"{1e3 * result.fit_depth:.3g} mm (maximum likelihood); p-value "
        f"{result.fit_p_value:.3g}: how often the model's own reducers with that crack, "
        "identified with the same scatter, fit as badly or worse (whole pattern or one mode "
        f"alone); below {ref.fit_false_alarm_rate:g} the pattern is not a ring crack.",
    ]
