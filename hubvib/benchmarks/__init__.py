"""``hubvib benchmark``: every timing a ratio against a baseline run in the same process,
one module per figure.

The machine's cores are shared, so absolute seconds drift by 2-3x from one minute to the
next; each figure is therefore measured beside its baseline, interleaved, and the ratio
is the figure to trust.  The figures and their baselines:

- ``ring_2d``: 2D c_ru against the previous FE path (``hubvib.validation.previous_fe``) on
  the same mesh, and its error against finer uniform levels;
- ``crack_case``: a crack case with one shared factorisation per level against separate
  ones (``estimate_ring`` + ``engaged_ring_mesh``, as the crack sweep did);
- ``substructure``: a plane crack case by substructures (the crack study's default)
  against the whole ring meshed and factorised;
- ``elastic_case``: one elastic-ring crack case against the whole-ring plane crack case;
- ``solid``: 3D c_ru against CalculiX 2.20 (``ccx``, SPOOLES, 2 threads) and against the
  previous FE path, same mesh and nodal loads;
- ``memory``: peak memory of ``hubvib stiffness --solid`` and of the 3D solve alone;
- ``crack_growth``: the shipped 3D crack-growth scene from an empty cache (wall time);
- the lumped and signal stages report their own baselines
  (``hubvib.lumped.batch.benchmark_batch``, ``hubvib.signal.benchmark.benchmark_signal``);
- ``main_job``: the default scene from an empty cache and again cached, and the fresh
  run's time per stage (``main_job_stage_seconds``);
  ``tests_command``: the README's test command, from a source checkout;
- ``solid_mesh``: the 3D ring's meshing time against its element count
  (``tables.solid_mesh_table``, no baseline), the docs' table of it.

``python -m hubvib.benchmarks.tables`` prints the README's tables of error / size against
time.  Timings are measured here, never asserted in tests.
"""
from __future__ import annotations

import time

from hubvib.benchmarks.crack_case import crack_case
from hubvib.benchmarks.elastic_case import elastic_case_figures
from hubvib.benchmarks.substructure import substructure_speedup
from hubvib.benchmarks.crack_growth import crack_growth_3d
from hubvib.benchmarks.main_job import main_job
from hubvib.benchmarks.memory import memory_figures
from hubvib.benchmarks.ring_2d import (QUICK_REFERENCE_SCALES, QUICK_WORK_SCALES,
                                       REFERENCE_SCALES, ring_2d)
from hubvib.validation.convergence import NESTED_SCALES
from hubvib.benchmarks.solid import solid_figures
from hubvib.benchmarks.tables import solid_mesh_table
from hubvib.benchmarks.tests_command import readme_test_command
from hubvib.reducer import lumped_preset
from hubvib.design import preset_design
from hubvib.lumped.batch import benchmark_batch
from hubvib.signal.benchmark import benchmark_signal
from hubvib.validation import calculix as ccx


#: why ``substructure_speedup_solid`` is null
SOLID_NOT_SUBSTRUCTURED = ("the solid ring is not substructured: every solid case meshes "
                           "and factorises the whole (half-width) ring")


def run_benchmark(quick: bool = False, progress=None, scene_3d: bool = True,
                  ci: bool = False) -> dict:
    """Every figure of ``hubvib benchmark`` (SI: seconds, GB, N/m; ratios are baseline time
    over ours).  ``quick`` skips the 3D race and the memory probes, takes the 2D reference
    from the default level (``QUICK_REFERENCE_SCALES``), runs the crack case at scale 2
    and the signal stage over two revolutions; ``scene_3d=False`` skips the 3D
    crack-growth scene (``crack_growth_3d_seconds`` is then null and said skipped).
    ``substructure_speedup_plane``: a plane crack case, whole ring over substructures
    (``substructure_speedup_solid``: null, ``substructure_solid_skipped`` says why);
    ``elastic_case_seconds``: one elastic-ring crack case beside the whole-ring plane crack
    case (``elastic_case_baseline_seconds``); ``ci_seconds``: the wall time of ``.ci/run``
    with ``ci``, else null."""
    say = progress or (lambda line: None)
    started = time.perf_counter()
    out = {"quick": quick}
    out.update(ring_2d(reference_scales=QUICK_REFERENCE_SCALES if quick else REFERENCE_SCALES,
                       progress=say, work_scales=QUICK_WORK_SCALES if quick else NESTED_SCALES))
    out.update(crack_case(scale=2.0 if quick else 1.0, progress=say))
    out.update(substructure_speedup(scale=2.0 if quick else 1.0, progress=say))
    out["substructure_speedup_solid"] = None
    out["substructure_solid_skipped"] = SOLID_NOT_SUBSTRUCTURED
    out.update(elastic_case_figures(progress=say))
    out["ci_seconds"] = ci_seconds(say) if ci else None
    skipped = "skipped (--quick)"
    if quick:
        out.update({key: None for key in (
            "calculix_speedup", "calculix_max_rel_difference", "solid_peak_memory_gb",
            "crack_growth_3d_seconds")})
        out["solid_skipped"] = skipped
        out["solid_mesh"] = None
    else:
        out.update(solid_figures(say))
        if not ccx.available():
            out.update(calculix_speedup=None, calculix_max_rel_difference=None,
                       calculix_skipped="ccx not found: install Debian's calculix-ccx")
        out.update(memory_figures(say))
        out["solid_mesh"] = solid_mesh_table()
        say("3D meshing table: done")
        out.update(crack_growth_3d(say) if scene_3d else {
            "crack_growth_3d_seconds": None, "crack_growth_3d_skipped": "skipped (--no-3d-scene)"})
    out["lumped"] = benchmark_batch(lumped_preset("raba118"))
    out["lumped_points_per_second"] = out["lumped"]["points_per_second"]
    say(f"lumped: {out['lumped_points_per_second']:.0f} points/s")
    # --quick: two carrier revolutions instead of ten (its solve_ivp baseline takes minutes)
    out["signal"] = benchmark_signal(preset_design("raba118"), lumped_preset("raba118"),
                                     **({"revolutions": 2} if quick else {}))
    say("signal: done")
    if quick:
        out.update(main_job_fresh_seconds=None, main_job_cached_seconds=None,
                   main_job_stage_seconds=None, main_job_rigid_ring_seconds=None,
                   elastic_ring_time_ratio=None, elastic_ring_cpu_ratio=None,
                   tests_seconds=None, main_job_skipped=skipped, tests_skipped=skipped)
    else:
        out.update(main_job(say))
        out.update(readme_test_command(say))
    out["seconds_total"] = time.perf_counter() - started
    return out


def ci_seconds(progress) -> float:
    """Wall time [s] of the repository's ``.ci/run`` (RuntimeError if it fails)."""
    import subprocess
    from pathlib import Path

    script = Path(__file__).resolve().parents[2] / ".ci" / "run"
    if not script.is_file():
        raise RuntimeError(f"no CI script at {script}")
    started = time.perf_counter()
    result = subprocess.run([str(script)], cwd=script.parents[1], capture_output=True, text=True)
    seconds = time.perf_counter() - started
    if result.returncode != 0:
        raise RuntimeError(f".ci/run failed (exit {result.returncode}): "
                           f"{result.stderr.strip().splitlines()[-1:] or ''}")
    progress(f".ci/run: {seconds:.0f} s")
    return seconds


__all__ = ["REFERENCE_SCALES", "run_benchmark"]
