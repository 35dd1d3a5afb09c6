"""FE elasticity and ring stiffness checks (sources and tolerances in each assertion)."""
import math

import numpy as np
import pytest

pytest.importorskip("gmsh")
skfem = pytest.importorskip("skfem")

from hubvib.fem.annulus import fe_k_theta  # noqa: E402
from hubvib.fem.elasticity import SingularSystemError, plane_model, solve  # noqa: E402
from hubvib.fem.material import Material, MaterialError  # noqa: E402
from hubvib.fem.ring_stiffness import ring_stiffness  # noqa: E402
from hubvib.reducer import raba118  # noqa: E402
from hubvib.meshing.annulus import annulus_mesh  # noqa: E402
from hubvib.meshing.crack import Crack  # noqa: E402
from hubvib.meshing.ring_gear import Supports  # noqa: E402
from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh  # noqa: E402

A, B, T = 0.08, 0.10, 0.01  # annulus radii and thickness [m]
STEEL = Material()


def annulus_k_theta(size, order):
    return fe_k_theta(A, B, T, STEEL, size, order)


EXACT = 4 * math.pi * STEEL.shear_modulus * T * A ** 2 * B ** 2 / (B ** 2 - A ** 2)


def test_annulus_curved_p2_reaches_1e6():
    """Exact k_theta = 4 pi G t a^2 b^2 / (b^2 - a^2) (Timoshenko & Goodier, Lame problem):
    curved P2 within 1e-6 at under 1e4 DOFs."""
    k, dofs = annulus_k_theta(4e-3, 2)
    assert dofs < 1e4
    assert k == pytest.approx(EXACT, rel=1e-6)


@pytest.mark.parametrize("order, rate", [(1, 2.0), (2, 4.0)])
def test_annulus_converges_at_the_theoretical_rate(order, rate):
    """Energy-norm error h^p gives stiffness error h^(2p): fitted rate within 0.5 of 2p."""
    sizes = [8e-3, 4e-3, 2e-3]
    errors = [abs(annulus_k_theta(h, order)[0] / EXACT - 1) for h in sizes]
    fitted = np.polyfit(np.log(sizes), np.log(errors), 1)[0]
    assert fitted == pytest.approx(rate, abs=0.5), errors


@pytest.mark.parametrize("order", [1, 2])
def test_stiffness_is_symmetric_and_rigid_motions_cost_nothing(order):
    """K symmetric; a rigid rotation and a translation (interpolated exactly: isoparametric
    elements reproduce linear fields) give zero strain energy (1e-12 relative)."""
    model = plane_model(annulus_mesh(A, B, 8e-3, order), STEEL, T)
    K = model.K
    assert abs(K - K.T).max() <= 1e-12 * abs(K).max()
    for field in (lambda x: np.array([-x[1], x[0]]), lambda x: np.array([1.0 + 0 * x[0], 0 * x[0]])):
        u = model.basis.project(field)
        assert model.energy(u) <= 1e-12 * abs(K).max() * (u @ u)


def test_unsupported_model_is_refused():
    model = plane_model(annulus_mesh(A, B, 8e-3, 1), STEEL, T)
    with pytest.raises(SingularSystemError, match="no support"):
        solve(model, np.zeros(model.ndofs), [])
    with pytest.raises(SingularSystemError, match="missing: hub"):
        solve(model, np.zeros(model.ndofs), ["hub"])


@pytest.mark.parametrize("kwargs, field", [(dict(nu=0.5), "nu"), (dict(nu=-1.0), "nu"),
                                           (dict(E=0.0), "E"), (dict(density=-1), "density")])
def test_bad_material(kwargs, field):
    with pytest.raises(MaterialError, match=f"material.{field}"):
        Material(**kwargs)


def test_bad_thickness():
    with pytest.raises(MaterialError, match="thickness"):
        plane_model(annulus_mesh(A, B, 8e-3, 1), STEEL, 0.0)


