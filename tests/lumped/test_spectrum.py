import numpy as np
import pytest

from hubvib import lumped
from hubvib.reducer import lumped_preset
from hubvib.lumped.eigensolve import solve_assembled
from hubvib.lumped.network import mass_diagonal
from hubvib.validation.raba118 import PUBLISHED_RAD_S


def test_printed_matrix_reproduces_published_spectrum():
    """Paper eq. (16), 18 values; raba118.md fact 3: within 0.2 % as sqrt(|lambda|)."""
    spectrum = lumped.printed_modes(lumped_preset("raba118"))
    np.testing.assert_allclose(spectrum.omega, PUBLISHED_RAD_S, rtol=2e-3,
                               err_msg="printed matrix vs Yaglinsky et al. eq. (16)")
    assert spectrum.imaginary.sum() == 4  # fact 2: four negative eigenvalues
    published_imaginary = set(PUBLISHED_RAD_S[spectrum.imaginary])
    assert published_imaginary == {6575.0, 13520.0}


def test_printed_matrix_is_reported_indefinite():
    p = lumped_preset("raba118")
    with pytest.raises(lumped.IndefiniteStiffnessError, match="4 negative eigenvalue"):
        solve_assembled(lumped.printed_stiffness_matrix(p), mass_diagonal(p))


def test_energy_model_spectrum_fact4():
    """raba118.md fact 4: translational pairs near 1908, 3370, 5865 rad/s; rotational agree."""
    spectrum = lumped.natural_modes(lumped_preset("raba118"))
    kinds = np.array(spectrum.kind)
    translational = np.unique(np.round(spectrum.omega[kinds == "translational"], 3))
    np.testing.assert_allclose(translational[:3], [1908, 3370, 5865], rtol=1e-3)
    rotational = spectrum.omega[kinds == "rotational"]
    np.testing.assert_allclose(rotational, [337, 537, 8090, 10440, 31760, 43330], rtol=2e-3,
                               err_msg="rotational modes vs published eq. (16)")


@pytest.mark.parametrize("method", lumped.METHODS)
def test_modes_are_mass_normalised_eigenvectors(method):
    p = lumped_preset("raba118").replace(theta=(0.0, 2.2, 4.5, 5.5))
    s = lumped.natural_modes(p, method)
    K, M = lumped.stiffness_matrix(p), lumped.mass_matrix(p)
    np.testing.assert_allclose(s.shapes.T @ M @ s.shapes, np.eye(p.n_dof), atol=1e-12)
    residual = K @ s.shapes - M @ s.shapes * s.eigenvalues
    assert np.abs(residual).max() <= 1e-9 * np.abs(K).max() * np.abs(s.shapes).max()
    # Rayleigh quotient equals the eigenvalue (scikit-fem TestEx21 habit)
    np.testing.assert_allclose(np.einsum("ij,ij->j", s.shapes, K @ s.shapes), s.eigenvalues,
                               rtol=1e-10)


def test_canonical_shapes_do_not_depend_on_solver():
    p = lumped_preset("raba118")
    a = lumped.natural_modes(p, "jacobi").shapes
    b = lumped.natural_modes(p, "eigh").shapes
    np.testing.assert_allclose(a, b, atol=1e-7 * np.abs(a).max())


def test_repeatable_bitwise():
    a = lumped.natural_modes(lumped_preset("raba118"))
    b = lumped.natural_modes(lumped_preset("raba118"))
    assert np.array_equal(a.shapes, b.shapes) and np.array_equal(a.eigenvalues, b.eigenvalues)


@pytest.mark.parametrize("n", range(3, 13))
def test_multiplicities_lin_parker(n):
    """Lin & Parker (1999): 6 rotational x1, 6 translational x2, 3 planet x(N-3)."""
    from hubvib.validation.theory import expected_pattern, multiplicity_pattern

    params = lumped_preset("raba118").replace(theta=lumped.equally_spaced_angles(n, 0.4))
    assert multiplicity_pattern(params) == expected_pattern(n)


def test_planet_modes_leave_central_members_at_rest():
    s = lumped.natural_modes(lumped_preset("raba118").replace(theta=lumped.equally_spaced_angles(6)))
    planet = np.array(s.kind) == "planet"
    assert planet.sum() == 9
    assert np.abs(s.shapes[:9, planet]).max() < 1e-8 * np.abs(s.shapes[:, planet]).max()


def test_unequal_spacing_mixes_types():
    s = lumped.natural_modes(lumped_preset("raba118").replace(theta=(0.0, 2.0, 4.5)))
    assert "mixed" in s.kind and max(s.multiplicity) == 1


def test_rigid_body_modes_reported_as_zero():
    p = lumped_preset("raba118").replace(c_su=0.0, c_cu=0.0, c_ru=0.0)
    s = lumped.natural_modes(p)
    # floating sun, all members free to turn: the 2-DOF differential is a mechanism
    assert s.n_rigid == 2
    assert s.kind[:2] == ("rigid-body", "rigid-body")
    assert np.all(s.omega[:2] == 0.0) and np.all(np.isfinite(s.omega)) and s.omega[2] > 100
    K = lumped.stiffness_matrix(p)
    assert np.abs(K @ s.shapes[:, :2]).max() < 1e-6 * np.abs(K).max() * np.abs(s.shapes).max()
