"""The diagnosis check of docs/diagnosis.md: how ``hubvib diagnose`` performs on a scene.

``python -m hubvib.studies.diagnosis_check [--scene S] [--ring rigid|elastic]
[--modes 13,15,16,18] [--trials N] [--out FILE.md]`` builds the scene's spectrum model (the
rigid-ring crack model from its FE cases, or the elastic ring) and runs
``hubvib.detection.calibration.calibrate`` on it: the verdicts on intact reducers, the
coverage of the intervals over depths drawn uniformly from the sweep, and the verdicts on
patterns no ring crack produces, written as a markdown table.
"""
from __future__ import annotations

import argparse
from pathlib import Path

from hubvib.cases.runner import crack_cases
from hubvib.detection.calibration import calibrate
from hubvib.detection.carrier import mesh_timing
from hubvib.detection.diagnosis import elastic_scene_model, reference
from hubvib.detection.model import CrackModel
from hubvib.detection.options import detection_options
from hubvib.studies.scene import load_scene


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="raba118_crack")
    parser.add_argument("--ring", default="rigid", choices=("rigid", "elastic"))
    parser.add_argument("--modes", default="13,15,16,18",
                        help="model modes (1-based, in the chosen ring's own order: the "
                        "numbers name different modes in the two models)")
    parser.add_argument("--trials", type=int, default=400)
    parser.add_argument("--out", type=Path)
    args = parser.parse_args(argv)
    scene = load_scene(args.scene)
    options = detection_options(scene)
    if args.ring == "elastic":
        model = elastic_scene_model(scene)
    else:
        fe, _ = crack_cases(scene.crack, False)
        model = CrackModel.from_fe(scene.params, scene.crack, fe, scene.method,
                                   c_rp_given=scene.c_rp_given)
    timing = mesh_timing(scene.crack.reducer, options.carrier_speed)
    ref = reference(model, options, timing)
    modes = [int(m) for m in args.modes.split(",")]
    if any(not 1 <= m <= len(ref.labels) for m in modes):
        raise SystemExit(f"--modes {args.modes}: the {args.ring} ring has modes 1.."
                         f"{len(ref.labels)}")
    result = calibrate(model, options, timing, ref, modes, args.trials)
    text = "\n".join([f"Scene `{scene.name}`, "
                      + ("elastic ring, " if args.ring == "elastic" else "")
                      + "modes " + "; ".join(ref.labels[m - 1] for m in modes) + ", damping "
                      f"{100 * options.damping_ratio:g} %, records {options.record_length:g} s, "
                      f"SNR {options.snr:g}, {args.trials} trials each:", "", *result.table()])
    if args.out:
        args.out.write_text(text + "\n", encoding="utf-8")
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