RING = raba118.ring_gear()
COARSE = MeshOptions(size=4e-3, tooth_size=1e-3, tip_size=1e-4, load_size=2e-4)


@pytest.mark.slow
def test_c_ru_is_independent_of_carrier_angle_on_a_symmetric_ring():
    """Uncracked ring held on its whole outer surface: c_ru equal at every carrier
    position (tooth steps) within the mesh's asymmetry, 2e-3."""
    ring = raba118.ring_gear(supports=Supports(count=0))
    result = ring_stiffness(ring, ring_mesh(ring, None, COARSE), carrier_teeth=[0, 5, 11])
    spread = np.ptp(result.c_ru_positions) / result.c_ru
    assert spread < 2e-3


@pytest.mark.slow
def test_c_ru_falls_with_crack_depth_and_zero_depth_is_intact():
    """c_ru of the Raba ring (mean over one planet pitch of carrier positions): a zero-depth
    crack gives the intact value exactly (same mesh); deeper cracks give lower values."""
    values = []
    for depth in (0.0, 4e-3, 10e-3, 18e-3):
        mesh = ring_mesh(RING, Crack(0, depth), COARSE)
        values.append(ring_stiffness(RING, mesh).c_ru)
    intact = ring_stiffness(RING, ring_mesh(RING, None, COARSE)).c_ru
    assert values[0] == intact
    assert all(b < a for a, b in zip(values, values[1:])), values


def test_ring_stiffness_needs_its_groups():
    mesh = annulus_mesh(A, B, 8e-3, 1)
    with pytest.raises(ValueError, match="lacks the groups"):
        ring_stiffness(RING, mesh)


# -- boundary integrals and point location on fine curved meshes -------

def _small_curved_mesh(side=1e-5, origin=(0.1, 0.05)):
    """A curved-type (isoparametric P2) square of side ``side`` [m] far from the origin, with
    its edge mid nodes on the straight edges: elements ~side/4, |x| / h ~ 1e4."""
    square = skfem.MeshTri1.init_sqsymmetric().refined(2)
    mesh = skfem.MeshTri2.from_mesh(square)
    return skfem.MeshTri2(mesh.doflocs * side + np.array(origin)[:, None], mesh.t)


def test_facet_basis_integrates_exactly_where_newton_fails():
    """The perimeter and first moment of a square are exact (4 L, L^2 (4 x0 + 2 L)); scikit-fem's
    FacetBasis, whose Newton inversion fails on such elements (the ring at scale 0.6), is the
    failure this replaces."""
    from hubvib.fem.facets import facet_basis

    side, (x0, y0) = 1e-5, (0.1, 0.05)
    mesh = _small_curved_mesh(side, (x0, y0))
    boundary = mesh.boundary_facets()
    with pytest.raises(Exception, match="Newton"):
        skfem.FacetBasis(mesh, skfem.ElementTriP2(), facets=boundary, intorder=4)
    basis = facet_basis(mesh, skfem.ElementTriP2(), boundary, 4)
    length = skfem.Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(basis)
    moment = skfem.Functional(lambda w: w.x[0]).assemble(basis)
    assert length == pytest.approx(4 * side, rel=1e-12), "perimeter 4 L"
    assert moment == pytest.approx(side * (4 * x0 + 2 * side), rel=1e-12), "int x ds"


def test_facet_basis_matches_scikit_fem_where_newton_converges():
    """On the annulus (curved P2, normal element sizes) the reference points and a load
    vector with normals equal scikit-fem's own FacetBasis (its Newton tolerance, 1e-12)."""
    from hubvib.fem.facets import facet_basis
    from hubvib.meshing.to_skfem import to_skfem

    mesh, _ = to_skfem(annulus_mesh(A, B, 8e-3, 2))
    element = skfem.ElementVector(skfem.ElementTriP2())
    facets = mesh.boundaries["outer"]
    ours = facet_basis(mesh, element, facets, 4)
    theirs = skfem.FacetBasis(mesh, element, facets=facets, intorder=4)

    @skfem.LinearForm
    def load(v, w):
        return (1 + w.x[0]) * v[0] + w.x[1] * v[1] + w.n[0] * v[1] - w.n[1] * v[0]

    a, b = load.assemble(ours), load.assemble(theirs)
    assert np.abs(a - b).max() <= 1e-11 * np.abs(b).max()


