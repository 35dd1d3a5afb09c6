"""The docs' benchmark tables come from ``docs/data/benchmark.json`` only: a figure the
committed run does not hold says "not measured" instead of failing the docs build, and a
figure it holds is printed from it (no timing typed by hand)."""
import copy
import importlib.util
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]
TABLES = ("benchmark_fe", "benchmark_full", "benchmark_solid_mesh", "benchmark_crack_growth_3d")


@pytest.fixture
def generate():
    spec = importlib.util.spec_from_file_location("docs_generate_bench",
                                                  ROOT / "docs" / "generate.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _committed() -> dict:
    return json.loads((ROOT / "docs" / "data" / "benchmark.json").read_text())


def _with(generate, monkeypatch, figures):
    monkeypatch.setattr(generate, "_benchmark", lambda: figures)


@pytest.mark.parametrize("missing", ["main_job_fresh_seconds", "crack_growth_3d_seconds",
                                     "solid_mesh", "c_ru_2d_speedup", "lumped"])
def test_a_figure_the_run_lacks_says_not_measured(generate, monkeypatch, missing):
    figures = copy.deepcopy(_committed())
    figures.pop(missing, None)
    _with(generate, monkeypatch, figures)
    text = "\n".join(getattr(generate, name)() for name in TABLES)
    assert generate.NOT_MEASURED in text, missing


def test_an_empty_run_still_builds_every_benchmark_table(generate, monkeypatch):
    _with(generate, monkeypatch, {})
    for name in TABLES:
        assert generate.NOT_MEASURED in getattr(generate, name)(), name


def test_measured_figures_are_printed_from_the_json(generate, monkeypatch):
    figures = copy.deepcopy(_committed())
    figures.update(main_job_fresh_seconds=123.4, main_job_cached_seconds=2.5,
                   crack_growth_3d_seconds=270.0,
                   solid_mesh=[{"case": "intact", "tooth_size_mm": 4.0, "elements": 85_000,
                                "nodes_p2": 130_000, "volume_rel_error": 1e-4,
                                "straightened": 3, "seconds": 8.94}])
    _with(generate, monkeypatch, figures)
    full = generate.benchmark_full()
    row = next(line for line in full.splitlines() if line.startswith("| main job"))
    assert row.split("|")[2:5] == [" 123 s ", " 2.5 s ", " 49.4 "], row  # 123.4 / 2.5
    assert "took 4.5 minutes" in generate.benchmark_crack_growth_3d()
    mesh = generate.benchmark_solid_mesh()
    assert "| intact | 4 | 85,000 | 130,000 | 8.94 |" in mesh, mesh


def test_no_page_types_a_benchmark_timing_by_hand():
    """The pages that quote the benchmark hold its markers, and no hand-typed 3D meshing
    or crack-growth time is left beside them."""
    fe = (ROOT / "docs" / "fe_accuracy.md").read_text()
    growth = (ROOT / "docs" / "crack_growth_3d.md").read_text()
    assert "<!-- gen: benchmark_solid_mesh -->" in fe
    assert "<!-- gen: benchmark_crack_growth_3d -->" in growth
    assert not re.search(r"\| \d+k tetrahedra \| [\d.–-]+ s \|", fe)
    assert "15 minutes" not in growth and "9 minutes" not in growth


def test_the_1e4_route_row_shows_both_routes_and_their_ratio(generate, monkeypatch):
    figures = copy.deepcopy(_committed())
    figures.update(c_ru_2d_1e4_seconds=0.5, c_ru_2d_1e4_previous_seconds=4.0,
                   c_ru_2d_1e4_previous_rel_error=2.3e-4,
                   c_ru_2d_1e4_route="Richardson of the first three pitch levels")
    _with(generate, monkeypatch, figures)
    row = next(line for line in generate.benchmark_fe().splitlines()
               if line.startswith("| 2D work-conjugate c_ru to a verified 1e-4"))
    assert "pitch levels" in row and "2.3e-04 from the reference" in row, row
    assert row.split("|")[2:5] == [" 4.00 s ", " 0.50 s ", " 8 "], row  # 4.0 / 0.5
    figures.pop("c_ru_2d_1e4_seconds")
    assert generate.NOT_MEASURED in generate.benchmark_fe()
