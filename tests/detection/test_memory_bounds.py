"""Memory within documented bounds.  The POD Monte Carlo and the
detectability map are estimated from the array shapes when the scene is parsed and refused
above the memory budget (one error line, exit 2, nothing written); the eigen-solves run in
chunks (the same numbers as in one piece); a long map reports progress off a terminal."""
from __future__ import annotations

import tracemalloc

import numpy as np
import pytest
from tests.helpers.synthetic_rows import TIMING, synthetic_model

from hubvib.cli import main
from hubvib.detection import budget, detectability
from hubvib.detection.budget import MEMORY_BUDGET, check_scene, estimate
from hubvib.detection.diagnosis import reference
from hubvib.detection.options import DetectionOptions
from hubvib.detection.pod import RECORD_LENGTHS, pod_study
from hubvib.foundation.errors import SceneError
from hubvib.identification.law import _fisher_sigma_hz
from hubvib.studies.scene import default_scene_text, load_scene, parse_scene


def _scene(tmp_path, old, new):
    text = default_scene_text()
    assert old in text, f"default scene has no {old!r}"
    path = tmp_path / "big.toml"
    path.write_text(text.replace(old, new).replace(
        'folder = "hubvib-out/raba118-crack"', f'folder = "{tmp_path / "scene-out"}"'),
        encoding="utf-8")
    return path