def test_points_are_located_in_small_curved_elements():
    """Reference coordinates of mapped points come back to round-off in an element whose
    size is 1e-4 of its distance from the origin (scikit-fem's invF gives up there)."""
    from hubvib.fem.locate import reference_coordinates

    mesh = _small_curved_mesh()
    # curve the elements: move every mid node by a tenth of the element size
    bent = mesh.doflocs.copy()
    mids = np.arange(mesh.nvertices, bent.shape[1])
    bent[:, mids] += 2.5e-7 * np.array([[0.1], [-0.07]])
    mesh = skfem.MeshTri2(bent, mesh.t)
    cells = np.arange(mesh.nelements)
    X = np.tile(np.array([[0.2], [0.3]]), len(cells))
    points = skfem.MappingIsoparametric(mesh, mesh.elem(), mesh.bndelem).F(
        X[:, :, None], tind=cells)[:, :, 0]
    found = reference_coordinates(mesh, points, cells)
    assert np.abs(found - X).max() < 1e-9


@pytest.mark.slow
def test_c_ru_at_scale_0_6():
    """The ring at element scale 0.6 (the tooth-load facet basis failed);
    c_ru lies between the values at scales 0.71 and 0.5 within their spread (1.66337e10,
    1.66364e10 N/m, convergence study)."""
    from hubvib.reducer import raba118
    from hubvib.validation.convergence import _ring_level

    value = _ring_level(0.6, "c_ru", raba118.ring_gear())["value"]
    assert 1.6632e10 < value < 1.6638e10


# -- one factorisation for c_ru, c_r and the cracked tooth ---------------

@pytest.mark.slow
def test_one_factorisation_gives_the_ring_and_the_cracked_tooth():
    """Ring loads and the cracked tooth's unit forces as columns of one solve: c_ru at every
    carrier position, c_r and the tooth compliance equal those of separate assemblies and
    factorisations (ring_stiffness with SuperLU, fe_tooth_compliance) on the same mesh,
    to 1e-9."""
    from hubvib.fem.crack_level import ring_and_tooth
    from hubvib.fem.tooth_fe import fe_tooth_compliance
    from hubvib.meshing.levels import scaled_options

    planet = raba118.gear_body("planet")
    crack = Crack(0, 8e-3)
    mesh = ring_mesh(RING, crack, scaled_options(8.0))  # any mesh: both paths solve it
    ring, tooth = ring_and_tooth(RING, planet, crack, mesh)
    alone = ring_stiffness(RING, mesh, solver="superlu")  # and a second solver
    np.testing.assert_allclose(ring.c_ru_positions, alone.c_ru_positions, rtol=1e-9)
    assert ring.c_r == pytest.approx(alone.c_r, rel=1e-9)
    # the work-conjugate rim parts (the lumped model's) from the shared solve too
    np.testing.assert_allclose(ring.work.c_ru_rim_positions, alone.work.c_ru_rim_positions,
                               rtol=1e-9)
    assert ring.work.c_r_rim == pytest.approx(alone.work.c_r_rim, rel=1e-9)
    separate = fe_tooth_compliance(RING, mesh, tooth.radii)
    np.testing.assert_allclose(tooth.compliance, separate.compliance, rtol=1e-9)


