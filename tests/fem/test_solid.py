"""3D elasticity, the solver layer and the race against CalculiX."""
import importlib.util
import shutil

import numpy as np
import pytest

skfem = pytest.importorskip("skfem")

from hubvib.fem.elasticity import SingularSystemError, rigid_body_modes, solve  # noqa: E402
from hubvib.fem.fast_assembly import elasticity_matrix  # noqa: E402
from hubvib.fem.solvers import DOUBLE_COLUMNS, pick  # noqa: E402
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


@pytest.fixture(scope="module")
def box():
    """The clamped box with its node blocks, built once for the module (no test changes it)."""
    return _box_with_blocks()


def test_rigid_body_modes_carry_no_stress(box):
    modes = rigid_body_modes(box.basis)
    assert modes.shape == (box.ndofs, 6)
    assert np.abs(box.K @ modes).max() < 1e-9 * abs(box.K).max()


@pytest.mark.parametrize("solver", ["amg", "pardiso"])
def test_solvers_agree_with_superlu(solver, box):
    """A second method: the same system by sparse LU, AMG-CG and PARDISO (1e-7)."""
    if solver == "pardiso" and importlib.util.find_spec("pypardiso") is None:
        pytest.skip("pypardiso not installed")
    reference = solve(box, box.f, ["clamp"], solver="superlu")
    other = solve(box, box.f, ["clamp"], solver=solver)
    assert other.solver == solver
    assert np.abs(other.u - reference.u).max() <= 1e-7 * np.abs(reference.u).max()


@pytest.mark.parametrize("solver", ["superlu", "amg", "pardiso"])
def test_supports_that_leave_a_rigid_motion_are_refused(solver, box):
    on_axis = np.flatnonzero((np.abs(box.basis.doflocs[1] - 0.5) < 1e-12)
                             & (np.abs(box.basis.doflocs[2] - 0.5) < 1e-12))
    with pytest.raises(SingularSystemError, match="1 rigid-body motion"):
        solve(box, box.f, [], fixed_dofs=on_axis, solver=solver)  # a line: it can spin


def test_solver_choice_by_size_and_name():
    if importlib.util.find_spec("pypardiso"):
        assert pick("auto", 10 ** 6, 2) == pick("auto", 10 ** 4, 3) == "pardiso"
    else:
        assert pick("auto", 10 ** 6, 2) == pick("auto", 10 ** 4, 3) == "superlu"
        assert pick("auto", 10 ** 6, 3) == "amg"
    assert pick("amg", 10, 2) == "amg"
    with pytest.raises(ValueError, match="solver = 'cholesky'; allowed"):
        pick("cholesky", 10, 3)


@pytest.fixture(scope="module")
def coarse_solid_ring():
    pytest.importorskip("gmsh")
    from hubvib.reducer import raba118
    from hubvib.meshing.ring_mesh_3d import ring_mesh_3d
    from hubvib.meshing.levels import solid_options

    return ring_mesh_3d(raba118.ring_gear(), None, options=solid_options(16e-3, 8e-3, 6e-3))


@pytest.mark.slow
def test_solid_c_ru_between_plane_stress_and_plane_strain(coarse_solid_ring):
    """A 40 mm wide ring in 3D is stiffer than in plane stress and softer than in plane
    strain, whose bending stiffness is 1 / (1 - nu^2) = 1.099 times higher."""
    from hubvib.fem.ring_stiffness import ring_stiffness
    from hubvib.reducer import raba118
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
    from hubvib.benchmarks.solid import solid_race

    row = solid_race(mesh=coarse_solid_ring, folder=tmp_path)
    assert row["max_rel_difference"] < 1e-6
    assert row["ccx_c_ru"] == pytest.approx(row["c_ru"], rel=1e-6)


def _box_with_blocks():
    """The box as a model with node blocks (what PARDISO's block path needs)."""
    from hubvib.fem.fast_assembly import elasticity_block_matrix

    box = _Box()
    box.blocks = elasticity_block_matrix(box.basis, 1.2e11, 8e10)
    return box


