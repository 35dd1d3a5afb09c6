import math

import numpy as np
import pytest

from hubvib import lumped
from hubvib.reducer import lumped_preset
from tests.helpers.energy_reference import stiffness_by_polarisation


def _variants():
    p = lumped_preset("raba118")
    yield "raba118", p
    yield "unequal, c_s, two angles", p.replace(
        theta=(0.1, 1.9, 4.0, 5.2), c_s=2e7, alpha_s=math.radians(21.0), c_sp=2.5e8)
    yield "N = 1", p.replace(theta=(0.7,))
    yield "N = 7", p.replace(theta=lumped.equally_spaced_angles(7, 0.2))
    yield "cracked ring tooth at planet 1", p.replace(c_rp_factors=(0.94, 1.0, 1.0))


@pytest.mark.parametrize("name, params", list(_variants()))
def test_stiffness_equals_polarised_energy(name, params):
    """C from the spring network equals the Hessian of the paper's energy eq. (8)."""
    K = lumped.stiffness_matrix(params)
    reference = np.array(stiffness_by_polarisation(params))
    np.testing.assert_allclose(K, reference, rtol=0, atol=1e-7 * np.abs(reference).max(),
                               err_msg=f"{name}: network vs polarised energy (eq. 8)")


@pytest.mark.parametrize("name, params", list(_variants()))
def test_stiffness_symmetric_positive_semidefinite(name, params):
    K = lumped.stiffness_matrix(params)
    assert np.array_equal(K, K.T)
    assert np.linalg.eigvalsh(K).min() >= -K.shape[0] * np.finfo(float).eps * np.abs(K).max()


def test_mass_matrix_is_paper_eq15():
    p = lumped_preset("raba118")
    expected = [1.9, 1.9, 13.8, 13.8, 6.8, 6.8, 1.16, 13.88, 5.36] + [0.85, 0.85, 0.52] * 3
    np.testing.assert_array_equal(np.diag(lumped.mass_matrix(p)), expected)


def test_printed_matrix_differs_exactly_by_eq10_error():
    """raba118.md fact 2: printed C lacks 1.5 c_sp on x_s, y_s and 1.5 c_rp on x_r, y_r."""
    p = lumped_preset("raba118")
    difference = lumped.stiffness_matrix(p) - lumped.printed_stiffness_matrix(p)
    expected = np.zeros((18, 18))
    expected[0, 0] = expected[1, 1] = 1.5 * p.c_sp
    expected[4, 4] = expected[5, 5] = 1.5 * p.c_rp
    np.testing.assert_allclose(difference, expected, rtol=0, atol=1e-6 * p.c_sp)


def test_printed_matrix_refuses_other_layouts():
    with pytest.raises(lumped.ParameterError, match="N = 3 equally spaced"):
        lumped.printed_stiffness_matrix(lumped_preset("raba118").replace(theta=(0.0, 2.0, 4.0)))


def test_dof_names_follow_paper_eq5():
    assert lumped.dof_names(2)[:12] == (
        "x_s", "y_s", "x_c", "y_c", "x_r", "y_r", "u_s", "u_c", "u_r", "tau_1", "eta_1", "u_1")


def test_unit_ring_mesh_factors_change_nothing():
    p = lumped_preset("raba118")
    np.testing.assert_array_equal(lumped.stiffness_matrix(p.replace(c_rp_factors=(1.0,) * 3)),
                                  lumped.stiffness_matrix(p))


@pytest.mark.parametrize("factors", [(0.9, 1.0), (1.0, 0.0, 1.0), (1.0, float("nan"), 1.0)])
def test_ring_mesh_factors_checked(factors):
    with pytest.raises(lumped.ParameterError, match="c_rp_factors"):
        lumped_preset("raba118").replace(c_rp_factors=factors)