@pytest.mark.slow
def test_crack_case_equals_separate_solves():
    """A crack case computed with one assembly and factorisation per level gives the values
    of the separate path (ring: estimate_ring; cracked tooth: engaged_ring_mesh, each with its
    own assembly and SuperLU factorisation) to 1e-9, the work-conjugate rim parts (the lumped
    model's c_ru, c_r) and the root-land readings beside them, on three levels; scale 2
    keeps it cheap (at scale 4 the coarsest level's planet tooth is too coarse to probe)."""
    import functools

    from hubvib.fem.estimate import estimate_crack_case, estimate_ring
    from hubvib.fem.three_level import three_level_error
    from hubvib.fem.tooth_stiffness import engaged_ring_mesh
    from hubvib.meshing.levels import scaled_options

    planet = raba118.gear_body("planet")
    crack = Crack(0, 8e-3)
    mesher = functools.lru_cache(maxsize=2)(ring_mesh)
    shared = estimate_crack_case(RING, planet, crack, 2.0, mesher=mesher)
    ring = estimate_ring(RING, crack, 2.0, mesher=mesher, definition="rim")
    fine, coarse, coarsest = (engaged_ring_mesh(planet, RING, crack, scaled_options(s),
                                                mesher=mesher) for s in (2.0, 4.0, 8.0))
    pairs = [(shared.c_ru, ring.c_ru), (shared.c_ru_min, ring.c_ru_min),
             (shared.c_ru_max, ring.c_ru_max), (shared.c_r, ring.c_r),
             (shared.c_rp_engaged_ratio, fine.mean_ratio),
             (shared.c_rp_engaged_min_ratio, fine.min_ratio),
             (shared.c_ru_root_land, ring.c_ru_root_land),
             (shared.c_r_root_land, ring.c_r_root_land)]
    for ours, theirs in pairs:
        assert ours == pytest.approx(theirs, rel=1e-9), "shared against separate solves"
    assert shared.c_ru_error == pytest.approx(ring.c_ru_error, rel=1e-6)
    assert shared.c_ru_root_land_error == pytest.approx(ring.c_ru_root_land_error, rel=1e-6)
    assert shared.c_ru < shared.c_ru_root_land, "rim part softer than the root-land reading"
    assert shared.c_rp_engaged_ratio_error == pytest.approx(three_level_error(
        coarsest.mean_ratio, coarse.mean_ratio, fine.mean_ratio).error, rel=1e-6), \
        "the three-level bar of the separate solves"
    assert shared.c_rp_engaged_ratio < 1 and shared.dofs == ring.dofs
    assert set(shared.to_dict()) >= {"c_ru_N_m", "c_r_error_N_m", "c_rp_engaged_ratio",
                                     "seconds_total"}


@pytest.mark.slow
def test_tooth_compliance_follows_the_tooth():
    """Measured on another tooth, the tooth compliance equals tooth 0's on a ring held all
    round (rotational symmetry; mesh noise 5e-3 at scale 4); on the Raba ring, held on six
    arcs, the tooth between supports differs by per cents: where the crack is matters."""
    from hubvib.fem.tooth_fe import fe_tooth_compliance
    from hubvib.fem.tooth_stiffness import chebyshev_radii, contact_radii
    from hubvib.fem.mesh_cycle import GearPair
    from hubvib.meshing.levels import scaled_options

    planet = raba118.gear_body("planet")
    spread = {}
    for held in (Supports(count=0), RING.supports):
        ring = raba118.ring_gear(supports=held)
        radii = chebyshev_radii(*contact_radii(ring, [GearPair(planet, ring)]), 3)
        mesh = ring_mesh(ring, None, scaled_options(4.0))
        zero, five = (fe_tooth_compliance(ring, mesh, radii, tooth=k).compliance for k in (0, 5))
        spread[held.count] = np.abs(five / zero - 1).max()
    assert spread[0] < 5e-3, "symmetric ring: every tooth alike"
    assert spread[6] > 2e-2, "six support arcs: tooth 5 sits between them"
