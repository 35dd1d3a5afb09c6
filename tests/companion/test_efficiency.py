"""Seed 001: efficiency and optimal geometry of ball/roller planetary gears (hubvib efficiency).

Sources: Kapitonov 2024, Transport Engineering 3:20-30 (``../shared/seeds/001_*.txt``: text,
Figs. 5-9, Table) and the reading of its equations in ``../shared/reference/seeds_000_002.md``
("the reference").
"""
import json
import math
import subprocess
import sys

import pytest

from hubvib.cli import main
from hubvib.companion.efficiency.core import Friction, losses, optimum
from hubvib.companion.efficiency.design import gear_design
from hubvib.companion.efficiency.table import PUBLISHED, paper_table
from hubvib.companion.efficiency.track_geometry import fixed_track_lift_angle, track_geometry

RATIOS = (5, 10, 15, 20, 25, 30)
# The paper's Table, typed from the seed text (angles deg, lengths mm).
TABLE = {
    "alpha1_deg": (9, 5, 3, 3, 2, 2),
    "alpha2_deg": (32.3558, 38.2168, 14, 44.8779, 39.9663, 45.3616),
    "z2": (4, 9, 14, 19, 24, 29),
    "R_ball_mm": (14.92564, 40.69789, 60.10152, 102.8505, 114.5504, 159.0755),
    "A_ball_mm": (2.334885, 3.547055, 3.14547, 5.382782, 3.997752, 5.551653),
    "R_roller_mm": (9.950427, 27.13193, 40.06768, 68.56703, 76.36695, 106.0503),
    "A_roller_mm": (1.55659, 2.364703, 2.09698, 3.588521, 2.665168, 3.701102),
}


def _raw_psi(ratio, alpha1, f=(0.004, 0.05, 0.1), rho=0.037, omega3=2.1, f3n=123.0):
    """psi from the paper's eqs. (1)-(9) step by step, with the force balance of its ref. [1]
    (F1h w1 = F3n w3, F3n = F1h + F2h) and w1 = i w3; rho, omega3, F3n are arbitrary."""
    z2 = ratio - 1
    alpha2 = math.atan(z2 * math.tan(alpha1))
    omega1 = ratio * omega3
    f1h = f3n * omega3 / omega1
    f2h = f3n - f1h
    f1t, f2t, f3t = f[0] * f1h / math.sin(alpha1), f[1] * f2h / math.sin(alpha2), f[2] * f3n
    v1 = rho * (omega1 - omega3) / math.cos(alpha1)
    v2 = rho * omega3 / math.cos(alpha2)
    v2s = rho * omega3 * math.tan(alpha2)
    return (f1t * v1 + f2t * v2 + f3t * v2s) / (f3n * rho * omega3)


@pytest.mark.parametrize("ratio, alpha1_deg", [(5, 9), (10, 5), (30, 2), (7, 17.3)])
def test_closed_form_equals_the_step_by_step_equations(ratio, alpha1_deg):
    a1 = math.radians(alpha1_deg)
    assert losses(ratio, a1).psi == pytest.approx(_raw_psi(ratio, a1), rel=1e-12), \
        "closed-form psi vs eqs. (1)-(9) evaluated step by step (reference, seed 001), rel 1e-12"


@pytest.mark.parametrize("k, ratio", enumerate(RATIOS))
def test_whole_degree_optimum_is_the_papers(k, ratio):
    best = optimum(ratio).whole
    assert round(math.degrees(best.alpha1_rad)) == TABLE["alpha1_deg"][k], \
        f"optimal alpha1 at i = {ratio} vs paper Table / Figs. 5-8 (exact whole degree)"


