import math

import pytest

from hubvib import lumped
from hubvib.reducer import lumped_preset
from hubvib.runtime.params_input import preset_parameters
from hubvib.lumped import ParameterError


def test_raba118_preset_matches_paper_table():
    p = lumped_preset("raba118")  # paper's table (raba118.md)
    assert (p.m_s, p.m_r, p.m_c, p.m_p) == (1.9, 6.8, 13.8, 0.85)
    assert (p.mu_s, p.mu_r, p.mu_c, p.mu_p) == (1.16, 5.36, 13.88, 0.52)
    assert (p.c_sp, p.c_rp, p.c_p, p.c_c, p.c_r) == (3e8, 3e8, 1e8, 1e8, 1e8)
    assert (p.c_su, p.c_cu, p.c_ru, p.c_s) == (1e6, 1e6, 1e6, 0.0)
    assert math.degrees(p.alpha_r) == pytest.approx(25.28, abs=1e-12)
    assert p.n_planets == 3 and p.n_dof == 18 and p.equally_spaced()


@pytest.mark.parametrize("field", ["c_sp", "c_rp", "c_p", "c_c", "c_r", "c_s", "c_su", "c_cu", "c_ru"])
@pytest.mark.parametrize("value", [-1.0, math.nan, math.inf, "1e6"])
def test_bad_stiffness_names_field_and_range(field, value):
    with pytest.raises(ParameterError, match=field):
        lumped_preset("raba118").replace(**{field: value})


@pytest.mark.parametrize("field", ["m_s", "m_c", "m_r", "m_p", "mu_s", "mu_c", "mu_r", "mu_p", "d_r"])
@pytest.mark.parametrize("value", [0.0, -2.0, math.nan, -math.inf])
def test_bad_mass_or_diameter(field, value):
    with pytest.raises(ParameterError, match=rf"{field} = .* must be"):
        lumped_preset("raba118").replace(**{field: value})


def test_zero_stiffness_is_allowed():
    assert lumped_preset("raba118").replace(c_ru=0.0).c_ru == 0.0


@pytest.mark.parametrize("theta, message", [
    ((), "N >= 1"),
    ((0.0, 0.0, 2.0), "same place"),
    ((0.0, 2 * math.pi), "same place"),
    (0.5, "sequence"),
    ((0.0, math.nan), r"theta\[1\]"),
])
def test_bad_planet_angles(theta, message):
    with pytest.raises(ParameterError, match=message):
        lumped_preset("raba118").replace(theta=theta)


@pytest.mark.parametrize("value", [0.0, math.pi / 2, -0.1])
def test_bad_pressure_angle(value):
    with pytest.raises(ParameterError, match=r"alpha_s .*\(0, pi/2\)|alpha_s = .* must be"):
        lumped_preset("raba118").replace(alpha_s=value)


def test_unknown_field_and_preset():
    with pytest.raises(ParameterError, match="unknown parameter"):
        lumped_preset("raba118").replace(c_xx=1.0)
    with pytest.raises(ParameterError, match="available: .*'raba118'"):
        preset_parameters("raba119")


@pytest.mark.parametrize("n", [0, -1, 2.5, True])
def test_bad_planet_count(n):
    with pytest.raises(ParameterError, match="n_planets"):
        lumped.equally_spaced_angles(n)
