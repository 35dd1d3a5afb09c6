"""Shift-invert Lanczos with the project's PARDISO factor (``fem.modal.lowest_modes``)
against ARPACK's own SuperLU factor, on the Raba 118/76 ring gear with a root crack: the
same modes to round-off, and a clear refusal where K - sigma M is not positive definite."""
import numpy as np
import pytest

pytest.importorskip("pypardiso")
pytest.importorskip("gmsh")
pytest.importorskip("skfem")

from hubvib.fem.modal import lowest_modes  # noqa: E402

#: relative eigenvalue agreement of the two factorisations.  Clamped (sigma = 0) both
#: give the Rayleigh quotients of their shapes to ~1e-13; free-free (K + 1e4 M, condition
#: ~1e11) SuperLU's sixth mode is off its own Rayleigh quotient by 2e-10, PARDISO's by 3e-13
EIGENVALUE_RTOL = {"clamped": 1e-10, "free-free": 1e-9}


@pytest.fixture(scope="module")
def ring_model():
    from hubvib.reducer import raba118
    from hubvib.reducer.stages import material, ring_gear
    from hubvib.fem.elasticity import plane_model
    from hubvib.meshing.crack import Crack
    from hubvib.meshing.levels import scaled_options
    from hubvib.meshing.ring_mesh import ring_mesh

    design = raba118.design()
    ring = ring_gear(design)
    mesh = ring_mesh(ring, Crack(0, 0.012), scaled_options(8.0))
    return plane_model(mesh, material(design), ring.gear.face_width)


# ~5 s with the ring's mesh: the default run's renders take the PARDISO path
# (tests/render/test_renders.py: test_fe_ring_fields_physics)
@pytest.mark.slow
@pytest.mark.parametrize("case, groups, first", [("clamped", ["supports"], 0),
                                                  ("free-free", None, 3)],
                         ids=["clamped sigma 0", "free-free sigma -1e4"])
def test_pardiso_modes_equal_superlu_modes(ring_model, case, groups, first):
    superlu = lowest_modes(ring_model, 6, groups, solver="superlu")
    pardiso = lowest_modes(ring_model, 6, groups, solver="pardiso")
    assert (superlu.solver, pardiso.solver) == ("superlu", "pardiso"), \
        "each side of the comparison took the factorisation it names"
    if first:  # free-free: three rigid-body modes at ~0, any basis of their space
        assert np.all(superlu.omega[:first] < 1.0) and np.all(pardiso.omega[:first] < 1.0), \
            "free-free ring: three rigid-body modes below 1 rad/s with either factor"
    rtol = EIGENVALUE_RTOL[case]
    np.testing.assert_allclose(
        pardiso.omega[first:] ** 2, superlu.omega[first:] ** 2, rtol=rtol,
        err_msg=f"{case} eigenvalues: PARDISO vs SuperLU shift-invert (rtol {rtol:g})")
    # both sign-fixed (largest entry positive) and mass-normalised: the same vectors
    np.testing.assert_allclose(pardiso.shapes[:, first:], superlu.shapes[:, first:],
                               atol=1e-8 * np.abs(superlu.shapes).max(),
                               err_msg="sign-fixed, mass-normalised shapes: PARDISO vs "
                                       "SuperLU (1e-8 of the largest entry)")
    assert pardiso.rayleigh_error < 1e-12, \
        f"PARDISO: Rayleigh quotient = eigenvalue to 1e-12 (got {pardiso.rayleigh_error:.1e})"


# slow: the default run's renders take the "auto" path (tests/render/test_renders.py)
@pytest.mark.slow
def test_auto_solver_is_pardiso_and_repeatable(ring_model):
    """``solver="auto"`` picks PARDISO where pypardiso is installed
    (``fem.solvers.pick``): the same modes as naming it, twice alike."""
    named = lowest_modes(ring_model, 2, ["supports"], solver="pardiso")
    auto = lowest_modes(ring_model, 2, ["supports"])
    assert auto.solver == "pardiso"
    np.testing.assert_array_equal(auto.omega, named.omega)
    np.testing.assert_array_equal(auto.shapes, named.shapes)


@pytest.mark.slow  # the ring's mesh (~2 s)
def test_unsupported_ring_at_shift_zero_is_refused_by_name(ring_model):
    """A group that holds nothing (sigma = 0): K is singular, and PARDISO's Cholesky says so
    in one line naming the shift and the supports (ARPACK's SuperLU returned zero
    frequencies for the rigid-body motion)."""
    from hubvib.fem.elasticity import SingularSystemError

    empty = "no_such_facets"
    ring_model.basis.mesh.boundaries[empty] = np.array([], dtype=np.int64)
    try:
        with pytest.raises(SingularSystemError, match=r"sigma = 0 .*no_such_facets"):
            lowest_modes(ring_model, 2, [empty], sigma=0.0, solver="pardiso")
    finally:
        del ring_model.basis.mesh.boundaries[empty]


def test_amg_is_no_shift_invert_solver():
    """AMG gives no shift-invert operator: refused before any model is read."""
    with pytest.raises(ValueError, match="solver = 'amg'; allowed: auto, pardiso, superlu"):
        lowest_modes(None, 2, ["supports"], solver="amg")
