"""``hubvib run [SCENE]``: run a scene file or a shipped scene by name."""
from __future__ import annotations

import importlib.util
import sys
import time
from pathlib import Path

from hubvib.foundation.output import json_text, output_set
from hubvib.runtime.progress import stage


def add_parser(sub) -> None:
    p = sub.add_parser("run", help="run a scene (default: the embedded Raba 118/76 study)")
    p.add_argument("scene", nargs="?", help="scene TOML file, or the name of a shipped scene "
                   "(hubvib scenes lists them)")
    p.add_argument("--out", type=Path, help="output folder (overrides the scene's)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


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


def run(args) -> int:
    from hubvib.studies.scene import load_scene

    scene = load_scene(args.scene)
    missing = _missing_extras(scene)
    if missing:
        print(f"hubvib: error: {missing}", file=sys.stderr)
        return 2
    folder = Path(args.out or scene.folder)
    if scene.crack is not None:  # before any work: the FE results must have a place to go
        from hubvib.runtime.cache_check import check_writable

        check_writable("stiffness")
    # the folder is checked and locked before any work; the files go to a stage and
    # move into place together when all are written (printing comes after: a closed
    # stdout must not cost the files)
    with output_set(folder) as staged:
        result = (_crack_study if scene.crack is not None else _lumped_study)(scene, staged)
    files = [folder / Path(f).relative_to(staged) for f in result.files]
    if scene.crack is not None and scene.crack.model == "solid":
        return _print_growth(scene, result, folder, files, args.json)
    if scene.crack is not None:
        return _print_crack(scene, result, folder, files, args.json)
    return _print_lumped(scene, result, folder, files, args.json)


def _lumped_study(scene, staged: Path):
    from hubvib.studies.sweep import run_study, write_study

    started = time.perf_counter()
    result = run_study(scene)
    stage(f"lumped spectra and shifts of {len(scene.values)} values", started)
    started = time.perf_counter()
    write_study(result, staged)
    stage(f"tables{', plots' if scene.plots else ''} and report", started)
    return result


def _crack_growth(scene, staged: Path):
    from hubvib.studies.crack_growth import run_crack_growth, write_crack_growth

    started = time.perf_counter()
    result = run_crack_growth(scene)
    stage(f"FE stage ({result.computed} of {len(result.rows) + len(result.plane)} cases "
          f"computed) and lumped spectra of {len(result.studies)} half-lengths", started)
    started = time.perf_counter()
    write_crack_growth(result, staged)
    stage("tables, plots and reports", started)
    return result


def _crack_study(scene, staged: Path):
    from hubvib.studies.crack_study import run_crack_study, write_crack_study

    if scene.crack.model == "solid":
        return _crack_growth(scene, staged)
    started = time.perf_counter()
    result = run_crack_study(scene)
    stage(f"FE stage ({result.computed} of {len(result.fe)} cases computed) and lumped "
          "spectra", started)
    started = time.perf_counter()
    if "signal" in scene.tables:  # the vibration signature beside the frequency study
        from hubvib.signal.report import write_signal_study
        from hubvib.signal.study import run_signal_study

        study = run_signal_study(scene)
        stage(f"signals of {len(study.depths)} crack depth(s)", started)
        signal_files = write_signal_study(study, staged / "signal", plots=scene.plots)["files"]
        started = time.perf_counter()
    write_crack_study(result, staged)
    if "signal" in scene.tables:
        from hubvib.foundation.output import write_text

        report = staged / "report.md"
        write_text(report, report.read_text(encoding="utf-8") + (
            "\n## Vibration signature\n\nThe signal a sensor on the ring records, its order "
            "spectrum, spectrogram and condition indicators against crack depth: "
            "[signal/report.md](signal/report.md).\n"))
        result.files += [staged / "signal" / f for f in signal_files]
    stage("tables, plots, renders and report", started)
    return result


def _print_lumped(scene, result, folder: Path, files: list[Path], as_json: bool) -> int:
    if as_json:
        print(json_text({"scene": scene.name, "folder": str(folder),
                         "files": [str(f) for f in files],
                         "detection": result.detection()}))
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


def _print_growth(scene, result, folder: Path, files: list[Path], as_json: bool) -> int:
    grid = result.grid_rows()
    if as_json:
        print(json_text({"scene": scene.name, "folder": str(folder),
                         "files": [str(f) for f in files],
                         "fe_cases_computed": result.computed, "grid": grid}))
        return 0
    print(f"scene {scene.name!r}: semi-elliptic ring root cracks, {len(grid) - 1} solid cases "
          f"({result.computed} FE cases computed, the others cached)")
    print(f"{'depth [mm]':>10} {'half-length [mm]':>16} {'c_ru change [%]':>16} {'+-':>7} "
          f"{'1/2 poor':>8} {'plane through [%]':>17} {'c_rp ratio':>10}")
    for r in grid[1:]:
        print(f"{r['depth_mm']:>10.3g} {r['half_length_mm']:>16.3g} "
              f"{r['c_ru_change_percent']:>+16.3f} {r['c_ru_change_error_percent']:>7.3f} "
              f"{r['c_ru_change_poor_cells_percent']:>+8.3f} "
              f"{r['plane_through_c_ru_change_percent']:>+17.3f} {r['c_rp_slice_ratio']:>10.4f}")
    print("+-: fine minus coarse level; 1/2 poor: the change with the cells of min SICN < 0.1 "
          "at half stiffness (take the larger)")
    print(f"\nreport: {folder / 'report.md'}")
    return 0


def _print_crack(scene, result, folder: Path, files: list[Path], as_json: bool) -> int:
    if as_json:
        print(json_text({"scene": scene.name, "folder": str(folder),
                         "files": [str(f) for f in files],
                         "fe_cases_computed": result.computed,
                         "modes": result.mode_rows()}))
        return 0
    print(f"scene {scene.name!r}: ring crack depths "
          f"{', '.join(f'{1e3 * d:.3g}' for d in result.depths)} mm "
          f"({result.computed} FE cases computed, {len(result.fe) - result.computed} cached)")
    from hubvib.detection.numbers import percent

    rows = result.mode_rows()
    physical = "detectable_depth_mm" in rows[0]
    if physical:
        from hubvib.detection.options import DetectionOptions

        pod = scene.tables.get("detection", DetectionOptions()).detection_probability
        last = f"detectable from (POD >= {pod:g}), via"
    else:
        last = f"smallest crack shifting >= {scene.threshold_percent:g} %"
    print(f"{'mode':>4} {'type':<13} {'f intact [Hz]':>13} {'shift at deepest [%]':>21} "
          f"{'follows':>10}  {last}")
    for r in rows:
        depth = r["detectable_depth_mm"] if physical else r["smallest_detectable_depth_mm"]
        where = f" ({r['signal_in']})" if physical and depth is not None else ""
        print(f"{r['mode']:>4} {r['kind']:<13} {r['frequency_intact_hz']:>13.3f} "
              f"{percent(r['shift_at_deepest_percent']):>21} {r['follows']:>10}  "
              f"{'not detectable' if depth is None else f'{depth:.3g} mm'}{where}")
    print(f"\nreport: {folder / 'report.md'}")
    return 0

