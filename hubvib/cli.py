"""``hubvib`` command line.  ``main(argv)`` returns the exit code (testable in-process)."""
from __future__ import annotations

import argparse
import importlib.util
import json
import sys
import tempfile
from pathlib import Path

from lumped import METHODS, PRESETS, ParameterError, field_names
from meshing.session import MeshingError

from . import convergence_command, mesh_command, stiffness_command
from .params_input import CONVENIENCE_KEYS, load_parameters, parse_set

PARAMETER_HELP = (
    "Parameter keys (SI: kg, m, N/m, rad): " + ", ".join(field_names())
    + "; edge conveniences: " + ", ".join(CONVENIENCE_KEYS)
    + ". m_* masses, mu_* reduced masses J/r_b^2, d_* base diameters, c_sp/c_rp mesh, "
    "c_p/c_c/c_r/c_s bearings, c_su/c_cu/c_ru reduced torsional stiffness, alpha_s/alpha_r "
    "working pressure angles, theta planet angles."
)


def main(argv: list[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        return args.handler(args)
    except (ParameterError, ValueError, MeshingError) as exc:
        print(f"hubvib: error: {exc}", file=sys.stderr)
        return 2
    except ModuleNotFoundError as exc:
        print(f"hubvib: error: {exc.name} is not installed; this command needs the FE extras: "
              f"pip install \"hubvib[fem]\"", file=sys.stderr)
        return 2


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="hubvib", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)

    def params_options(p):
        p.add_argument("--preset", default="raba118", choices=sorted(PRESETS))
        p.add_argument("--params", type=Path, metavar="FILE.toml",
                       help="TOML file of parameter keys (may name its own preset)")
        p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                       help=PARAMETER_HELP)
        p.add_argument("--method", default="jacobi", choices=METHODS)
        p.add_argument("--json", action="store_true", help="machine-readable output")

    p = sub.add_parser("spectrum", help="natural frequencies, mode types and multiplicities",
                       epilog=PARAMETER_HELP)
    params_options(p)
    p.set_defaults(handler=_spectrum)

    p = sub.add_parser("shift", help="per-mode frequency shift when one parameter changes")
    params_options(p)
    p.add_argument("--to", nargs=2, required=True, metavar=("KEY", "VALUE"),
                   help="the modified parameter and its new value, e.g. --to c_ru 1e5")
    p.set_defaults(handler=_shift)

    p = sub.add_parser("validate", help="scripted validation against published data")
    p.add_argument("case", choices=["raba118"])
    p.add_argument("--out", type=Path, default=Path("hubvib-out/validate-raba118"))
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=_validate)

    p = sub.add_parser("stability", help="stiff/extreme cases: error vs 50-digit reference and time")
    p.add_argument("--repeats", type=int, default=20)
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=_stability)

    mesh_command.add_parser(sub)
    stiffness_command.add_parser(sub)
    convergence_command.add_parser(sub)

    p = sub.add_parser("run", help="run a scene (default: the embedded Raba 118/76 study)")
    p.add_argument("scene", nargs="?", type=Path, help="scene TOML file (see scenes/)")
    p.add_argument("--out", type=Path, help="output folder (overrides the scene's)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=_run)
    return parser


def _load(args):
    return load_parameters(args.preset, args.params, parse_set(args.set))


def _spectrum(args) -> int:
    from lumped import natural_modes

    spectrum = natural_modes(_load(args), args.method)
    if args.json:
        print(json.dumps({"method": spectrum.method, "n_rigid": spectrum.n_rigid,
                          "modes": spectrum.rows()}, indent=2))
        return 0
    print(f"{'mode':>4} {'omega [rad/s]':>14} {'f [Hz]':>11}  {'type':<13} mult")
    for r in spectrum.rows():
        print(f"{r['mode']:>4} {r['omega_rad_s']:>14.3f} {r['frequency_hz']:>11.3f}  "
              f"{r['kind']:<13} {r['multiplicity']}")
    if spectrum.n_rigid:
        print(f"{spectrum.n_rigid} rigid-body mode(s): the supports and springs leave the "
              "system free to move without strain; their frequency is exactly 0.")
    return 0


def _shift(args) -> int:
    from lumped import frequency_shift

    key, text = args.to
    value = parse_set([f"{key}={text}"])[key]
    shift = frequency_shift(_load(args), key, value, method=args.method)
    if args.json:
        print(json.dumps({"parameter": key, "base": shift.base_value, "modified": value,
                          "modes": shift.rows()}, indent=2))
        return 0
    print(f"{key}: {shift.base_value:.6g} -> {value:.6g}")
    print(f"{'mode':>4} {'type':<13} {'base [rad/s]':>13} {'new [rad/s]':>12} "
          f"{'d [rad/s]':>10} {'d [Hz]':>9} {'d [%]':>8}")
    for r in shift.rows():
        print(f"{r['mode']:>4} {r['kind']:<13} {r['omega_base_rad_s']:>13.3f} "
              f"{r['omega_modified_rad_s']:>12.3f} {r['delta_rad_s']:>10.3f} "
              f"{r['delta_hz']:>9.3f} {r['percent']:>8.3f}")
    return 0


def _validate(args) -> int:
    from validation import raba118

    result = raba118.write_report(raba118.validate(), args.out)
    if args.json:
        print(json.dumps({**result.summary(), "files": [str(f) for f in result.files]}, indent=2))
    else:
        print(raba118.format_report(result))
        print(f"\nwritten: {', '.join(str(f) for f in result.files)}")
    return 0 if result.passed else 1


def _stability(args) -> int:
    from validation import stability

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


def _missing_extras(scene) -> str | None:
    """What the scene needs that is not installed, as an error message."""
    needs = [("plots = true", "matplotlib", "report", scene.plots)]
    if scene.crack is not None:
        needs += [("[crack] (FE stage)", module, "fem", True)
                  for module in ("gmsh", "skfem")] + [("[crack]", "tqdm", "report", True)]
    needs += [("renders = true", module, "render", scene.renders)
              for module in ("pyvista", "imageio")]
    for what, module, extra, wanted in needs:
        if wanted and importlib.util.find_spec(module) is None:
            return (f"scene asks for {what} but {module} is not installed: "
                    f"pip install 'hubvib[{extra}]'")
    return None


def _run(args) -> int:
    from .scene import load_scene

    scene = load_scene(args.scene)
    missing = _missing_extras(scene)
    if missing:
        print(f"hubvib: error: {missing}", file=sys.stderr)
        return 2
    folder = Path(args.out or scene.folder)
    try:  # before any work: a run that cannot write its report must not start
        folder.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=folder).close()
    except OSError as exc:
        print(f"hubvib: error: cannot write the output folder {str(folder)!r}: {exc.strerror}",
              file=sys.stderr)
        return 2
    if scene.crack is not None:
        return _run_crack(scene, folder, args.json)
    from .study import run_study, write_study

    result = write_study(run_study(scene), folder)
    if args.json:
        print(json.dumps({"scene": scene.name, "folder": str(folder),
                          "files": [str(f) for f in result.files],
                          "detection": result.detection()}, indent=2))
        return 0
    print(f"scene {scene.name!r}: {scene.parameter} {result.base_value:.6g} -> "
          f"{', '.join(f'{v:.3g}' for v in scene.values)}")
    print(f"{'mode':>4} {'type':<13} {'base [rad/s]':>13} {'shift at last value [%]':>24}  "
          f"first value shifting >= {scene.threshold_percent:g} %")
    last = result.shifts[-1]
    for r in result.detection():
        first = "not reached" if r["detectable_at"] is None else f"{r['detectable_at']:.4g}"
        print(f"{r['mode']:>4} {r['kind']:<13} {r['omega_base_rad_s']:>13.3f} "
              f"{last.percent[r['mode'] - 1]:>24.3f}  {first}")
    print(f"\nreport: {folder / 'report.md'}")
    return 0


