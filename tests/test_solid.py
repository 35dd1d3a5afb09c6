"""3D elasticity, the solver layer and the race against CalculiX."""
import importlib.util
import shutil

import numpy as np
import pytest

skfem = pytest.importorskip("skfem")

from hubvib.fem.elasticity import SingularSystemError, rigid_body_modes, solve  # noqa: E402
from hubvib.fem.fast_assembly import elasticity_matrix  # noqa: E402
from hubvib.fem.solvers import pick  # noqa: E402
from skfem.models.elasticity import linear_elasticity  # noqa: E402


@pytest.mark.parametrize("mesh, element", [
    (skfem.MeshTet2.from_mesh(skfem.MeshTet1().refined(2)), skfem.ElementTetP2()),
    (skfem.MeshTet1().refined(3), skfem.ElementTetP1()),
    (skfem.MeshTri2.from_mesh(skfem.MeshTri1().refined(3)), skfem.ElementTriP2()),
])
def test_fast_assembly_equals_scikit_fem(mesh, element):
    """Independent computation: scikit-fem's own weak-form assembly (rounding, 1e-13)."""
    basis = skfem.Basis(mesh, skfem.ElementVector(element), intorder=2)
    reference = linear_elasticity(1.3, 0.7).assemble(basis)
    difference = elasticity_matrix(basis, 1.3, 0.7) - reference
    assert abs(difference).max() <= 1e-13 * abs(reference).max()


class _Box:
    """Unit cube of P2 tetrahedra clamped at x = 0, pulled and twisted at x = 1."""

    def __init__(self):
        mesh = skfem.MeshTet2.from_mesh(skfem.MeshTet1.init_tensor(*[np.linspace(0, 1, 7)] * 3))
        self.basis = skfem.Basis(mesh.with_boundaries({"clamp": lambda x: x[0] == 0}),
                                 skfem.ElementVector(skfem.ElementTetP2()), intorder=2)
        self.K = elasticity_matrix(self.basis, 1.2e11, 8e10)
        face = skfem.FacetBasis(mesh, self.basis.elem, facets=mesh.facets_satisfying(
            lambda x: x[0] == 1))

        @skfem.LinearForm
        def load(v, w):
            x, y, z = w.x
            return 1e6 * v[0] + 1e6 * (-(z - 0.5) * v[1] + (y - 0.5) * v[2])

        self.f = load.assemble(face)

    @property
    def ndofs(self):
        return self.K.shape[0]


def test_rigid_body_modes_carry_no_stress():
    box = _Box()
    modes = rigid_body_modes(box.basis)
    assert modes.shape == (box.ndofs, 6)
    assert np.abs(box.K @ modes).max() < 1e-9 * abs(box.K).max()


@pytest.mark.parametrize("solver", ["amg", "pardiso"])
def test_solvers_agree_with_superlu(solver):
    """A second method: the same system by sparse LU, AMG-CG and PARDISO (1e-7)."""
    if solver == "pardiso" and importlib.util.find_spec("pypardiso") is None:
        pytest.skip("pypardiso not installed")
    box = _Box()
    reference = solve(box, box.f, ["clamp"], solver="superlu")
    other = solve(box, box.f, ["clamp"], solver=solver)
    assert other.solver == solver
    assert np.abs(other.u - reference.u).max() <= 1e-7 * np.abs(reference.u).max()


@pytest.mark.parametrize("solver", ["superlu", "amg", "pardiso"])
def test_supports_that_leave_a_rigid_motion_are_refused(solver):
    box = _Box()
    on_axis = np.flatnonzero((np.abs(box.basis.doflocs[1] - 0.5) < 1e-12)
                             & (np.abs(box.basis.doflocs[2] - 0.5) < 1e-12))
    with pytest.raises(SingularSystemError, match="1 rigid-body motion"):
        solve(box, box.f, [], fixed_dofs=on_axis, solver=solver)  # a line: it can spin


def test_solver_choice_by_size_and_name():
    assert pick("auto", 10 ** 6, 2) == "superlu"
    assert pick("auto", 10 ** 4, 3) == "superlu"
    assert pick("auto", 10 ** 6, 3) in ("pardiso", "amg")
    assert pick("amg", 10, 2) == "amg"
    with pytest.raises(ValueError, match="solver = 'cholesky'; allowed"):
        pick("cholesky", 10, 3)


@pytest.fixture(scope="module")
def coarse_solid_ring():
    pytest.importorskip("gmsh")
    from hubvib.meshing import raba118
    from hubvib.meshing.ring_mesh_3d import ring_mesh_3d
    from hubvib.meshing.levels import solid_options

    return ring_mesh_3d(raba118.ring_gear(), None, options=solid_options(16e-3, 8e-3, 6e-3))


@pytest.mark.slow
def test_solid_c_ru_between_plane_stress_and_plane_strain(coarse_solid_ring):
    """A 40 mm wide ring in 3D is stiffer than in plane stress and softer than in plane
    strain, whose bending stiffness is 1 / (1 - nu^2) = 1.099 times higher."""
    from hubvib.fem.ring_stiffness import ring_stiffness
    from hubvib.meshing import raba118
    from hubvib.meshing.ring_mesh import ring_mesh

    ring = raba118.ring_gear()
    solid = ring_stiffness(ring, coarse_solid_ring, carrier_teeth=[0])
    plane = ring_stiffness(ring, ring_mesh(ring), carrier_teeth=[0])
    assert 1.0 < solid.c_ru / plane.c_ru < 1 / (1 - 0.3 ** 2)
    assert 1.0 < solid.c_r / plane.c_r < 1 / (1 - 0.3 ** 2)


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) not installed")
def test_calculix_solves_the_same_problem(tmp_path, coarse_solid_ring):
    """Second code: CalculiX on our mesh and nodal loads gives the same displacements
    to its print precision (7 digits) and the same c_ru (1e-6)."""
    from hubvib.validation.benchmark import solid_race

    row = solid_race(mesh=coarse_solid_ring, folder=tmp_path)
    assert row["max_rel_difference"] < 1e-6
    assert row["ccx_c_ru"] == pytest.approx(row["c_ru"], rel=1e-6)