def test_headline_85_3_percent_at_i_5():
    best = optimum(5)
    eta = best.whole.eta * 100
    assert round(eta, 1) == 85.3, "eta at i = 5 vs paper text and Fig. 9: 85.3 % (1 decimal)"
    assert eta == pytest.approx(85.2847, abs=1e-4), \
        "eta at 9 deg, the reference's psi formula evaluated independently: 85.2847 %, abs 1e-4"
    assert round(best.continuous.eta * 100, 2) == 85.29, \
        "reference's 85.29 % (2 decimals) is the continuous optimum (8.70 deg); 9 deg gives 85.28"


@pytest.mark.parametrize("k, ratio", enumerate(RATIOS))
def test_R_and_A_reproduce_the_papers_table(k, ratio):
    design = gear_design(ratio)
    got = {f"{q}_{t.satellite}_mm": v * 1e3 for t in design.tracks
           for q, v in (("R", t.mean_radius_m), ("A", t.amplitude_m))}
    for key, value in got.items():
        assert value == pytest.approx(TABLE[key][k], rel=1e-5), \
            f"{key} at i = {ratio} vs paper Table (reference: within 1e-5 relative)"


@pytest.mark.parametrize("k, ratio", [(k, i) for k, i in enumerate(RATIOS) if i != 15])
def test_alpha2_eq_11_reproduces_the_table(k, ratio):
    alpha2 = math.degrees(gear_design(ratio).at.alpha2_rad)
    assert alpha2 == pytest.approx(TABLE["alpha2_deg"][k], abs=5e-5), \
        f"alpha2 at i = {ratio} vs paper Table, abs 5e-5 deg (half the last printed digit)"


def test_alpha2_at_i_15_is_a_print_slip():
    alpha2 = math.degrees(fixed_track_lift_angle(math.radians(3), 14))
    assert alpha2 == pytest.approx(math.degrees(math.atan(14 * math.tan(math.radians(3)))),
                                   rel=1e-15), "eq. (11) alpha2 = arctan(z2 tan alpha1), exact"
    assert alpha2 == pytest.approx(36.2678, abs=5e-5), "eq. (11) at i = 15, abs 5e-5 deg"
    assert TABLE["alpha2_deg"][2] == TABLE["z2"][2] == 14, \
        "paper Table prints alpha2 = 14 at i = 15, the z2 beside it (slip)"
    table = paper_table()
    bad = [(c.quantity, c.ratio) for c in table.disagreements()]
    assert bad == [("alpha2_deg", 15)], "only the known slip disagrees with the printed Table"


def test_table_compares_only_what_the_paper_printed():
    table = paper_table(satellites={"ball": 0.020})
    r_cells = [c for c in table.cells if c.quantity == "R_ball_mm"]
    assert all(c.published is None for c in r_cells), "20 mm balls: no printed R to compare"
    assert r_cells[0].computed == pytest.approx(14.92564 * 20 / 15, rel=1e-5), \
        "eq. (12): R scales with d_c; paper Table R_ball at i = 5 times 20/15, rel 1e-5"
    other = paper_table(friction=Friction(f3=0.2))
    assert all(c.published is None for c in other.cells), "other friction: nothing compared"


def test_library_copy_of_the_published_table_matches_the_seed_text():
    for key, values in TABLE.items():
        assert PUBLISHED[key] == values, f"efficiency_table.PUBLISHED[{key}] vs seed 001 Table"


def test_ball_and_roller_geometry_scale_with_the_diameter():
    for ratio in RATIOS:
        ball, roller = gear_design(ratio).tracks
        assert ball.mean_radius_m / roller.mean_radius_m == pytest.approx(1.5, rel=1e-14), \
            "eq. (12): R proportional to d_c (15 mm / 10 mm), rel 1e-14"
        assert ball.amplitude_m == pytest.approx(ball.mean_radius_m * math.sin(
            gear_design(ratio).at.alpha1_rad), rel=1e-15), "eq. (13) A = R sin alpha1"