def _free(box) -> np.ndarray:
    """The DOFs off the clamped face, as a mask."""
    keep = np.ones(box.ndofs, dtype=bool)
    keep[np.unique(box.basis.get_dofs("clamp").flatten())] = False
    return keep


needs_pardiso = pytest.mark.skipif(importlib.util.find_spec("pypardiso") is None,
                                   reason="pypardiso not installed")


@needs_pardiso
@pytest.mark.parametrize("single", [False, True])
def test_pardiso_on_node_blocks_agrees_with_superlu(single, box):
    """PARDISO on the upper node blocks, in double and in single precision with refinement
    in double, against sparse LU on the CSR matrix: the same displacements to 1e-10, the
    refined residual at the double factorisation's level (1e-12 relative)."""
    from hubvib.fem.solvers import REFINE_TOLERANCE, factorise_blocks

    reference = solve(box, box.f, ["clamp"], solver="superlu").u
    keep = _free(box)
    factor = factorise_blocks(*box.blocks.upper(keep.reshape(-1, 3)[:, 0]), single=single)
    u = factor.solve(box.f[keep])
    factor.free()
    assert np.abs(u - reference[keep]).max() <= 1e-10 * np.abs(reference).max()
    residual = box.K[keep][:, keep] @ u - box.f[keep]
    assert np.abs(residual).max() <= 10 * REFINE_TOLERANCE * np.abs(box.f).max()


@needs_pardiso
def test_single_precision_solve_in_column_chunks_agrees_with_superlu(monkeypatch, box):
    """More unknowns x load columns than ``SOLVE_ENTRIES`` (here set to 5 columns' worth):
    the refined single-precision solve runs chunk by chunk (a ragged last chunk too) and
    gives every column what sparse LU gives, to 1e-10 relative (the refinement's 1e-12
    with margin)."""
    import hubvib.fem.solvers as solvers
    from hubvib.fem.solvers import factorise_blocks

    keep = _free(box)
    monkeypatch.setattr(solvers, "SOLVE_ENTRIES", 5 * int(keep.sum()))
    rng = np.random.default_rng(5)
    loads = np.zeros((box.ndofs, 2 * 5 + 3))
    loads[keep] = rng.standard_normal((keep.sum(), loads.shape[1])) * np.abs(box.f).max()
    reference = solve(box, loads, ["clamp"], solver="superlu").u[keep]
    factor = factorise_blocks(*box.blocks.upper(keep.reshape(-1, 3)[:, 0]), single=True)
    u = factor.solve(loads[keep])
    factor.free()
    scale = np.abs(reference).max(axis=0)
    assert np.all(np.abs(u - reference).max(axis=0) <= 1e-10 * scale), \
        "single precision + refinement, chunked, against SuperLU: 1e-10 relative per column"


@needs_pardiso
def test_single_precision_falls_back_to_double_where_refinement_stalls(monkeypatch, box):
    """Where the refinement does not converge (here: no refinement steps allowed), the
    factor refactorises in double precision (the block arrays its matvec shares) and still
    agrees with SuperLU to 1e-10."""
    import hubvib.fem.solvers as solvers

    keep = _free(box)
    reference = solve(box, box.f, ["clamp"], solver="superlu").u[keep]
    factor = solvers.factorise_blocks(*box.blocks.upper(keep.reshape(-1, 3)[:, 0]),
                                      single=True)
    monkeypatch.setattr(solvers, "REFINE_STEPS", 0)
    u = factor.solve(box.f[keep])
    assert not factor._single, "the stalled refinement refactorised in double precision"
    again = factor.solve(box.f[keep])
    factor.free()
    for v in (u, again):
        assert np.abs(v - reference).max() <= 1e-10 * np.abs(reference).max(), \
            "double refactorisation against SuperLU: 1e-10 relative"


