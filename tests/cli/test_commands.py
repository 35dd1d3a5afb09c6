import json
import subprocess
import sys

import pytest

from hubvib.cli import main


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_spectrum_json(capsys):
    data = _json(capsys, ["spectrum", "--json"])
    assert len(data["modes"]) == 18 and data["n_rigid"] == 0
    assert data["modes"][0]["omega_rad_s"] == pytest.approx(336.454, abs=1e-3)


def test_spectrum_set_and_params_file(capsys, tmp_path):
    params = tmp_path / "p.toml"
    params.write_text('preset = "raba118"\nc_ru = 1e5\nn_planets = 4\n')
    data = _json(capsys, ["spectrum", "--params", str(params), "--set", "alpha_w_deg=22", "--json"])
    assert len(data["modes"]) == 21
    assert {m["kind"] for m in data["modes"]} == {"rotational", "translational", "planet"}


def test_spectrum_reports_rigid_body_modes(capsys):
    assert main(["spectrum", "--set", "c_su=0", "--set", "c_cu=0", "--set", "c_ru=0"]) == 0
    assert "2 rigid-body mode(s)" in capsys.readouterr().out


def test_shift_json(capsys):
    data = _json(capsys, ["shift", "--to", "c_ru", "1e5", "--json"])
    assert data["modes"][0]["percent"] == pytest.approx(-43.64, abs=0.01)


@pytest.mark.parametrize("argv, message", [
    (["spectrum", "--set", "c_ru=-5"], "c_ru = -5.0, but it must be >= 0.0"),
    (["spectrum", "--set", "m_p=nan"], "m_p = nan, but it must be finite"),
    (["spectrum", "--set", "n_planets=0"], "n_planets = 0"),
    (["spectrum", "--set", "theta_deg=10,10"], "same place"),
    (["spectrum", "--set", "c_xx=1"], "unknown parameter 'c_xx'"),
    (["spectrum", "--set", "c_ru"], "expected KEY=VALUE"),
    (["shift", "--to", "c_ru", "abc"], "c_ru = 'abc', but it must be a number"),
])
def test_bad_input_exit_code_and_message(capsys, argv, message):
    assert main(argv) == 2
    assert message in capsys.readouterr().err


def test_unknown_preset_rejected(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["spectrum", "--preset", "nope"])
    assert exc.value.code == 2
    assert "invalid choice: 'nope'" in capsys.readouterr().err


@pytest.mark.slow
def test_validate_writes_report(capsys, tmp_path):
    assert main(["validate", "raba118", "--out", str(tmp_path), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["passed"] and summary["printed_max_relative_deviation"] <= 0.002
    assert len(summary["printed_negative_eigenvalues_rad2_s2"]) == 4
    for name in ("spectrum.csv", "theory.csv", "summary.json", "fig4_c_ru_sweep.png"):
        assert (tmp_path / name).stat().st_size > 0


@pytest.mark.slow  # the same command and answer as the default run's
# tests/cli/test_progress_and_file_lists.py::test_stability_reports_each_case_on_stderr
def test_stability_command(capsys):
    data = _json(capsys, ["stability", "--repeats", "1", "--json"])
    assert data["passed"] and data["target"] == 1e-6


def test_import_lumped_stays_light():
    code = ("import sys, hubvib.lumped, hubvib.cli; "
            "heavy = {'gmsh', 'skfem', 'pyvista', 'matplotlib', 'meshio', 'mpmath'} & set(sys.modules); "
            "print(sorted(heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_mesh_planet_json(capsys, tmp_path):
    pytest.importorskip("gmsh")
    data = _json(capsys, ["mesh", "planet", "--out", str(tmp_path), "--json"])
    # exact area of the planet body (closed forms, tests/meshing/test_plane_meshes.py),
    # P2 within 1e-5
    assert abs(data["relative_error"]) < 1e-5 and data["min_quality_sicn"] > 0.5
    assert {"supports", "tooth0_load"} <= set(data["groups"])
    assert all((tmp_path / f"planet.{ext}").stat().st_size > 0 for ext in ("vtu", "png"))


def test_mesh_rejects_a_cracked_planet(capsys, tmp_path):
    pytest.importorskip("gmsh")
    assert main(["mesh", "planet", "--crack-depth", "1e-3", "--out", str(tmp_path)]) == 2
    assert "ring only" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


@pytest.mark.slow
def test_mesh_ring_3d_semi_elliptic(capsys, tmp_path):
    pytest.importorskip("gmsh")
    data = _json(capsys, ["mesh", "ring", "--dim", "3", "--crack-depth", "6e-3",
                          "--crack-front", "semi_elliptic", "--crack-half-length", "8e-3",
                          "--size", "12e-3", "--out", str(tmp_path), "--json"])
    # exact volume = exact area x face width; straightened fillet edges cost ~1e-5 here
    assert abs(data["relative_error"]) < 3e-5
    assert data["cell_type"] == "tetra10" and data["min_quality_sicn"] > 0
    assert {"crack_a", "crack_b", "face_0", "face_1"} <= set(data["groups"])


def test_convergence_writes_csv_plot_and_resumes(capsys, tmp_path):
    """The annulus study: exact reference, error falls at every level (curved P2), CSV and
    plot written; a rerun computes nothing (every level is read back)."""
    pytest.importorskip("skfem")
    import csv

    assert main(["convergence", "annulus", "--out", str(tmp_path)]) == 0
    assert "annulus: scale" in capsys.readouterr().err  # one progress line per level
    rows = list(csv.DictReader(open(tmp_path / "convergence_annulus.csv")))
    errors = [float(r["relative_error"]) for r in rows]
    assert len(rows) == 5 and all(b < a for a, b in zip(errors, errors[1:]))
    assert errors[-1] < 1e-6
    assert (tmp_path / "convergence_annulus.png").stat().st_size > 0
    capsys.readouterr()
    assert main(["convergence", "annulus", "--out", str(tmp_path)]) == 0
    assert "annulus: scale" not in capsys.readouterr().err


@pytest.mark.slow
def test_stiffness_prints_every_stiffness_intact_and_cracked(capsys):
    """Every stiffness: c_ru, c_r, c_rp, c_sp, c_p (and c_c) intact and cracked, each with
    an error estimate and a run time; the crack lowers c_ru and c_r, and c_rp while engaged."""
    from hubvib.fem.bearing import RollerBearing

    out = _json(capsys, ["stiffness", "--crack-depth", "5e-3", "--json"])["cases"]
    intact, cracked = out["intact"], out["crack 0.005 m"]
    for case in (intact, cracked):
        for key in ("c_ru", "c_r", "c_sp", "c_rp"):
            assert 0 < case[key]["error_N_m"] < 0.02 * case[key]["value_N_m"]
        for key in ("c_p", "c_c"):  # tangent = dF/d delta: central difference (step 1e-4 F)
            r = case[key]
            bearing = RollerBearing(int(r["rollers"]), r["roller_length_m"])
            step = 1e-4 * r["load_N"]
            slope = 2 * step / (bearing.deflection(r["load_N"] + step)
                                - bearing.deflection(r["load_N"] - step))
            assert r["tangent_N_m"] == pytest.approx(slope, rel=1e-6), \
                f"{key} tangent vs central difference of the Palmgren deflection"
    assert cracked["c_ru"]["value_N_m"] < intact["c_ru"]["value_N_m"]
    assert cracked["c_r"]["value_N_m"] < intact["c_r"]["value_N_m"]
    assert cracked["c_rp"]["engaged_N_m"] < cracked["c_rp"]["engaged_intact_N_m"]