def test_continuous_optimum_is_a_stationary_point():
    for ratio in RATIOS:
        best = optimum(ratio)
        a, h = best.continuous.alpha1_rad, 1e-5
        slope = (losses(ratio, a + h).psi - losses(ratio, a - h).psi) / (2 * h)
        assert abs(slope) < 1e-5, f"d psi / d alpha1 = 0 at the continuous optimum, i = {ratio}"
        assert best.continuous.psi <= best.whole.psi + 1e-15, "continuous psi <= whole-degree psi"
        assert abs(best.continuous.alpha1_rad - best.whole.alpha1_rad) < math.radians(1), \
            "continuous optimum within 1 deg of the whole-degree one"


def test_loss_ordering_at_i_5():
    at = optimum(5).whole
    assert at.psi_driving < at.psi_carrier < at.psi_fixed, \
        "paper text on Fig. 5 / reference: at i = 5, alpha1 = 9 deg, driving < carrier < fixed"


def test_losses_at_i_30_differ_little():
    at = optimum(30).whole
    terms = (at.psi_driving, at.psi_fixed, at.psi_carrier)
    assert max(terms) / min(terms) < 1.15, \
        "paper text on Fig. 6: at i = 30, 2 deg the three link losses differ little (within 15 %)"


def test_best_efficiency_falls_with_the_ratio():
    etas = [optimum(i).whole.eta for i in RATIOS]
    assert all(a > b for a, b in zip(etas, etas[1:])), "paper Fig. 9: eta falls as i grows"


def test_carrier_to_driving_loss_ratio_trend():
    cont = [optimum(i).continuous for i in RATIOS]
    ratios = [c.psi_carrier / c.psi_driving for c in cont]
    assert all(a > b for a, b in zip(ratios, ratios[1:])), \
        "paper text: carrier/driving loss ratio falls with i (holds at the continuous optimum)"
    whole = [optimum(i).whole for i in RATIOS]
    steps = [c.psi_carrier / c.psi_driving for c in whole]
    assert steps[3] > steps[2], \
        "on whole degrees it is not monotone: i = 20 (3 deg) above i = 15 (3 deg), README says so"


def test_power_balance():
    design = gear_design(5, input_power_w=1500.0)
    p = design.power
    assert p.output_w + p.total_loss_w == pytest.approx(1500.0, rel=1e-14), \
        "W_in = W_out + sum of link losses (energy balance), rel 1e-14"
    assert p.output_w == pytest.approx(design.at.eta * 1500.0, rel=1e-14), "W_out = eta W_in"


def test_friction_free_gear_is_lossless():
    assert losses(5, math.radians(9), Friction(0, 0, 0)).eta == 1.0, "f = 0: eta = 1 exactly"


def test_geometry_docstring_value():
    g = track_geometry(math.radians(9), 4, 0.015)
    assert g.mean_radius_m == pytest.approx(14.92564e-3, rel=1e-5), "paper Table, R_ball i = 5"


# --- CLI -------------------------------------------------------------------------------------

def test_cli_single_ratio(capsys):
    assert main(["efficiency", "--ratio", "5"]) == 0
    out = capsys.readouterr().out
    assert "9 deg on whole degrees (eta = 85.285 %)" in out, "headline, paper: 85.3 % at 9 deg"
    assert "14.92564" in out and "2.334884" in out, "R, A of the ball gear, paper Table"
    assert "loss ordering: driving < carrier < fixed" in out, "paper text on Fig. 5"


