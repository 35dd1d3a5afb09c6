"""``hubvib diagnose --scene SCENE (--measured FILE.csv | --record FILE --baseline-record FILE)
[--ring rigid|elastic]``: crack depth from measured frequencies or from two accelerometer
records, on the ring model the scene's ``[elastic] ring`` chooses (``both``: both verdicts)
or ``--ring``."""
from __future__ import annotations

import json
import sys
import textwrap
from pathlib import Path

#: width the explanations are wrapped to
WIDTH = 96
#: the ring models ``--ring`` chooses from
RINGS = ("rigid", "elastic")


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
    p.add_argument("--ring", metavar="{" + ",".join(RINGS) + "}", help="ring model: rigid (the 9 + 3N model) or elastic (the FE "
                   "ring coupled to the lumped bodies); default: the scene's [elastic] ring "
                   "(both: both verdicts, the rigid ring's first)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def rings_of(scene, flag: str | None) -> tuple[str, ...]:
    """The ring models to diagnose on: ``--ring`` if given, else the scene's ``[elastic]
    ring`` (``both``: rigid, then elastic)."""
    from hubvib.detection.diagnosis import scene_ring

    if flag is not None:
        if flag not in RINGS:
            raise ValueError(f"--ring = {flag!r}; allowed: {', '.join(RINGS)}")
        return (flag,)
    ring = scene_ring(scene)
    return RINGS if ring == "both" else (ring,)


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
    from hubvib.detection.from_records import NotIdentified, diagnose_records
    from hubvib.detection.measured import read_measured
    from hubvib.studies.scene import load_scene

    if args.ring is not None and args.ring not in RINGS:
        raise ValueError(f"--ring = {args.ring!r}; allowed: {', '.join(RINGS)}")
    if (args.measured is None) == (args.record is None):
        raise ValueError("give either --measured FILE.csv or --record FILE with "
                         "--baseline-record FILE")
    if (args.record is None) != (args.baseline_record is None):
        raise ValueError("--record and --baseline-record go together: the record now and "
                         "the record of the same reducer intact")
    scene = load_scene(args.scene)
    rings = rings_of(scene, args.ring)
    if args.record is not None:
        answers, measured_of, found = [], {}, None
        if "rigid" in rings:
            result, ref, found = diagnose_records(scene, args.record, args.baseline_record,
                                                  progress=not args.json)
            if isinstance(result, NotIdentified):
                if len(rings) == 1:
                    if args.json:
                        print(json.dumps({"scene": scene.name, **result.to_dict(),
                                          **ref.mesh_stiffness}, indent=2, allow_nan=False))
                    else:
                        _print_skipped(found)
                        _print_not_identified(scene, result)
                    return 0
                answers.append(("rigid", "no mode of the model is identified in both records",
                                None))
                found = None
            else:
                answers.append(("rigid", result, ref))
                measured_of["rigid"] = found.measured
        if "elastic" in rings:
            try:
                measured = _elastic_record_measured(scene, args.record, args.baseline_record)
            except ValueError as error:
                if len(rings) == 1:
                    raise
                answers.append(("elastic", str(error), None))
            else:
                measured_of["elastic"] = measured
                answers.append(_diagnosed(scene, measured, "elastic", progress=not args.json,
                                          fail=len(rings) == 1))
        return _report(scene, measured_of, answers, found, args.json)
    measured = read_measured(args.measured)
    answers = [_diagnosed(scene, measured, ring, progress=not args.json, fail=len(rings) == 1)
               for ring in rings]
    return _report(scene, {ring: measured for ring in rings}, answers, None, args.json)


def _elastic_record_measured(scene, record: Path, baseline: Path):
    """The elastic ring's watched coupled modes identified in both records
    (``detection.from_records.elastic_measured``) as measured frequencies with their
    scatter; a record in which none is identified is refused, naming why per mode."""
    from hubvib.detection.from_records import elastic_measured
    from hubvib.identification.readers import read_record
    from hubvib.signal.elastic_record import scene_floquet_shift

    # a running reducer's record shows the Floquet modes over the mesh cycle, not the
    # mean-stiffness ones
    measured, left_out = elastic_measured(
        scene, read_record(record, "--record"), read_record(baseline, "--baseline-record"),
        lambda: scene_floquet_shift(scene))
    for line in left_out[:len(left_out) - (measured is None)]:
        print(line, file=sys.stderr)  # stdout holds the answer (or the JSON)
    if measured is None:
        raise ValueError(f"--record: no coupled mode of the elastic ring is identified in "
                         f"both records near its model frequency ({left_out[-1]})")
    return measured


def _diagnosed(scene, measured, ring: str, progress: bool, fail: bool):
    """(ring, diagnosis, reference) of ``measured`` on ``ring``; with ``fail`` False a
    measurement that does not pair with this ring's modes gives (ring, message, None)."""
    from hubvib.detection.diagnosis import diagnose_scene
    from hubvib.detection.measured import MeasuredError

    try:
        result, ref = diagnose_scene(scene, measured, progress=progress, ring=ring)
    except MeasuredError as error:
        if fail:
            raise
        return ring, str(error), None
    return ring, result, ref


def _report(scene, measured_of: dict, answers, found, as_json: bool) -> int:
    """Print every ring's answer (JSON: the first at the top level as a single ring gives
    it, the second under its ring's name); ``measured_of``: each ring's measured
    frequencies; ``found``: the rigid ring's record identification (None: none)."""
    if all(ref is None for _, _, ref in answers):
        raise ValueError("; ".join(f"{ring} ring: {message}" for ring, message, _ in answers))
    if as_json:
        payload = None
        for ring, result, ref in answers:
            body = ({"error": result} if ref is None else
                    {"ring": ring, **result.labelled(ref.labels), **ref.mesh_stiffness})
            if payload is None:
                payload = {"scene": scene.name, **body}
                if found is not None:
                    payload["skipped_modes"] = {str(mode): why
                                                for mode, why in found.skipped().items()}
            else:
                payload[ring] = body
        print(json.dumps(payload, indent=2, allow_nan=False))
        return 0
    for n, (ring, result, ref) in enumerate(answers):
        if len(answers) > 1:
            print(("" if n == 0 else "\n") + f"== {ring} ring "
                  + ("(9 + 3N model)" if ring == "rigid" else "(FE ring coupled to the lumped "
                     "bodies)") + " ==")
        if ref is None:
            _say(f"verdict: not diagnosed on the {ring} ring: {result}")
            continue
        _print_answer(scene, measured_of[ring], result, ref,
                      found if ring == "rigid" else None)
    return 0


def _print_answer(scene, measured, result, ref, found) -> None:
    if found is not None:
        damping = ", ".join(f"{100 * m.damping_ratio:.3g} % (rigid mode {i + 1})"
                            for i, m in zip(found.now.index, found.now.modes)
                            if i + 1 in result.modes)
        _say(f"identified in both records (Bayesian FFT, one mode per band): rigid modes "
              f"{', '.join(str(m) for m in result.modes)}; their damping identified in the "
              f"record now: {damping}")
        _print_skipped(found)
    nominal = ref.nominal_hz[0]
    print(f"scene {scene.name!r}: {len(result.modes)} measured mode(s), baseline: "
          f"{'the measured intact frequencies' if result.baseline == 'measured' else 'the model intact spectrum'}")
    names = [ref.labels[m - 1] if len(ref.labels) >= m else f"{ref.ring} {m}"
             for m in result.modes]
    width = max(len("mode"), *(len(n) for n in names))
    print(f"{'mode':<{width}} {'model intact [Hz]':>17} {'measured [Hz]':>13} "
          f"{'shift [Hz]':>10} {'sigma [Hz]':>10}  informative")
    for name, mode, f, shift, sigma, useful in zip(names, result.modes, measured.frequency_hz,
                                                   result.shift_hz, result.sigma_hz,
                                                   result.informative):
        print(f"{name:<{width}} {nominal[mode - 1]:>17.3f} {f:>13.3f} {shift:>+10.3f} "
              f"{sigma:>10.3f}  {'yes' if useful else 'no'}")
    for line in explain(result, ref):
        print(textwrap.fill(line, WIDTH, initial_indent="  ", subsequent_indent="    "))
    if result.verdict == "not explained by a ring crack":
        _say(f"verdict: {result.verdict} (fit statistic {result.fit_statistic:.3g}, p = "
              f"{result.fit_p_value:.2g} < {ref.fit_false_alarm_rate:g}): "
              f"{result.explanation(ref.labels)}")
    elif result.depth_high is None:
        _say(f"verdict: {result.verdict} (no measured mode tells the deepest crack of the "
              f"sweep, {1e3 * ref.depths[-1]:.3g} mm, from an intact reducer)")
    elif result.verdict == "crack indicated":
        _say(f"verdict: {result.verdict}: {result.words} (it holds the depth with probability "
              f"{result.confidence:g} under the model; depths computed: "
              f"{', '.join(f'{1e3 * d:.3g}' for d in ref.depths)} mm)")
    else:
        _say(f"verdict: {result.verdict}: depth {result.words}")


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
        f"{_fit_depth(result.fit_depth, ref.depths)} (maximum likelihood); p-value "
        f"{result.fit_p_value:.3g}: how often the model's own reducers with that crack, "
        "identified with the same scatter, fit as badly or worse (whole pattern or one mode "
        f"alone); below {ref.fit_false_alarm_rate:g} the pattern is not a ring crack.",
    ]


def _fit_depth(depth: float, computed) -> str:
    """The best-fitting depth in words: ``4.2 mm``, ``0 (intact)``, or ``below 3 mm``
    between the intact reducer and the shallowest crack computed (the sweep tells no
    finer)."""
    if depth == 0:
        return "0 (intact)"
    if depth < computed[1]:
        return f"below {1e3 * computed[1]:.3g} mm (the shallowest crack computed)"
    return f"{1e3 * depth:.3g} mm"
