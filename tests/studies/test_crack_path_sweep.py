"""Crack scenes that follow the path, slow: root cracks at -75 and -90 deg
mesh and solve on the Raba ring and a thin-rim variant, and a sweep with ``path =
"predicted"`` takes the crack-path command's path, meshes the polyline truncated at each
depth, and carries its FE values into the lumped model and the detection study."""
import json
import math
from dataclasses import replace

import numpy as np
import pytest

from hubvib.reducer.stages import gear_body, material, ring_gear
from hubvib.cli import main
from hubvib.design.model import RimSpec
from hubvib.design.presets import raba118
from hubvib.fem.crack_level import crack_level
from hubvib.fem.ring_stiffness import ring_stiffness
from hubvib.meshing.crack import Crack
from hubvib.meshing.polyline_crack import path_ring_mesh, tooth_height
from hubvib.meshing.levels import scaled_options
from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh
from hubvib.studies.crack_study import crack_study_from_fe
from hubvib.cases.runner import case_inputs, run_fe_cases
from hubvib.cases.sweep import ACCURACY
from hubvib.cases.predicted_path import predicted_path, truncated
from hubvib.studies.scene import parse_scene

from tests.helpers.crack_scenes import fast_crack_scene

RABA = raba118()
COARSE = MeshOptions(size=3e-3, tooth_size=0.8e-3, load_size=0.3e-3)
THIN = replace(RABA, name="raba118_mB0.5",
               rim=RimSpec(thickness=0.5 * tooth_height(ring_gear(RABA))))


@pytest.mark.slow
@pytest.mark.parametrize("design", [RABA, THIN], ids=["raba", "thin_rim_mB0.5"])
@pytest.mark.parametrize("degrees", [-75.0, -90.0])
def test_root_crack_meshes_and_solves_at_large_angles(design, degrees):
    """"any angle between -90 and +90 deg meshes and solves".  Root cracks
    turned -75 and -90 deg (towards and along the root circle under their own tooth), 2 mm
    deep and as deep as they are allowed (through the rim, or to 0.5 mm from the tooth's
    other fillet), mesh with every flank facet on a cell, the crack tip on the path's tip
    (1e-12 m), and give a finite c_ru within a factor 2 of the intact ring's on the same
    sizes, below it once the crack splits the rim (+60..90 deg are refused:
    tests/meshing/test_crack_kinds.py)."""
    ring = ring_gear(design)
    intact = ring_stiffness(ring, ring_mesh(ring, None, COARSE), carrier_teeth=[0],
                            solver="superlu").c_ru
    probe = Crack(0, 1e-3, math.radians(degrees))
    deepest = min(probe.through_depth(ring), probe.kind.tooth_reach(probe, ring))
    for depth in (2e-3, deepest):
        crack = Crack(0, depth, math.radians(degrees))
        mesh = ring_mesh(ring, crack, COARSE)
        cells = mesh.cells[:, :3]
        for a, b in mesh.boundaries["tooth0_flank_pos"][:, :2]:
            assert np.any((cells == a).any(axis=1) & (cells == b).any(axis=1)), (
                f"flank facet ({a}, {b}) is no cell edge")
        if not crack.is_through(ring):
            tip = mesh.points[mesh.points_of["crack_tip"][0]]
            assert np.allclose(tip, crack.path(ring)[-1], atol=1e-12)
        ratio = ring_stiffness(ring, mesh, carrier_teeth=[0], solver="superlu").c_ru / intact
        low, high = (0.0, 1.0) if crack.is_through(ring) else (0.5, 2.0)
        assert math.isfinite(ratio) and low < ratio < high, (
            f"{design.name} {degrees} deg {depth} m: c_ru ratio {ratio}, allowed {low}..{high} "
            "(a crack through the rim splits it: softer)")


