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
from hubvib.meshing import raba118  # noqa: E402
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
    curved P2 within 1e-6 at under 1e4 DOFs (issue 4)."""
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
