"""Detection on the elastic ring: the family POD against a Monte Carlo of the same
measurement model, the watched-mode rule, and the report's side-by-side answer."""
from __future__ import annotations

import numpy as np
import pytest

from hubvib.detection.elastic_model import ElasticDetail, bilinear_hz, elastic_mode_rows
from hubvib.detection.pod import family_pod
from hubvib.detection.result import DetectionResult
from hubvib.reports.elastic_sections import elastic_section, side_by_side
from hubvib.elastic.options import ElasticScene, parse_elastic_table
from hubvib.foundation.errors import SceneError


def test_family_pod_equals_a_monte_carlo_of_two_identified_records():
    """Two records (intact, now), each frequency identified with N(0, sigma^2) error; a
    mode alarms below -z(1 - alpha_m) sqrt(2) sigma; the family on any watched mode.
    The closed form against 4e5 simulated record pairs: within 4 standard errors."""
    from scipy.stats import norm

    rng = np.random.default_rng(7)
    shift = np.array([[0.0, 0.0, 0.0], [-1.0, -3.0, -0.2], [-2.5, -1.0, 0.5]])
    sigma = np.array([1.0, 1.5, 0.7])
    watched, rate = (0, 1, 2), 1 - (1 - 0.01) ** (1 / 3)
    closed = family_pod(shift, sigma, watched, rate)
    n = 400_000
    t = norm.ppf(1 - rate) * np.sqrt(2) * sigma
    for k in range(shift.shape[0]):
        e0 = rng.normal(0, sigma, (n, 3))
        e1 = rng.normal(0, sigma, (n, 3))
        alarm = (shift[k] + e1 - e0 < -t).any(axis=1).mean()
        error = np.sqrt(closed[k] * (1 - closed[k]) / n)
        assert abs(alarm - closed[k]) < 4 * error + 1e-12, (k, alarm, closed[k])
    assert abs(closed[0] - 0.01) < 1e-12  # the intact reducer alarms at the family rate


def _synthetic(samples=0, pod_nominal=None, scatter=()) -> DetectionResult:
    depths = (0.0, 0.003, 0.006)
    intact = np.array([1000.0, 2800.0, 4700.0])
    open_hz = intact + np.array([[0, 0, 0], [-0.5, -18.0, -26.0], [-1.0, -55.0, np.nan]])
    sigma = {10.0: np.array([0.8, 1.1, 1.5]), 60.0: np.array([0.3, 0.45, 0.6]),
             600.0: np.array([0.1, 0.14, 0.2])}
    pod = {t: family_pod(open_hz - intact, s, (2, 1), 0.005) for t, s in sigma.items()}
    detail = ElasticDetail(("rotational", "rotational", "translational"), (0, 3, 4), (0, 0, 1),
                           (0.1, 0.9, 0.8), open_hz.copy(), np.zeros((3, 3), dtype=bool),
                           np.array([0.05, 1.0, 0.6]), 2e9, (7e8, 1.8e6), 38000, np.pi / 2,
                           scatter=scatter)
    labels = ("elastic n=0 (rotational, 1000.0 Hz)", "elastic n=3 (rotational, 2800.0 Hz)",
              "elastic n=4 (translational, 4700.0 Hz)")
    return DetectionResult("elastic", depths, open_hz, labels, sigma, (2, 1), pod,
                           pod if pod_nominal is None else pod_nominal, 0.9, 0.01, 10.0,
                           samples, left_out=((0.009, "through the rim: the ring is opened, "
                                               "its modes no longer continue the intact "
                                               "ones"),), detail=detail)


def test_first_detectable_and_the_report_lines():
    det = _synthetic()
    assert det.first_detectable(10.0) == 0.003
    assert np.isnan(bilinear_hz(det)[2, 2])
    # bilinear: open half the time, intact (closed) the other half
    assert bilinear_hz(det)[1, 1] == pytest.approx(2 * 2782.0 * 2800.0 / (2782.0 + 2800.0))
    lines = "\n".join(side_by_side(None, det))
    assert "| 10 s | - | below 3 mm |" in lines
    section = "\n".join(elastic_section(det))
    assert "elastic n=4 (translational, 4700.0 Hz) record / bilinear [Hz]" in section
    assert "| 6 | - / - |" in section  # not tracked: a dash, never nan
    assert "nan" not in section.lower()
    # a depth left out says why
    assert "9 mm (through the rim: the ring is opened" in section


def test_rows_are_json_ready():
    import json

    rows = elastic_mode_rows(_synthetic())
    text = json.dumps(rows, allow_nan=False)
    json.dumps(_synthetic().to_dict(), allow_nan=False)
    assert '"watched": true' in text
    assert rows[2]["shift_open_hz"][2] is None


def test_elastic_table_defaults_and_refusals():
    assert parse_elastic_table({}) == ElasticScene(ring="rigid",
                                                   options=parse_elastic_table({}).options)
    assert parse_elastic_table({"ring": "both"}).elastic
    for table, words in (({"ring": "flexible"}, "ring"), ({"band_hz": 0}, "band_hz"),
                         ({"foundation_k_t_N_m2": 1e6}, "give both"),
                         ({"sensor": 1}, "unknown key")):
        with pytest.raises(SceneError, match=words):
            parse_elastic_table(table)