def test_samples_beyond_the_memory_budget_are_refused_before_anything_runs(tmp_path, capsys):
    # samples = 1000000 was allowed and took 24 GB until the kernel killed it
    scene = _scene(tmp_path, "samples = 2000", "samples = 1000000")
    out = tmp_path / "out"
    assert main(["run", str(scene), "--out", str(out)]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hubvib: error: "), captured.err
    for piece in ("[detection] samples = 1000000", "GiB", "over 9 crack depths",
                  "allowed: an integer in [100, "):
        assert piece in lines[0], f"{piece!r} not in {lines[0]!r}"
    assert "Traceback" not in captured.err
    assert not out.exists() and not (tmp_path / "scene-out").exists(), \
        "a refused scene must write nothing"


def test_the_refusal_names_the_largest_allowed_value_and_it_is_accepted(tmp_path):
    with pytest.raises(SceneError) as info:
        load_scene(_scene(tmp_path, "samples = 2000", "samples = 1000000"))
    largest = int(info.value.args[0].split(", ")[-1].split("]")[0])
    scene = load_scene(_scene(tmp_path, "samples = 2000", f"samples = {largest}"))
    depths = len(scene.study.depths)
    assert estimate(scene.params, depths, largest).peak_bytes <= MEMORY_BUDGET
    assert estimate(scene.params, depths, largest + 1).peak_bytes > MEMORY_BUDGET, \
        "the named bound is the largest value within the budget"


def test_map_samples_beyond_the_budget_are_refused_naming_the_key(tmp_path, capsys):
    # the map runs one Monte Carlo of map_samples per mounting value, one at a time
    scene = parse_scene(default_scene_text(), "raba118_crack")
    budget_bytes = 256 * 2**20
    with pytest.raises(SceneError) as info:
        check_scene(DetectionOptions(map_samples=100_000), scene.study, scene.params,
                    budget_bytes)
    message = info.value.args[0]
    assert message.startswith("[detection] map_samples = 100000: ") and "[20, " in message, \
        message
    largest = int(message.split(", ")[-1].split("]")[0])
    check_scene(DetectionOptions(map_samples=largest), scene.study, scene.params, budget_bytes)


def test_the_shipped_settings_are_well_within_the_budget():
    scene = parse_scene(default_scene_text(), "raba118_crack")
    peak = estimate(scene.params, len(scene.study.depths),
                    scene.tables["detection"].samples).peak_bytes
    assert peak < MEMORY_BUDGET / 10, f"default scene: {peak} B"


def test_chunked_monte_carlo_gives_the_numbers_of_one_piece():
    # each parameter point is solved on its own (stacked LAPACK), so splitting the samples
    # into chunks changes nothing: compared bit for bit (tolerance 0) with one piece
    model = synthetic_model("series")
    options = DetectionOptions(samples=300)
    whole = pod_study(model, options, TIMING, chunk_points=10**9)
    chunked = pod_study(model, options, TIMING, chunk_points=2 * len(model.depths) * 7)
    for name in ("pod", "pod_model", "threshold_model_hz", "shift_mean_hz", "shift_p05_hz",
                 "shift_p95_hz"):
        np.testing.assert_array_equal(getattr(chunked, name), getattr(whole, name),
                                      err_msg=f"{name}: chunked vs one piece, exact")
    for T in whole.family_pod:
        np.testing.assert_array_equal(chunked.family_pod_drift[T], whole.family_pod_drift[T],
                                      err_msg=f"family POD with drift, T = {T} s, exact")


def test_the_diagnosis_reference_is_chunked_with_the_same_numbers(monkeypatch):
    model = synthetic_model("series")
    options = DetectionOptions(samples=150)
    whole = reference(model, options, TIMING)
    monkeypatch.setattr(budget, "CHUNK_POINTS", 2 * len(model.depths) * 11)
    chunked = reference(model, options, TIMING)
    np.testing.assert_array_equal(chunked.frequency_hz, whole.frequency_hz,
                                  err_msg="diagnosis reference: chunked vs one piece, exact")


def _peak(call) -> int:
    # the identification bound is remembered per (frequency, record); the estimate is for
    # a cold run, so the measurement starts cold too
    _fisher_sigma_hz.cache_clear()
    tracemalloc.start()
    try:
        call()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


@pytest.mark.slow
@pytest.mark.parametrize("samples, baseline, damping, chunk, phase", [
    (300, False, 0.02, None, "identification band"),
    (1500, True, 0.02, None, "identification band"),
    (2000, False, 0.001, None, "chunk of solves"),
    (2000, True, 0.001, 256, "statistics")])
def test_the_estimate_is_within_a_factor_2_of_the_measured_peak(samples, baseline, damping,
                                                                chunk, phase):
    # independent measurement: tracemalloc's peak of the traced (numpy) allocations; the
    # cases make each of the three phases of the estimate the largest in turn
    model = synthetic_model("series")
    options = DetectionOptions(samples=samples, damping_ratio=damping)
    measured = _peak(lambda: pod_study(model, options, TIMING, model_baseline=baseline,
                                       chunk_points=chunk))
    found = estimate(model.params, len(model.depths), samples, baseline, options,
                     chunk_points=chunk)
    largest = max(found.array_bytes + found.solve_bytes,
                  2 * found.array_bytes + found.band_bytes,
                  budget.KEPT_ARRAYS * found.array_bytes)
    assert {"chunk of solves": found.array_bytes + found.solve_bytes,
            "identification band": 2 * found.array_bytes + found.band_bytes,
            "statistics": budget.KEPT_ARRAYS * found.array_bytes}[phase] == largest, phase
    assert 0.5 <= found.peak_bytes / measured <= 2.0, \
        f"samples {samples}: estimate {found.peak_bytes} B vs tracemalloc peak {measured} B"


@pytest.mark.slow
def test_chunks_keep_the_solve_memory_from_growing_with_samples():
    # in one piece the peak grows with the B and B^T B of every parameter point (~6 kB
    # each); in chunks only the (samples, depths, modes) statistics grow.  A small damping
    # keeps the identification band (which does not grow with samples) out of the peak.
    model = synthetic_model("series")
    options = DetectionOptions(samples=2000, damping_ratio=0.001)
    whole = _peak(lambda: pod_study(model, options, TIMING, model_baseline=False,
                                    chunk_points=10**9))
    chunked = _peak(lambda: pod_study(model, options, TIMING, model_baseline=False))
    assert chunked < whole / 3, f"chunked peak {chunked} B vs one piece {whole} B"


def test_the_longest_record_of_the_estimate_is_the_pod_s():
    assert budget.LONGEST_RECORD == max(RECORD_LENGTHS)


def test_a_record_length_whose_band_exceeds_the_budget_is_refused():
    # the Cramer-Rao bound runs over f (1 +- kappa zeta) in bins of 1/T: record_length_s =
    # 1e5 s takes ~25 GB for the 6.9 kHz highest mode of Raba 118/76
    scene = parse_scene(default_scene_text(), "raba118_crack")
    with pytest.raises(SceneError) as info:
        check_scene(DetectionOptions(record_length=1e5), scene.study, scene.params)
    message = info.value.args[0]
    assert message.startswith("[detection] record_length_s = 100000: ") and \
        "allowed: a number in (0, " in message, message
    longest = float(message.split("(0, ")[-1].rstrip("]"))
    check_scene(DetectionOptions(record_length=0.99 * longest), scene.study, scene.params)


def test_a_long_map_reports_progress_lines_off_a_terminal(monkeypatch, capsys):
    monkeypatch.setattr(detectability, "PROGRESS_SOLVES", 0)
    options = DetectionOptions(map_samples=20, mount_points=2)
    detectability.detectability_map(synthetic_model("series"), options, TIMING)
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 4, lines
    assert lines[0].startswith("detectability map: 1/4 mountings (c_ru_mount = 1e+06 N/m)")
    assert lines[-1].startswith("detectability map: 4/4 mountings (c_r_mount = 1e+12 N/m)")


def test_a_short_map_stays_quiet(capsys):
    options = DetectionOptions(map_samples=20, mount_points=2)
    detectability.detectability_map(synthetic_model("series"), options, TIMING)
    assert capsys.readouterr().err == ""


def test_a_map_of_200_mount_points_is_long_enough_to_report():
    # map_samples = 1e5 with mount_points = 200 (the reference case) is above the threshold
    scene = parse_scene(default_scene_text(), "raba118_crack")
    solves = 2 * 200 * estimate(scene.params, len(scene.study.depths), 100_000, False).solves
    assert solves > detectability.PROGRESS_SOLVES
    default = 2 * 13 * estimate(scene.params, len(scene.study.depths), 200, False).solves
    assert default < detectability.PROGRESS_SOLVES, "the default map stays quiet"
