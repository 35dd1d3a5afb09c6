"""The benchmark's baselines and reference values, and ``hubvib benchmark`` (timings are
measured there, never asserted here)."""
import json
import math
import sys

import numpy as np
import pytest

from hubvib.cli import main


def test_reference_is_richardson_in_the_asymptotic_range():
    """v_k = R + C h_k^2 with h shrinking by sqrt 2: Richardson of the last three gives R
    (to rounding) and reports the order 2."""
    from hubvib.validation.convergence import reference_value

    h = 2.0 ** (-np.arange(5) / 2)
    values = 1.7e10 + 3e8 * h ** 2
    limit, how = reference_value(list(values), math.sqrt(2))
    assert limit == pytest.approx(1.7e10, rel=1e-12)
    assert "order 2.00" in how


@pytest.mark.parametrize("values", [[1.0, 1.1, 1.2, 1.3], [1.0, 1.2, 1.1, 1.15]],
                         ids=["flat increments", "oscillating"])
def test_reference_outside_the_asymptotic_range_is_the_finest_level(values):
    """Equal steps (no convergence seen: c_ru's finest levels) or alternating ones: no
    extrapolation, the finest value, labelled as such."""
    from hubvib.validation.convergence import reference_value

    limit, how = reference_value(values, math.sqrt(2))
    assert limit == values[-1] and how.startswith("finest level")


def test_ring_levels_reach_past_the_default():
    """The c_ru table goes at least two levels finer than the default
    (scale 1), and its reference levels are all finer than the default."""
    from hubvib.benchmarks.ring_2d import REFERENCE_SCALES
    from hubvib.validation.convergence import scales_of

    for quantity in ("c_ru", "c_r", "c_sp", "c_rp"):
        assert sum(s < 1 for s in scales_of(quantity)) >= 2
    assert scales_of("c_ru")[-3:] == REFERENCE_SCALES and max(REFERENCE_SCALES) < 1


@pytest.mark.slow
def test_previous_path_solves_the_same_problem():
    """The baseline (previous FE path: eager basis, triplet assembly, scikit-fem's facet
    bases, K[free][:, free]) gives the c_ru and c_r of today's path on the same mesh to
    1e-10: the timings compare the same computation."""
    pytest.importorskip("gmsh")
    from hubvib.fem.ring_stiffness import ring_stiffness
    from hubvib.reducer import raba118
    from hubvib.meshing.levels import scaled_options
    from hubvib.meshing.ring_mesh import ring_mesh
    from hubvib.validation.previous_fe import previous_ring_fe

    ring = raba118.ring_gear()
    mesh = ring_mesh(ring, None, scaled_options(8.0))  # any mesh: both paths solve it
    ours = ring_stiffness(ring, mesh)
    previous = previous_ring_fe(ring, mesh)
    np.testing.assert_allclose(previous["c_ru"], ours.c_ru_positions, rtol=1e-10)
    assert previous["c_r"] == pytest.approx(ours.c_r, rel=1e-10)


def test_peak_memory_of_a_command():
    """A child that holds 300 MB peaks above 0.3 GB (and far below the 2 GB a leak would
    show); a failing child is an error, not a number."""
    from hubvib.benchmarks.memory import peak_memory_gb

    touch = "a = bytearray(300_000_000); a[::4096] = b'x' * len(a[::4096])"
    gb = peak_memory_gb([sys.executable, "-c", touch])
    assert 0.3 <= gb < 2.0
    with pytest.raises(RuntimeError, match="failed"):
        peak_memory_gb([sys.executable, "-c", "raise SystemExit(3)"])


FIGURES = {"quick": True, "c_ru_2d_seconds": 1.5, "c_ru_2d_previous_seconds": 2.6,
           "c_ru_2d_rel_error": 6e-4, "crack_case_seconds": 3.0,
           "crack_case_previous_seconds": 6.0, "crack_case_max_rel_difference": 1e-14,
           "calculix_speedup": None, "calculix_max_rel_difference": None,
           "solid_peak_memory_gb": None, "solid_skipped": "skipped (--quick)",
           "lumped_points_per_second": 2.5e4, "lumped": {"points_per_second": 2.5e4},
           "signal": None, "signal_skipped": "hubvib.signal.benchmark_signal not available"}


def test_benchmark_command_prints_ratios_and_standard_json(monkeypatch, capsys):
    """The command is thin: the library's figures as standard JSON (nulls, no NaN), or a
    table whose ratio column is baseline / ours."""
    import hubvib.benchmarks as benchmark

    calls = []
    monkeypatch.setattr(benchmark, "run_benchmark", lambda quick, progress, scene_3d, ci:
                        calls.append((quick, scene_3d, ci)) or dict(FIGURES))
    assert main(["benchmark", "--quick", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["calculix_speedup"] is None and data["c_ru_2d_seconds"] == 1.5
    assert main(["benchmark", "--no-3d-scene", "--json"]) == 0
    capsys.readouterr()
    assert main(["benchmark", "--quick", "--ci", "--json"]) == 0
    capsys.readouterr()
    assert calls == [(True, True, False), (False, False, False), (True, True, True)]
    assert main(["benchmark", "--quick"]) == 0
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("2D c_ru, mesh + FE"))
    assert row.split()[-1] == f"{2.6 / 1.5:.2f}"
    assert "signal: hubvib.signal.benchmark_signal not available" in out


@pytest.mark.slow
def test_quick_benchmark_runs():
    """The smoke test of the whole benchmark: the previous path and the shared crack case
    give the same numbers (1e-9), the 2D c_ru level is within 0.1 % of the default level."""
    pytest.importorskip("gmsh")
    from hubvib.benchmarks import run_benchmark

    figures = run_benchmark(quick=True)
    assert figures["c_ru_2d_previous_max_rel_difference"] < 1e-9
    assert figures["crack_case_max_rel_difference"] < 1e-9
    assert figures["c_ru_2d_rel_error"] < 1e-3
    # substructures and the whole ring are two discretisations: they agree within the
    # crack case's own error estimate (fine against coarse level)
    assert figures["substructure_max_rel_difference"] <= figures[
        "substructure_rel_error_estimate"], "substructured vs whole-ring c_ru, c_r"
    assert figures["substructure_speedup_plane"] > 0
    assert figures["substructure_speedup_solid"] is None and figures["ci_seconds"] is None
    assert "not substructured" in figures["substructure_solid_skipped"], "null with a reason"
    assert figures["elastic_case_seconds"] > 0 and figures["elastic_case_baseline_seconds"] > 0
    assert figures["elastic_case_ratio"] == pytest.approx(
        figures["elastic_case_seconds"] / figures["elastic_case_baseline_seconds"], rel=1e-12)
    json.dumps(figures, allow_nan=False)


def test_main_job_and_test_command_failures_are_named_not_timed(monkeypatch):
    import subprocess

    from hubvib.benchmarks.main_job import main_job
    from hubvib.benchmarks.tests_command import readme_test_command

    def failing(command, **kwargs):
        return subprocess.CompletedProcess(command, 2, "1 failed, 9 passed\n",
                                           "hubvib: error: no display\n")

    monkeypatch.setattr(subprocess, "run", failing)
    assert main_job() == {"main_job_fresh_seconds": None,
                                    "main_job_cached_seconds": None,
                                    "main_job_stage_seconds": None,
                                    "main_job_skipped": "hubvib run (fresh) failed: hubvib: "
                                                        "error: no display"}
    assert readme_test_command() == {
        "tests_seconds": None, "tests_skipped": "the tests failed: 1 failed, 9 passed"}