@pytest.mark.slow
def test_crack_scene_reports_both_ring_models(tmp_path):
    """A two-depth Raba crack scene with ``[elastic] ring = "both"``: results.json holds
    the elastic ring's answer, the report's short answer both models side by side and an
    Elastic ring section; the 6 mm crack moves the n = 3 and n = 4 coupled modes by tens of
    Hz (docs/elastic_ring.md: -55 and -69 Hz on the finer modal mesh), so the elastic ring
    detects it with 10 s records where the rigid ring does not."""
    import json

    from hubvib.cli import main

    scene = tmp_path / "both.toml"
    scene.write_text("""
[reducer]
preset = "raba118"
[crack]
depths = [0.0, 0.006]
through_rim = false
workers = 2
[detection]
samples = 200
map_samples = 20
mount_points = 2
[elastic]
ring = "both"
[output]
folder = "out"
plots = false
renders = false
""")
    assert main(["run", str(scene), "--out", str(tmp_path / "out")]) == 0
    results = json.loads((tmp_path / "out" / "results.json").read_text())
    elastic = results["elastic_ring"]
    crossing = elastic["pod_crossing"]["10"]  # depths added below 6 mm resolve it
    assert crossing["resolved"] and crossing["high_mm"] <= 6.0, crossing
    assert elastic["added_depths_mm"] and min(elastic["added_depths_mm"]) >= 0.5
    assert results["detection"]["family_pod"]["10"][1] < 0.9
    watched = [elastic["modes"][i - 1] for i in elastic["watched_modes"]]
    at_6mm = elastic["depths_mm"].index(6.0)
    assert min(m["shift_open_hz"][at_6mm] for m in watched) < -30
    report = (tmp_path / "out" / "report.md").read_text()
    assert report.count("## Short answer") == 1 and "## Elastic ring" in report
    assert f"| 10 s | not within the sweep (up to 6 mm) | {crossing['words']} |" in report
    assert (tmp_path / "out" / "elastic_ring.csv").stat().st_size > 0


def test_family_pod_over_sampled_reducers_is_their_mean_pod():
    """(samples, depths, modes) shifts: the family POD is the mean of each reducer's own
    (the identification noise integrated per reducer); NaN (not tracked) counts as no
    change."""
    rng = np.random.default_rng(2)
    shifts = rng.normal(-2.0, 1.0, (50, 3, 4))
    shifts[:, 0] = 0.0
    shifts[3, 2, 1] = np.nan
    sigma, watched, rate = np.array([1.0, 0.8, 1.2, 2.0]), (0, 1, 3), 0.004
    pooled = family_pod(shifts, sigma, watched, rate)
    each = np.mean([family_pod(s, sigma, watched, rate) for s in shifts], axis=0)
    assert np.allclose(pooled, each, rtol=1e-12)
    assert abs(pooled[0] - (1 - (1 - rate) ** 3)) < 1e-12


def test_monte_carlo_fields_have_defaults_and_reach_the_report():
    det = _synthetic(samples=2000, pod_nominal=_synthetic().pod,
                     scatter=(0.02, 0.10, 0.30, 0.01))
    assert _synthetic().samples == 0
    text = "\n".join(side_by_side(None, det))
    assert "2000 Monte Carlo reducers" in text
    assert "nominal reducer" in "\n".join(side_by_side(None, _synthetic()))


@pytest.mark.slow
def test_the_elastic_sweep_adds_depths_until_the_crossing_is_resolved(monkeypatch):
    """``studies.elastic_stage.refine_elastic`` on the small synthetic elastic ring (a
    crack softening it in proportion to depth, 4-12 mm computed): depths are added by
    bisection, none below 0.5 mm, at most 4 per record length, until each record length's
    POD crossing is resolved (within 0.5 mm, or below 0.5 mm); the POD at the sweep's own
    depths is unchanged by them (the same Monte Carlo reducers), and every added depth's
    case came through the case cache."""
    from dataclasses import replace

    from tests.elastic.test_elastic_diagnose import _synthetic_cases

    from hubvib.detection import elastic_model
    from hubvib.detection.resolution import FLOOR, MAX_ADDED, RESOLUTION
    from hubvib.studies import elastic_stage
    from hubvib.studies.scene import load_scene

    deepest = 0.012
    asked = []

    def case_at(design, crack, scene, k_rest):
        asked.append(crack.depth)
        return _synthetic_cases((0.0, crack.depth, deepest))[1]

    monkeypatch.setattr(elastic_model, "cached_case", case_at)
    from hubvib.detection import options as detection_options

    scene = load_scene(None)
    options = replace(detection_options.detection_options(scene), samples=100)
    monkeypatch.setattr(detection_options, "detection_options", lambda s: options)
    es = parse_elastic_table({"ring": "both"})
    monkeypatch.setattr(elastic_stage, "_elastic_scene", lambda s: es)
    depths = (0.0, 0.004, 0.008, deepest)
    cases = _synthetic_cases(depths)
    first = elastic_model.elastic_result(None, depths, lambda d: None, es, options, cases)
    refined = elastic_stage.refine_elastic(scene, first, cases)
    assert sorted(asked) == sorted(refined.added_depths) and refined.added_depths
    assert all(d >= FLOOR for d in refined.added_depths)
    assert len(refined.added_depths) <= MAX_ADDED * len(refined.lengths)
    for t in refined.lengths:
        b = refined.bracket(t)
        assert b.resolved, (t, b)
        assert b.high is None or b.high - b.low <= RESOLUTION + 1e-12 or b.high <= FLOOR, b
        kept = [refined.depths.index(d) for d in depths]
        assert np.array_equal(refined.pod[t][kept], first.pod[t]), t