@needs_pardiso
@pytest.mark.parametrize("steps", [None, 0])
def test_free_blocks_factor_agrees_with_superlu(box, monkeypatch, steps):
    """PARDISO on the free node blocks given in float32 only, refined against the whole
    block matrix (``factorise_free_blocks``): the displacements of sparse LU on the
    independently sliced CSR matrix to 1e-10 relative, its residual at the double
    factorisation's level (10 x REFINE_TOLERANCE); with no refinement steps allowed
    (``steps`` 0) the double refactorisation from the same blocks agrees as well."""
    import hubvib.fem.solvers as solvers

    keep = _free(box)
    reference = solve(box, box.f, ["clamp"], solver="superlu").u[keep]
    factor = solvers.factorise_free_blocks(box.blocks, keep.reshape(-1, 3)[:, 0])
    if steps is not None:
        monkeypatch.setattr(solvers, "REFINE_STEPS", steps)
    u = factor.solve(box.f[keep])
    assert factor._single == (steps is None), "float32 kept unless the refinement stalls"
    factor.free()
    assert np.abs(u - reference).max() <= 1e-10 * np.abs(reference).max(), \
        "free-block PARDISO against SuperLU: 1e-10 relative"
    residual = box.K[keep][:, keep] @ u - box.f[keep]
    assert np.abs(residual).max() <= 10 * solvers.REFINE_TOLERANCE * np.abs(box.f).max()