@pytest.mark.slow
def test_predicted_sweep_follows_the_crack_path(tmp_path, monkeypatch, capsys):
    """``path = "predicted"``, Raba tooth 0, depths 0 and 3 mm:

    - the path's first step is the crack-path command's (``hubvib crack-path --tooth 0
      --steps 2 --json``: same points to 1e-12 m, same first kink angle to 1e-9 deg);
    - the FE case at 3 mm meshes the path truncated at 3 mm (its cache inputs hold that
      polyline: the mouth and the first six analysed tips), and its c_ru, c_r equal a
      direct ``crack_level`` on ``path_ring_mesh`` of that polyline (1e-9 relative);
    - the lumped model takes those rows (c_rp factor = the row's extra compliance in
      series with the lumped c_rp, 1e-12) and the predicted 3 mm crack lowers the cracked tooth's mean c_rp more than
      the radial 3 mm crack (docs/crack_path.md: 0.923 vs 0.940 on the default mesh);
    - the detection study runs on it (a POD per mode at the deepest crack)."""
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    scene = parse_scene(fast_crack_scene((0.0, 0.003), 1, "predicted"), "predicted")
    sweep = scene.crack
    grown = predicted_path(RABA, 0, sweep.depths)
    assert main(["crack-path", "--tooth", "0", "--steps", "2", "--json", "--out",
                 str(tmp_path / "cp")]) == 0
    command = json.loads(capsys.readouterr().out)
    np.testing.assert_allclose(grown["path_m"][:3], command["path_m"][:3], atol=1e-12,
                               err_msg="predicted path vs hubvib crack-path, first step")
    assert grown["kink_angle_deg"][0] == pytest.approx(command["kink_angle_deg"][0], abs=1e-9)

    at_3mm = truncated(grown["path_m"], 3e-3, 0)
    np.testing.assert_array_equal(at_3mm.array, np.asarray(grown["path_m"])[:7])
    assert case_inputs(sweep, 3e-3)["crack"] == {"tooth": 0, "points": at_3mm.points}

    fe, computed = run_fe_cases(sweep, progress=False)
    assert computed == 2
    ring, planet, steel = ring_gear(RABA), gear_body(RABA, "planet"), material(RABA)
    options = scaled_options(ACCURACY["fast"])
    direct = crack_level(ring, planet, at_3mm, path_ring_mesh(ring, at_3mm, options), options,
                         steel, RABA.n_planets)
    # c_ru, c_r: the work-conjugate rim parts, the root-land readings beside
    assert fe[1]["c_ru_N_m"] == pytest.approx(direct.ring.work.c_ru_rim, rel=1e-9)
    assert fe[1]["c_r_N_m"] == pytest.approx(direct.ring.work.c_r_rim, rel=1e-9)
    assert fe[1]["c_ru_root_land_N_m"] == pytest.approx(direct.ring.c_ru, rel=1e-9)
    assert fe[1]["c_r_root_land_N_m"] == pytest.approx(direct.ring.c_r, rel=1e-9)
    assert fe[1]["c_rp_engaged_ratio"] == pytest.approx(direct.engaged.mean_ratio, rel=1e-9)

    radial_scene = parse_scene(fast_crack_scene((0.0, 0.003), 1, "radial"), "radial")
    radial, _ = run_fe_cases(radial_scene.crack, progress=False)
    assert fe[1]["c_rp_engaged_ratio"] < radial[1]["c_rp_engaged_ratio"] < 1, (
        "mean c_rp ratio predicted < radial (docs/crack_path.md, 0.923 vs 0.940)")

    result = crack_study_from_fe(scene, fe, computed, detection=True)
    # the intact mean over the contact window is the ratio's denominator
    ratio, c_fe = fe[1]["c_rp_engaged_ratio"], fe[1]["c_rp_engaged_intact_window_N_m"]
    series = 1 / (1 + scene.params.c_rp * (1 / ratio - 1) / c_fe)  # the crack's compliance
    np.testing.assert_allclose(result.c_rp_factor, [1.0, series], rtol=1e-12,
                               err_msg="lumped c_rp factor: the predicted row's extra "
                               "compliance in series with the lumped c_rp")
    other = crack_study_from_fe(radial_scene, radial, 0, detection=False)
    assert not np.allclose(result.omega[1], other.omega[1], rtol=1e-12, atol=0), (
        "the lumped spectra follow the crack's path")
    assert result.detection is not None


@pytest.mark.slow
def test_fe_render_takes_a_path_crack():
    """The crack study renders its deepest crack (``render.fe.ring_fields`` through
    ``ring_mesh``): a polyline crack meshes there too, its tip node on the path's tip
    (1e-12 m), as ``path_ring_mesh`` meshes it (``hubvib run raba118_crack_path`` failed
    with "'PathCrack' object has no attribute 'path'")."""
    from hubvib.meshing.polyline_crack import initial_crack
    from hubvib.render.fe import ring_fields

    ring = ring_gear(RABA)
    crack = initial_crack(ring, 0, 3e-3)
    crack = crack.extended(crack.tip + np.array([0.0, -1e-3]))
    fields = ring_fields(RABA, crack, scaled_options(2.0))
    np.testing.assert_allclose(fields.crack_tip, crack.tip, atol=1e-12)
    np.testing.assert_array_equal(crack.path(ring), crack.array)
