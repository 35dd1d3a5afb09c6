import math

import numpy as np
import pytest

from hubvib import lumped
from hubvib.reducer import lumped_preset


def _central_difference(params, parameter, h=1e-5):
    value = getattr(params, parameter)
    up = lumped.natural_modes(params.replace(**{parameter: value * (1 + h)})).omega
    down = lumped.natural_modes(params.replace(**{parameter: value * (1 - h)})).omega
    return (up - down) / (2 * h * value)


@pytest.mark.parametrize("theta", [None, (0.0, 2.0, 4.4)])
@pytest.mark.parametrize("parameter", ["c_ru", "c_sp", "c_rp", "c_p", "c_r", "m_s", "mu_r", "m_p"])
def test_analytic_sensitivity_matches_finite_differences(parameter, theta):
    params = lumped_preset("raba118") if theta is None else lumped_preset("raba118").replace(theta=theta)
    analytic = lumped.frequency_sensitivity(params, parameter).d_omega
    numeric = _central_difference(params, parameter)
    scale = np.abs(numeric).max()
    np.testing.assert_allclose(analytic, numeric, rtol=1e-4, atol=1e-6 * scale,
                               err_msg=f"d omega / d {parameter}: analytic vs central differences")


def test_sensitivity_rejects_unknown_parameter():
    with pytest.raises(lumped.ParameterError, match="sensitivities exist for"):
        lumped.frequency_sensitivity(lumped_preset("raba118"), "alpha_s")


def test_fig4_ratios_fact5():
    """raba118.md fact 5: c_ru 1e6 -> 1e5 lowers omega_1 ~1.8x and omega_2 ~1.1x."""
    ratio = lumped.sweep(lumped_preset("raba118"), "c_ru", [1e6, 1e5]).ratio(0, 1)
    assert 1 / ratio[0] == pytest.approx(1.8, abs=0.05)
    assert 1 / ratio[1] == pytest.approx(1.1, abs=0.05)


def test_tracking_follows_modes_through_crossings():
    """c_ru enters only rotational modes: tracked translational branches stay flat
    (Lin & Parker), although rotational branches cross them (Fig. 4 range)."""
    result = lumped.sweep(lumped_preset("raba118"), "c_ru", np.geomspace(1e4, 1e8, 61))
    translational = [i for i, k in enumerate(result.kind) if k == "translational"]
    np.testing.assert_allclose(result.omega[:, translational],
                               np.broadcast_to(result.omega[0, translational],
                                               result.omega[:, translational].shape), rtol=1e-9)
    assert not np.allclose(result.omega, result.sorted_omega)  # crossings did happen
    rotational = [i for i, k in enumerate(result.kind) if k == "rotational"]
    assert np.all(np.diff(result.omega[:, rotational], axis=0) >= -1e-9)  # Rayleigh monotonicity


def test_shift_table_consistency():
    shift = lumped.frequency_shift(lumped_preset("raba118"), "c_ru", 1e5)
    np.testing.assert_allclose(shift.delta_hz, shift.delta_rad_s / (2 * math.pi))
    np.testing.assert_allclose(shift.percent, 100 * shift.delta_rad_s / shift.omega_base)
    translational = np.array(shift.kind) == "translational"
    # c_ru does not enter the translational modes (Lin & Parker 1999): their shift is
    # exactly 0, never a round-off whose sign differs between BLAS builds
    assert not np.signbit(shift.delta_rad_s[translational]).any()
    assert (shift.percent[translational] == 0).all()
    assert shift.percent[0] == pytest.approx(-43.64, abs=0.01)


def test_shift_to_same_value_is_zero():
    shift = lumped.frequency_shift(lumped_preset("raba118"), "c_ru", 1e6)
    assert np.abs(shift.delta_rad_s).max() == 0.0


def test_modal_energy_fractions():
    s = lumped.natural_modes(lumped_preset("raba118").replace(theta=lumped.equally_spaced_angles(4)))
    e = lumped.modal_energy(s)
    np.testing.assert_allclose(e.strain.sum(axis=1), 1.0, rtol=1e-12)
    np.testing.assert_allclose(e.kinetic.sum(axis=1), 1.0, rtol=1e-12)
    kinds = np.array(s.kind)
    c_r = e.springs.index("c_r")
    assert e.strain[kinds == "rotational", c_r].max() < 1e-12  # ring does not translate
    central = [e.members.index(m) for m in ("sun", "carrier", "ring")]
    assert e.kinetic[np.ix_(kinds == "planet", central)].max() < 1e-12
