"""The crack's change of the elastic ring's modes: eigen model against the Floquet modes a
running record shows (``hubvib.studies.floquet_change``), on the default scene's Raba ring."""
import math

import numpy as np
import pytest


@pytest.fixture(scope="module")
def raba():
    """The default scene, its intact mesh curves and its intact elastic case."""
    from hubvib.cases.sweep import ACCURACY, crack_of
    from hubvib.detection.elastic_model import cached_case, case_arguments
    from hubvib.signal.mesh_curves import fe_mesh_curves
    from hubvib.studies.scene import load_scene

    scene = load_scene("raba118_crack")
    sweep = scene.crack
    fe = fe_mesh_curves((0.0,), sweep.start, sweep.angle, ACCURACY[sweep.accuracy], None,
                        scene.design)[0]
    curves = fe.to_preset(scene.params.c_sp, scene.params.c_rp)
    intact = cached_case(*case_arguments(sweep.reducer, (0.0,), lambda d: crack_of(sweep, d),
                                         scene.elastic)[0])
    return scene, curves, intact


def _direct_monodromy(model, curves, phasing, speed, position):
    """The monodromy matrix by integrating x' = A(t) X over one mesh period with the mesh
    stiffness evaluated at every time the integrator asks (DOP853)."""
    from scipy.integrate import solve_ivp

    from hubvib.signal.elastic_response import _mesh_terms

    m = model.kept
    pitch = 2 * math.pi / model.teeth
    period = pitch / speed
    start = model.patch_angles[position] - model.theta[0] - 0.5 * pitch
    omega = model.omega[position, :m]
    c = 2 * model.damping_ratio * omega

    def rhs(t, x):
        X = x.reshape(2 * m, 2 * m)
        U, W, _ = _mesh_terms(model, curves, phasing, np.array([start + speed * t]),
                              np.array([position]), 0.0)
        rows = U[0][:, :m]
        K = np.diag(omega ** 2) + rows.T @ (W[0][:, None] * rows)
        return np.vstack([X[m:], -K @ X[:m] - c[:, None] * X[m:]]).ravel()

    out = solve_ivp(rhs, (0.0, period), np.eye(2 * m).ravel(), method="DOP853",
                    rtol=1e-8, atol=1e-12)
    return out.y[:, -1].reshape(2 * m, 2 * m), period


@pytest.mark.slow
def test_monodromy_matches_direct_time_integration(raba):
    from hubvib.signal.mesh_phase import design_phasing, design_teeth
    from hubvib.signal.simulation import carrier_speed
    from hubvib.studies.floquet_change import case_time_model, mesh_steps, monodromy

    scene, curves, intact = raba
    model = case_time_model(intact, scene.signal)
    teeth = design_teeth(scene.design)
    speed = carrier_speed(scene.signal, teeth["ring"], teeth["sun"])
    p = intact.away.carrier_tooth
    product = np.linalg.eigvals(monodromy(model, curves, design_phasing(scene.design), speed,
                                          p, 1.0, 4 * mesh_steps(model, p, speed)))
    direct, period = _direct_monodromy(model, curves, design_phasing(scene.design), speed, p)
    exact = np.linalg.eigvals(direct)
    s_product = np.log(product) / period
    s_exact = np.log(exact) / period
    gap = np.abs(s_exact[:, None] - s_product[None, :]).min(axis=1) / (2 * math.pi)
    assert gap.max() < 0.2, (
        f"Floquet exponents of the piecewise-constant product (4 x the default steps) within "
        f"0.2 Hz of the direct time integration's (DOP853, rtol 1e-8); largest "
        f"{gap.max():.3g} Hz")


@pytest.mark.slow
def test_crack_changes_the_watched_modes_floquet_frequencies_as_the_eigen_ones(raba):
    """The default report's watched modes at 3 mm (faces open, planet 1 half a planet pitch
    from the crack): the Floquet change of the mode that decides the 10 s answer (16, the
    n = 3 ring mode, hardly loading the meshes) is the eigen change within the detection's
    FE error of a change (1 %); the others' stay within a factor 0.5 - 1.7 of it and
    within their alarm threshold; the continued branch's change is that of the record
    frequency ``floquet_modes`` attributes (another construction: the dominant harmonic of
    the full mesh cycle's Floquet mode) where it attributes one."""
    from hubvib.detection.elastic_model import FE_CHANGE_ERROR
    from hubvib.studies.floquet_change import floquet_change

    scene, curves, _ = raba
    result = floquet_change(scene, (0.0, 0.003), curves=curves)
    at = {i + 1: a for a, i in enumerate(result.modes)}
    eigen, floquet = result.eigen_change_hz[1], result.floquet_change_hz[1]
    record = result.record_change_hz[1]
    a = at[16]
    assert abs(floquet[a] - eigen[a]) <= FE_CHANGE_ERROR * abs(eigen[a]), (
        f"mode 16: Floquet change {floquet[a]:.3f} Hz within FE_CHANGE_ERROR of the eigen "
        f"change {eigen[a]:.3f} Hz")
    for mode in (16, 21, 22, 24):
        a = at[mode]
        assert result.unique[a], f"mode {mode}: one Floquet branch in both step counts"
        ratio = floquet[a] / eigen[a]
        assert 0.5 <= ratio <= 1.7, (
            f"mode {mode}: Floquet change / eigen change {ratio:.3f}, measured band 0.5-1.7")
        assert abs(floquet[a] - eigen[a]) < result.threshold_hz[a], (
            f"mode {mode}: Floquet - eigen change {floquet[a] - eigen[a]:.3f} Hz below the "
            f"alarm threshold {result.threshold_hz[a]:.3f} Hz")
        if np.isfinite(record[a]):
            assert abs(record[a] - floquet[a]) < 0.2, (
                f"mode {mode}: change of floquet_modes' record frequency {record[a]:.3f} Hz "
                f"within 0.2 Hz of the continued branch's {floquet[a]:.3f} Hz")


def test_depths_must_start_intact(tmp_path, capsys):
    from hubvib.studies.floquet_change import main

    with pytest.raises(SystemExit) as stop:
        main(["--out", str(tmp_path / "out.json"), "--depths-mm", "3,6"])
    assert stop.value.code == 2, "argparse's usage error: exit 2"
    assert "--depths-mm" in capsys.readouterr().err, "the message names the flag"
    assert not (tmp_path / "out.json").exists(), "nothing written on bad input"