def test_cli_json(capsys):
    assert main(["efficiency", "--ratio", "5", "10", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    first = data["designs"][0]
    assert first["optimum"]["alpha1_whole_deg"] == 9, "paper Table: 9 deg at i = 5"
    assert round(first["eta"] * 100, 1) == 85.3, "paper text / Fig. 9: 85.3 % at i = 5"
    assert len(first["curve"]) == 30, "eta and loss terms for alpha1 = 1..30 deg (Figs. 5-8)"
    assert first["power"]["input_w"] == 1500.0, "reference power stated: W1 = 1500 W"
    assert data["designs"][1]["optimum"]["alpha1_whole_deg"] == 5, "paper Table: 5 deg at i = 10"


def test_cli_alpha1_given(capsys):
    assert main(["efficiency", "--ratio", "5", "--alpha1-deg", "12", "--satellite", "roller",
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)["designs"][0]
    assert data["alpha1_deg"] == 12 and not data["at_optimum"]
    assert [t["satellite"] for t in data["tracks"]] == ["roller"]
    assert data["eta"] == pytest.approx(losses(5, math.radians(12)).eta, rel=1e-15)


def test_cli_table(capsys):
    assert main(["efficiency", "--table"]) == 0
    out = capsys.readouterr().out
    assert "36.2678*" in out and "the paper prints 14" in out, "alpha2 slip at i = 15 flagged"
    assert "42 of 43 cells within tolerance" in out, "paper Table: all cells but the slip"
    assert main(["efficiency", "--table", "--json"]) == 0
    cells = json.loads(capsys.readouterr().out)["table"]
    assert sum(c["agrees"] is False for c in cells) == 1


def test_cli_writes_plots(capsys, tmp_path):
    assert main(["efficiency", "--ratio", "5", "--out", str(tmp_path)]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["efficiency_curves.csv", "efficiency_losses_i5.png"]
    assert (tmp_path / "efficiency_losses_i5.png").read_bytes()[:4] == b"\x89PNG"
    assert (tmp_path / "efficiency_curves.csv").read_text().count("\n") == 31  # header + 30


def test_efficiency_figure_has_one_curve_per_ratio():
    import matplotlib.pyplot as plt

    from hubvib.companion.efficiency.plot import efficiency_figure

    fig = efficiency_figure((5, 30), Friction())
    psi_axis, eta_axis = fig.axes
    assert len(psi_axis.lines) == len(eta_axis.lines) == 2
    assert max(eta_axis.lines[0].get_ydata()) == pytest.approx(optimum(5).whole.eta * 100)
    plt.close(fig)


@pytest.mark.parametrize("argv, message", [
    (["--ratio", "1"], "ratio i (--ratio) must be a whole number in 2..1000"),
    (["--ratio", "2.5"], "ratio i (--ratio) must be a whole number in 2..1000"),
    (["--ratio", "nan"], "ratio i (--ratio) must be a whole number in 2..1000"),
    (["--ratio", "5", "--f1", "-0.01"], "friction coefficient f1 (--f1) must be in [0, 1)"),
    (["--ratio", "5", "--f2", "1"], "friction coefficient f2 (--f2) must be in [0, 1)"),
    (["--ratio", "5", "--f3", "1.5"], "friction coefficient f3 (--f3) must be in [0, 1)"),
    (["--ratio", "5", "--alpha1-deg", "0"], "alpha1 (--alpha1-deg) must be in (0, 90) deg"),
    (["--ratio", "5", "--alpha1-deg", "90"], "alpha1 (--alpha1-deg) must be in (0, 90) deg"),
    (["--ratio", "5", "--ball-diameter-mm", "0"], "(--ball-diameter-mm) must be > 0 mm"),
    (["--ratio", "5", "--roller-diameter-mm", "-2"], "(--roller-diameter-mm) must be > 0 mm"),
    (["--ratio", "5", "--input-power-w", "0"], "input power (--input-power-w) must be > 0 W"),
    ([], "--ratio is required"),
])
def test_bad_input(capsys, tmp_path, argv, message):
    out = tmp_path / "out"
    assert main(["efficiency", *argv, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err
    assert not out.exists(), "nothing written on bad input"


def test_import_pulls_in_nothing_heavy():
    code = ("import sys, hubvib.companion.efficiency.core, hubvib.companion.efficiency.design, "
            "hubvib.companion.efficiency.table, hubvib.companion.efficiency.report, "
            "hubvib.companion.efficiency.plot, hubvib.commands.efficiency; "
            "print([m for m in ('gmsh', 'skfem', 'pyvista', 'matplotlib') if m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]", "import must not load gmsh, skfem, pyvista, matplotlib"
