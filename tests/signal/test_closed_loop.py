"""Closed loop: records simulated by ``hubvib signal`` are read by
``hubvib diagnose --record ... --baseline-record ...``, which recovers the crack depth.

Settings of the loop (the shipped scene ``raba118_closed_loop``): Raba 118/76 (preset), plane root crack of tooth
0, fast FE; signal model ``mesh_stiffness = "ratio"`` (so diagnose uses the ratio crack
model, hubvib.detection.diagnosis.scene_reference); modal damping 1 %; records of 325
carrier revolutions (45.0 s) at 20 kHz; ambient forcing 10 N^2/Hz (one-sided) on each
central coordinate plus 5 % white noise and the periodic mesh response, its lines
notched by the identifier; ``contact = "linear"`` (at 1 % damping the periodic response
unloads the sun meshes and the piecewise model has no steady state; the ambient part and
the identification do not depend on it).  The degenerate pairs of the intact model (modes 3/4, 5/6,
7/8, 11/12, 13/14, 16/17, the translational modes of the cyclically symmetric stage)
cannot be told apart by the single-mode identifier and are skipped; the route uses the
distinct modes identified in both records.  The informative one is mode 15 (5050 Hz, the
planets' ring-mesh mode: -1.64 / -2.13 / -2.31 Hz at 6 / 12 / 18 mm in this scene's
ratio model, against about 0.6 Hz standard deviation of a shift at 1 % damping and
45 s: Au's law 0.43 Hz per record); modes 1, 2 and 9 barely move (< 0.05 Hz).
"""
import contextlib
import io
import json
import math

import pytest

from hubvib.cli import main
from hubvib.signal.frequency_route import observed_hz
from hubvib.signal.mesh_phase import design_phasing
from hubvib.signal.signature_study import curves_for
from hubvib.studies.scene import load_scene, shipped_scene_text

TRUE_DEPTH = 0.012
#: the shipped closed-loop scene (scenes/raba118_closed_loop.toml)
SCENE = shipped_scene_text("raba118_closed_loop")


@pytest.fixture(scope="module", autouse=True)
def _shared_fe_cases(shared_cache_folder):
    """The loop's plane FE cases at 0, 6 and 12 mm (fast accuracy, root crack of tooth 0)
    are the shipped signal scene's, which test_scenes and test_signal_cli run: the run's
    shared FE cache (conftest ``shared_cache_folder``) computes them once."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("HUBVIB_CACHE", str(shared_cache_folder))
        yield


@pytest.fixture(scope="module")
def scene_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("loop") / "loop.toml"
    path.write_text(SCENE)
    return path


def _law_shift_hz(scene, curves):
    """Frequency shifts [Hz] of the identified modes the simulator's own switched model
    predicts (averaged eigenvalues, hubvib.signal.frequency_route.observed_hz)."""
    phasing = design_phasing(scene.design)
    return observed_hz(scene.params, curves, phasing) - observed_hz(
        scene.params, curves_for(scene, scene.tables["signal"])[0], phasing)


@pytest.fixture(scope="module")
def records(scene_file):
    """``hubvib signal`` on the loop scene: its output folder."""
    out = scene_file.parent / "out"
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["signal", str(scene_file), "--out", str(out), "--json"]) == 0
    return out


def _diagnose(scene, records, *flags) -> str:
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        assert main(["diagnose", "--scene", str(scene), "--record",
                     str(records / "signal_12mm.csv"), "--baseline-record",
                     str(records / "signal_0mm.csv"), *flags]) == 0
    return printed.getvalue()


@pytest.fixture(scope="module")
def diagnosis(scene_file, records):
    """``hubvib diagnose`` of the loop's 12 mm record against its intact one: the JSON
    result."""
    return json.loads(_diagnose(scene_file, records, "--json"))


@pytest.mark.slow
def test_the_shipped_scene_closes_the_loop_and_explains_every_figure(records):
    """By its shipped name: the verdict with its depth, and each figure beside the table
    (the best-fit depth, the fit p-value) said in words."""
    text = _diagnose("raba118_closed_loop", records)
    assert "verdict: crack indicated: depth" in text and "(posterior median)" in text
    words = " ".join(text.split())  # the wrapping moves with the numbers' widths
    assert "(maximum likelihood)" in words and "p-value" in words and \
        "fit as badly or worse" in words, text
    assert max(map(len, text.splitlines())) <= 100, text


@pytest.mark.slow
def test_the_signal_scene_records_are_not_identifiable_with_what_would_help(
        tmp_path_factory, capsys):
    """The short, ambient-free records of the shipped signal scene (10 revolutions, 5 %
    damping) against its own crack study: the answer `not identifiable from these records`
    (exit 0), a reason per mode and what would help."""
    out = tmp_path_factory.mktemp("signal")
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["signal", "raba118_signal", "--out", str(out), "--json"]) == 0
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        assert main(["diagnose", "--scene", "raba118_signal", "--record",
                     str(out / "signal_12mm.csv"), "--baseline-record",
                     str(out / "signal_0mm.csv"), "--json"]) == 0
    result = json.loads(printed.getvalue())
    assert result["verdict"] == "not identifiable from these records"
    assert len(result["skipped_modes"]) == 18
    assert any("forcing" in line for line in result["what_would_help"])
    assert not any("fit:" in why for why in result["skipped_modes"].values())


@pytest.mark.slow
def test_signal_records_through_diagnose(scene_file, diagnosis):
    result = diagnosis
    assert result["c_rp_method"] == "ratio"
    assert result["verdict"] == "crack indicated", result
    assert 15 in result["modes"], "mode 15 (5050 Hz) is identified in both records"
    scene = load_scene(str(scene_file))
    law = _law_shift_hz(scene, curves_for(scene, scene.tables["signal"])[2])
    for mode, shift, sigma in zip(result["modes"], result["shift_hz"], result["sigma_hz"]):
        assert abs(shift - law[mode - 1]) < 4 * math.sqrt(2) * sigma, \
            f"mode {mode}: identified shift {shift:.3g} Hz vs the simulator's averaged " \
            f"eigenvalues {law[mode - 1]:.3g} Hz, within 4 standard deviations of a shift"


@pytest.mark.slow
def test_diagnosis_fits_the_12mm_records_inside_the_sweep(diagnosis):
    result = diagnosis
    # the crack model explains the records (p 0.012 before the engaged ratio was taken over
    # the contact time: the model moved mode 15 0.41 times as far as the records); the
    # maximum-likelihood grid depth may sit at the sweep's end, where the shifts flatten
    assert result["fit_p_value"] > 0.05, result
    assert result["depth_low_m"] <= TRUE_DEPTH <= result["depth_high_m"], result