def _run_crack(scene, folder, as_json: bool) -> int:
    from .crack_study import run_crack_study, write_crack_study

    result = write_crack_study(run_crack_study(scene), folder)
    if as_json:
        print(json.dumps({"scene": scene.name, "folder": str(folder),
                          "files": [str(f) for f in result.files],
                          "fe_cases_computed": result.computed,
                          "modes": result.mode_rows()}, indent=2))
        return 0
    print(f"scene {scene.name!r}: ring crack depths "
          f"{', '.join(f'{1e3 * d:.3g}' for d in result.depths)} mm "
          f"({result.computed} FE cases computed, {len(result.fe) - result.computed} cached)")
    print(f"{'mode':>4} {'type':<13} {'f intact [Hz]':>13} {'shift at deepest [%]':>21} "
          f"{'follows':>10}  smallest crack shifting >= {scene.threshold_percent:g} %")
    for r in result.mode_rows():
        depth = r["smallest_detectable_depth_mm"]
        print(f"{r['mode']:>4} {r['kind']:<13} {r['frequency_intact_hz']:>13.3f} "
              f"{r['shift_at_deepest_percent']:>21.3f} {r['follows']:>10}  "
              f"{'not reached' if depth is None else f'{depth:.3g} mm'}")
    print(f"\nreport: {folder / 'report.md'}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
