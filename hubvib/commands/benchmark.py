"""``hubvib benchmark [--json] [--quick] [--no-3d-scene]``: FE speed and memory, each timing a ratio against
its baseline measured in the same run (``hubvib.benchmarks``)."""
from __future__ import annotations

import sys

from hubvib.foundation.output import json_text

#: (key, label, unit, baseline key or None) of the printed table
ROWS = (
    ("c_ru_2d_seconds", "2D c_ru, mesh + FE", "s", "c_ru_2d_previous_seconds"),
    ("c_ru_2d_rel_error", "2D c_ru error against the reference", "", None),
    ("c_ru_2d_1e4_seconds", "2D work-conjugate c_ru to a verified 1e-4", "s",
     "c_ru_2d_1e4_previous_seconds"),
    ("c_ru_2d_1e4_previous_rel_error", "  the baseline (whole-ring route) lands at", "", None),
    ("crack_case_seconds", "crack case FE (c_ru, c_r, engaged c_rp; 2 levels)", "s",
     "crack_case_previous_seconds"),
    ("crack_case_max_rel_difference", "crack case: shared against separate solves", "", None),
    ("substructure_seconds_plane", "plane crack case by substructures (2 levels)", "s",
     "substructure_previous_seconds_plane"),
    ("substructure_max_rel_difference", "substructures against the whole ring (c_ru, c_r)", "",
     None),
    ("elastic_case_seconds", "elastic-ring crack case (coupled spectra)", "s",
     "elastic_case_baseline_seconds"),
    ("ci_seconds", "the repository's .ci/run", "s", None),
    ("solid_seconds", "3D c_ru: model + loads + solve", "s", "solid_previous_seconds"),
    ("calculix_seconds", "3D c_ru by CalculiX 2.20, same mesh and loads", "s", None),
    ("calculix_speedup", "CalculiX time / ours", "x", None),
    ("calculix_max_rel_difference", "displacements: CalculiX against ours", "", None),
    ("solid_peak_memory_gb", "peak memory of hubvib stiffness --solid", "GB", None),
    ("solid_solve_peak_memory_gb", "peak memory of the 3D solve alone", "GB",
     "solid_solve_peak_memory_gb_previous"),
    ("lumped_points_per_second", "lumped spectra per second (batched)", "1/s", None),
    ("main_job_fresh_seconds", "main job (hubvib run), empty cache", "s", None),
    ("main_job_cached_seconds", "main job, FE cases and renders cached", "s",
     "main_job_fresh_seconds"),
    ("main_job_rigid_ring_seconds", "main job with the rigid ring only, empty cache", "s",
     None),
    ("elastic_ring_time_ratio", "main job over the main job without the elastic ring", "x",
     None),
    ("elastic_ring_cpu_ratio", "  the same in CPU seconds (run and its workers)", "x", None),
    ("tests_seconds", "default test command (python -m pytest)", "s", None),
)


def add_parser(sub) -> None:
    p = sub.add_parser("benchmark", help="FE speed and memory against baselines run beside "
                       "them (CalculiX, the previous FE path, separate solves)")
    p.add_argument("--quick", action="store_true",
                   help="skip the 3D race, the memory probes, the main job and the tests "
                   "(a smoke test, ~1 min)")
    p.add_argument("--no-3d-scene", dest="scene_3d", action="store_false",
                   help="skip the 3D crack-growth scene (13 solid cases: ~8 min on 2 cores); "
                   "not with --quick (it skips it already)")
    p.add_argument("--ci", action="store_true",
                   help="also time the repository's .ci/run (ci_seconds; else null)")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    import hubvib.benchmarks as benchmarks

    from ._applies import FlagError

    if args.quick and not args.scene_3d:
        raise FlagError("--no-3d-scene applies only to a full run (--quick skips the 3D "
                        "scene already); drop it")

    figures = benchmarks.run_benchmark(quick=args.quick, scene_3d=args.scene_3d, ci=args.ci,
                            progress=lambda line: print(line, file=sys.stderr, flush=True))
    if args.json:
        print(json_text(figures))
        return 0
    print(f"{'figure':<52} {'value':>11} {'baseline':>11} {'ratio':>7}")
    for key, label, unit, baseline in ROWS:
        value = figures.get(key)
        if value is None:
            continue
        base = figures.get(baseline) if baseline else None
        ratio = f"{base / value:7.2f}" if base else f"{'':7}"
        base_text = f"{base:11.3g}" if base else f"{'':11}"
        print(f"{label + (f' [{unit}]' if unit else ''):<52} {value:11.3g} {base_text} {ratio}")
    if figures.get("main_job_stage_seconds"):
        print("main job, empty cache, per stage [s]: " + ", ".join(
            f"{key} {value:.3g}" for key, value in figures["main_job_stage_seconds"].items()))
    for key in ("substructure_solid_skipped", "solid_skipped", "calculix_skipped", "lumped_skipped", "signal_skipped",
                "main_job_skipped", "tests_skipped", "crack_growth_3d_skipped"):
        if key in figures:
            print(f"{key.removesuffix('_skipped').replace('_', ' ')}: {figures[key]}")
    print("ratio = baseline / ours (time or memory), measured in this run; seconds are wall "
          "times on a machine whose cores may be shared")
    return 0
