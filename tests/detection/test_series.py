"""Mounting in series with the FE ring body: limits, identification, the reference figures."""
import math

import numpy as np
import pytest
from tests.helpers.synthetic_rows import C_R, C_RU, synthetic_fe_rows, synthetic_model

from hubvib.detection.series import identify_mount, ring_support, series
from hubvib.lumped import frequency_sensitivity, natural_modes


def test_series_of_two_springs_is_the_textbook_formula():
    # two springs in series: 1/c = 1/c1 + 1/c2 (e.g. 2 and 2 give 1; 1 and 3 give 3/4)
    assert series(2.0, 2.0) == 1.0 and series(1.0, 3.0) == pytest.approx(0.75, rel=1e-15)
    assert series(math.inf, 5.0) == 5.0 and series(5.0, math.inf) == 5.0


def test_series_tends_to_direct_when_the_mounting_stiffens():
    direct = synthetic_model("direct")
    stiff = synthetic_model("series", c_ru_mount=1e30, c_r_mount=1e30)
    np.testing.assert_allclose(stiff.c_ru, direct.c_ru, rtol=1e-15)
    np.testing.assert_allclose(stiff.c_r, direct.c_r, rtol=1e-15)
    for k in (0, len(direct.depths) - 1):
        np.testing.assert_allclose(natural_modes(stiff.parameters(k)).omega,
                                   natural_modes(direct.parameters(k)).omega, rtol=1e-12,
                                   err_msg="series with a rigid mounting vs apply = direct")


def test_series_tends_to_the_mounting_when_the_body_stiffens():
    model = synthetic_model("series", c_ru_mount=1e6, c_r_mount=1e8, body_scale=1e24)
    np.testing.assert_allclose(model.c_ru, 1e6, rtol=1e-15)
    np.testing.assert_allclose(model.c_r, 1e8, rtol=1e-15)


def test_identified_mounting_gives_the_preset_totals():
    model = synthetic_model("series")
    assert model.c_ru[0] == pytest.approx(1e6, rel=1e-14) and \
        model.c_r[0] == pytest.approx(1e8, rel=1e-14)
    # 1/m = 1/c - 1/b, computed by hand for the paper's c_ru and the FE body
    assert model.c_ru_mount == pytest.approx(1 / (1 / 1e6 - 1 / C_RU), rel=1e-14)
    assert model.c_r_mount == pytest.approx(1 / (1 / 1e8 - 1 / C_R), rel=1e-14)


def test_no_mounting_can_be_stiffer_than_its_series_total():
    with pytest.raises(ValueError, match=r"c_ru = 2e\+10 N/m cannot be the series total"):
        identify_mount(2e10, C_RU, "c_ru")


def test_ratio_scales_the_preset_and_direct_uses_the_body():
    body = np.array([C_RU, 0.9 * C_RU])
    np.testing.assert_allclose(ring_support("ratio", body, C_RU, 1e6), [1e6, 9e5], rtol=1e-15)
    np.testing.assert_array_equal(ring_support("direct", body, C_RU, 1e6), body)


def test_a_soft_mounting_hides_the_crack_issue_13_numbers():
    # Measured with the lumped model: mounting identified for c_ru = 1e6 N/m in
    # series with the body; the through-rim crack (body x0.942) moves the total c_ru by 4e-6
    # and mode 1 by -0.0001 %
    model = synthetic_model("series", c_rp_drop=0.0, c_r_drop=0.0)
    change = 1 - model.c_ru[-1] / model.c_ru[0]
    assert change == pytest.approx(4e-6, rel=0.1), "total c_ru moves by 4e-6"
    intact = natural_modes(model.parameters(0))
    cracked = natural_modes(model.parameters(len(model.depths) - 1))
    shift = cracked.omega[0] / intact.omega[0] - 1
    assert 100 * shift == pytest.approx(-0.0001, abs=0.5e-4), "mode 1 -0.0001 %"
    # first-order perturbation: relative shift = sensitivity x relative stiffness change
    sensitivity = frequency_sensitivity(model.parameters(0), "c_ru").relative[0]
    assert shift == pytest.approx(-sensitivity * change, rel=1e-3), \
        "eigen-solve difference vs analytic sensitivity (first order)"


def test_a_rigid_mounting_shows_the_crack():
    # With the body alone the most sensitive mode moves by percents
    model = synthetic_model("direct")
    intact = natural_modes(model.parameters(0)).omega
    cracked = natural_modes(model.parameters(len(model.depths) - 1)).omega
    assert np.max(1 - cracked / intact) > 0.02


def test_cracked_tooth_keeps_its_fe_ratio_under_every_apply():
    for apply in ("series", "ratio", "direct"):
        model = synthetic_model(apply)
        params = model.parameters(len(model.depths) - 1)
        assert params.c_rp_factors[0] == model.c_rp_ratio[-1] == pytest.approx(0.9)
        assert params.c_rp_factors[1:] == (1.0, 1.0)
        assert model.parameters(3, engaged=False).c_rp_factors == (1.0, 1.0, 1.0)


def test_interpolated_depths_reproduce_the_sweep_at_its_own_depths():
    model = synthetic_model("series")
    again = model.at_depths(model.depths)
    np.testing.assert_allclose(again.c_ru, model.c_ru, rtol=1e-15)
    with pytest.raises(ValueError, match="must start at 0"):
        model.at_depths([0.001])
    rows = synthetic_fe_rows()
    assert len(rows) == len(model.depths)