def test_block_matrix_upper_in_single_precision_is_the_rounded_double(box, monkeypatch):
    """``BlockMatrix.upper(keep, float32)`` (copied slice by slice) is the double upper
    block triangle rounded to float32, bit for bit, with the same structure."""
    import hubvib.fem.fast_assembly as fast_assembly

    keep = np.ones(box.ndofs // 3, dtype=bool)
    keep[::7] = False
    double = box.blocks.upper(keep)
    monkeypatch.setattr(fast_assembly, "UPPER_CHUNK", 97)  # many ragged slices on the box
    single = box.blocks.upper(keep, np.float32)
    assert single[2].dtype == np.float32
    assert np.array_equal(single[0], double[0]) and np.array_equal(single[1], double[1])
    assert np.array_equal(single[2], double[2].astype(np.float32))


def test_block_matrix_is_the_csr_matrix(box):
    """The upper node blocks, read back whole, are K; their free part is K[free][:, free]
    (an independent scipy slicing)."""
    K = box.blocks.csr()
    assert abs(K - box.K).max() <= 1e-14 * abs(box.K).max()
    keep = np.ones(box.ndofs // 3, dtype=bool)
    keep[::5] = False
    indptr, indices, values = box.blocks.upper(keep)
    import scipy.sparse as sp

    n = 3 * int(keep.sum())
    upper = sp.bsr_matrix((values, indices, indptr), shape=(n, n))
    dofs = np.repeat(keep, 3)
    expected = sp.triu(box.K[dofs][:, dofs])
    # diagonal blocks are stored whole: compare the upper triangle only (sparse: the dense
    # 5,000 x 5,000 pair cost seconds and said the same)
    assert abs(sp.triu(upper) - expected).max() <= 1e-14 * abs(box.K).max()


def test_supported_system_solves_again_with_one_factorisation(box):
    """Two load sets through one factorisation equal two separate solves."""
    from hubvib.fem.elasticity import supported

    system = supported(box, ["clamp"], solver="superlu")
    first, second = system.solve(box.f).u, system.solve(2 * box.f).u
    system.release()
    alone = solve(box, box.f, ["clamp"], solver="superlu").u
    np.testing.assert_allclose(first, alone, rtol=0, atol=1e-14 * np.abs(alone).max())
    np.testing.assert_allclose(second, 2 * alone, rtol=0, atol=1e-14 * np.abs(alone).max())


@pytest.mark.parametrize("mesh, element", [
    (skfem.MeshTet2.from_mesh(skfem.MeshTet1().refined(1)), skfem.ElementTetP2()),
    (skfem.MeshTri1().refined(2), skfem.ElementTriP1()),
])
def test_lazy_basis_is_scikit_fems_basis(mesh, element):
    """The lazily evaluated basis: DOF locations, function values, measure and a mass matrix
    equal scikit-fem's eagerly built Basis (bit for bit)."""
    from hubvib.fem.basis import vector_basis

    eager = skfem.Basis(mesh, skfem.ElementVector(element), intorder=2)
    lazy = vector_basis(mesh, element, 2)
    assert np.array_equal(eager.doflocs, lazy.doflocs)
    assert np.array_equal(eager.element_dofs, lazy.element_dofs)
    assert np.array_equal(eager.dx, lazy.dx)
    for a, b in zip(eager.basis, lazy.basis):
        assert np.array_equal(a[0], b[0]) and np.array_equal(a[0].grad, b[0].grad)

    @skfem.BilinearForm
    def mass(u, v, w):
        return sum(u[i] * v[i] for i in range(mesh.dim()))

    assert abs(mass.assemble(eager) - mass.assemble(lazy)).max() == 0.0


def test_blas_threads_are_set_and_restored():
    """OpenBLAS runs with the asked thread count inside the block and its own after."""
    from hubvib.foundation.blas import _handles, blas_threads

    if not _handles():
        pytest.skip("no OpenBLAS loaded")
    before = [get() for get, _ in _handles()]
    with blas_threads(1):
        assert all(get() == 1 for get, _ in _handles())
    assert [get() for get, _ in _handles()] == before


@pytest.mark.slow
def test_rim_split_works_on_the_solid_model(coarse_solid_ring):
    """The work-conjugate rim parts (the lumped model's c_ru, c_r) on the solid
    model (the solid crack cases use them): the rigid motion fitted on the root lands of an
    in-plane rigid displacement is that motion (1e-9); the rim parts are stiffer than the
    whole work-conjugate values; and like the root-land readings they lie between plane
    stress and plane strain (factor 1 / (1 - nu^2) = 1.099) against the plane rim parts."""
    from hubvib.reducer import raba118
    from hubvib.fem.ring_stiffness import ring_model, ring_stiffness, root_lands
    from hubvib.fem.ring_work import land_rigid_motions
    from hubvib.meshing.ring_mesh import ring_mesh

    ring = raba118.ring_gear()
    model = ring_model(ring, coarse_solid_ring)
    motion = rigid_body_modes(model.basis)[:, [0, 1, 3]] @ np.array([1e-6, -2e-6, 3e-5])
    fitted = land_rigid_motions(model, root_lands(model, range(ring.teeth)), [0, 5],
                                motion[:, None])[:, :, 0]
    np.testing.assert_allclose(fitted, [[1e-6, -2e-6, 3e-5]] * 2, rtol=1e-9, atol=1e-15,
                               err_msg="solid: rigid motion of the lands reproduced, 1e-9")
    solid = ring_stiffness(ring, coarse_solid_ring, carrier_teeth=[0]).work
    plane = ring_stiffness(ring, ring_mesh(ring), carrier_teeth=[0]).work
    assert solid.c_ru_rim > solid.c_ru and solid.c_r_rim > solid.c_r, "rim stiffer than whole"
    assert 1.0 < solid.c_ru_rim / plane.c_ru_rim < 1 / (1 - 0.3 ** 2), "c_ru_rim, 3D vs 2D"
    assert 1.0 < solid.c_r_rim / plane.c_r_rim < 1 / (1 - 0.3 ** 2), "c_r_rim, 3D vs 2D"


@pytest.mark.parametrize("mesh", [skfem.MeshTet1().refined(2), skfem.MeshTri1().refined(3)])
@pytest.mark.parametrize("sort", [True, False])
def test_int64_entity_numbering_is_scikit_fems(mesh, sort):
    """``meshing/skfem_meshes.build_entities`` (one int64 key per vertex tuple) gives
    scikit-fem's own edges and facets and element maps, bit for bit (independent:
    ``np.unique`` over columns)."""
    from hubvib.meshing.skfem_meshes import build_entities

    for entities in (mesh.elem.refdom.facets, mesh.elem.refdom.edges):
        if entities is None:
            continue
        ours = build_entities(mesh.t, entities, sort)
        theirs = skfem.Mesh.build_entities(mesh.t, entities, sort)
        assert np.array_equal(ours[0], theirs[0]) and np.array_equal(ours[1], theirs[1])


@pytest.mark.slow
def test_to_skfem_boundary_facets_are_the_named_facets(coarse_solid_ring):
    """Every named boundary facet of the gmsh mesh maps to the scikit-fem facet with the
    same three vertices (searched by int64 keys); a facet that is no mesh facet is
    refused by name."""
    from dataclasses import replace

    from hubvib.meshing.to_skfem import to_skfem

    fe, vertex_of = to_skfem(coarse_solid_ring)
    for name, elements in coarse_solid_ring.boundaries.items():
        expected = np.sort(vertex_of[elements[:, :3]], axis=1)
        assert np.array_equal(np.sort(fe.facets[:, fe.boundaries[name]].T, axis=1), expected)
    cells = coarse_solid_ring.cells
    wrong = cells[:1, [0, 1, 2, 4, 5, 6]].copy()
    wrong[0, 2] = cells[:, :4][~np.isin(cells[:, :4], cells[0, :4])][0]  # a non-facet
    broken = replace(coarse_solid_ring, boundaries={"odd": wrong})
    with pytest.raises(ValueError, match="boundary group 'odd' has facets that are not"):
        to_skfem(broken)


@needs_pardiso
def test_mkl_symmetric_block_product_is_the_csr_product(box):
    """MKL's symmetric product on the upper block triangle equals scipy's product with the
    whole CSR matrix (1e-14 relative), for one column and several."""
    from hubvib.fem.mkl_sparse import SymmetricBlockProduct

    p = box.blocks.pattern
    product = SymmetricBlockProduct(p.indptr, p.indices, box.blocks.values)
    x = np.random.default_rng(3).standard_normal((box.ndofs, 3))
    for v in (x[:, 0], x):
        expected = box.K @ v
        assert np.abs(product(v) - expected).max() <= 1e-14 * np.abs(expected).max()


@needs_pardiso
@pytest.mark.parametrize("columns", [1, DOUBLE_COLUMNS])
def test_pardiso_with_partly_held_nodes_agrees_with_superlu(box, columns):
    """u_z held at the nodes of one half of the box (a symmetry plane's condition, nodes
    that keep u_x, u_y): PARDISO keeps those nodes as blocks (``_hold_components``) and
    gives what sparse LU gives on the CSR matrix without the held rows, to 1e-10 relative
    (the refinement's 1e-12 with margin), in single precision refined (1 column) and in
    double precision (``DOUBLE_COLUMNS`` columns, the solid sweep's path)."""
    from hubvib.fem.elasticity import supported

    z = box.basis.doflocs[2]
    held = np.flatnonzero((z <= np.median(z)) & (np.arange(box.ndofs) % 3 == 2))
    loads = box.f[:, None] * np.linspace(1.0, 2.0, columns)
    reference = solve(box, loads, ["clamp"], fixed_dofs=held, solver="superlu").u
    system = supported(box, ["clamp"], fixed_dofs=held, solver="pardiso", columns=columns)
    assert system.factor._factor._single == (columns < DOUBLE_COLUMNS), "precision switch"
    u = system.solve(loads).u
    system.release()
    assert np.abs(u - reference).max() <= 1e-10 * np.abs(reference).max(), \
        "PARDISO with held components against SuperLU: 1e-10 relative"
