"""Why the two ring models differ, printed beside both spectra: the rigid ring's table
values against the FE ring's (``hubvib.elastic.differences``), checked against the ring's
exact geometry and the lumped model."""
from __future__ import annotations

import math

import pytest

from tests.helpers.cli_output import run_cli

pytestmark = pytest.mark.slow  # each builds the FE ring (a few seconds)


@pytest.fixture(scope="module")
def raba():
    from hubvib.design.presets import preset_design
    from hubvib.elastic.differences import model_differences
    from hubvib.elastic.options import ElasticScene

    design = preset_design("raba118")
    return design, model_differences(design, ElasticScene().options)


def test_fe_ring_mass_and_inertia_against_the_exact_geometry(raba):
    """The FE mass matrix's rigid-body mass against area x face width x density of the
    ring's exact cross-section (Green's theorem on the tooth profile, no mesh), within
    1e-4; its rotational inertia between the exact bounds of a rim (outer to root circle,
    exact) plus the teeth's area placed at the tip and at the root radius."""
    from hubvib.reducer.stages import ring_gear

    design, d = raba
    ring = ring_gear(design)
    exact_mass = ring.mass()
    assert d.ring_mass_fe == pytest.approx(exact_mass, rel=1e-4), (
        f"FE ring mass {d.ring_mass_fe:.6f} kg vs exact geometry {exact_mass:.6f} kg "
        "(tolerance 1e-4)")
    rho_w = ring.density * ring.gear.face_width
    r_o, r_f, r_a = ring.outer_radius, ring.profile.root_radius, ring.profile.tip_radius
    teeth_area = math.pi * r_f ** 2 - ring.teeth * ring.tooth_space_area()
    assert teeth_area > 0
    rim = 0.5 * math.pi * (r_o ** 4 - r_f ** 4)
    low, high = rho_w * (rim + teeth_area * r_a ** 2), rho_w * (rim + teeth_area * r_f ** 2)
    assert low <= d.inertia_fe <= high, (
        f"FE ring inertia {d.inertia_fe:.5f} kg m^2 outside the exact bounds "
        f"[{low:.5f}, {high:.5f}] (rim exact, teeth at tip / root radius)")


def test_table_against_fe_ring_explains_mode_1(raba):
    """Raba's table holds mu_r = 5.36 kg, the FE ring's inertia gives 10.78 kg: the rigid
    model's mode 1 (53.5 Hz, 'hubvib spectrum') falls to the elastic ring's 45.1 Hz once the
    rigid ring gets the FE ring's mass and mounting (the validity band's model: within its
    1 % tolerance); the foundation is sized to the table's c_r and c_ru (equal within
    1e-6)."""
    from hubvib.lumped import natural_modes
    from hubvib.reducer.stages import lumped_parameters

    design, d = raba
    table = lumped_parameters(design)
    assert (d.mu_r_table, d.ring_mass_table) == (table.mu_r, table.m_r) == (5.36, 6.8)
    assert d.mu_r_fe > 1.9 * d.mu_r_table, (d.mu_r_fe, d.mu_r_table)
    assert d.c_r_fe == pytest.approx(d.c_r_table, rel=1e-6)
    assert d.c_ru_fe == pytest.approx(d.c_ru_table, rel=1e-6)
    assert d.mode1_table_hz == pytest.approx(natural_modes(table).frequency_hz[0], rel=1e-12)
    assert d.mode1_fe_rigid_hz == pytest.approx(d.mode1_elastic_hz, rel=0.01), (
        "rigid ring with the FE ring's mass and mounting vs elastic mode 1 (validity rtol 1 %)")
    assert d.mode1_table_hz > 1.1 * d.mode1_elastic_hz
    assert 0 < d.band_top_hz < d.compared_to_hz and d.band_reason


def test_both_spectra_print_the_differences(raba):
    """``hubvib modes --ring rigid`` and ``--ring elastic``: the same comparison in text
    and under ``model_differences`` in the JSON (SI)."""
    design, d = raba
    expected = d.to_dict()
    for ring in ("rigid", "elastic"):
        code, data, err = run_cli(["modes", "--preset", "raba118", "--ring", ring, "--json"])
        assert code == 0, err
        got = data["model_differences"]
        for key in ("ring_mass_kg", "ring_mu_r_kg", "c_r_N_m", "c_ru_N_m"):
            for side in ("rigid_ring_table", "fe_ring"):
                assert got[key][side] == pytest.approx(expected[key][side], rel=1e-9), \
                    (ring, key, side)
        assert got["validity_band"]["rigid_ring_holds_below_hz"] == pytest.approx(
            d.band_top_hz, rel=1e-9)
        code, text, err = run_cli(["modes", "--preset", "raba118", "--ring", ring])
        assert code == 0, err
        for words in ("why the two ring models differ (raba118)", "5.36 kg", "10.78 kg",
                      f"mode 1: {d.mode1_table_hz:.1f} Hz rigid with the table's ring",
                      f"holds below {d.band_top_hz:.0f} Hz"):
            assert words in text, (ring, words)
