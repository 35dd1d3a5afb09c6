"""Work-conjugate ring stiffnesses: c_ru and c_r from the work of the
loads, and the exact split of c_ru into the rim and the loaded teeth."""
import csv
import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("gmsh")

from hubvib.reducer import raba118  # noqa: E402
from hubvib.fem.elasticity import rigid_body_modes, solve  # noqa: E402
from hubvib.fem.ring_stiffness import (default_carrier_teeth, ring_loads, ring_model,  # noqa: E402
                                       ring_response, ring_stiffness, root_lands)
from hubvib.fem.ring_work import land_rigid_motions, ring_work  # noqa: E402
from hubvib.meshing.ring_mesh import ring_mesh  # noqa: E402
from hubvib.validation.convergence import NESTED_BASE  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def raba_coarse():
    """The real Raba ring on the coarsest nested level (curved P2, 2.0e4 DOFs)."""
    ring = raba118.ring_gear()
    mesh = ring_mesh(ring, None, NESTED_BASE)
    model = ring_model(ring, mesh)
    loads = ring_loads(model, ring, default_carrier_teeth(ring, 3), 3)
    u = solve(model, loads.loads, ["supports"]).u
    lands = root_lands(model, range(ring.teeth))
    return ring, mesh, model, loads, u, ring_work(model, ring, loads, u, loads.forces, lands)


def _strain_energy(model, u: np.ndarray) -> float:
    """1/2 of the integral of sigma : epsilon [J], by scikit-fem's own elasticity form (not
    the block assembly the solve used), plane stress over the face width."""
    import skfem

    lam, mu = model.material.lame("stress")
    field = model.basis.interpolate(u)

    @skfem.Functional
    def density(w):
        eps = 0.5 * (w["u"].grad + np.transpose(w["u"].grad, (1, 0, 2, 3)))
        trace = eps[0, 0] + eps[1, 1]
        return 0.5 * (lam * trace ** 2 + 2 * mu * (eps ** 2).sum(axis=(0, 1)))

    return model.thickness * density.assemble(model.basis, u=field)


def test_work_equals_twice_the_strain_energy(raba_coarse):
    """Clapeyron: c_ru_work = T^2 / (2 U) / r_b^2 with U the strain energy integrated over
    the elements by scikit-fem (independent of the load-vector product and of the block
    assembly), to 1e-8."""
    ring, _, model, loads, u, work = raba_coarse
    rb = ring.gear.base_diameter / 2
    for column, teeth in enumerate(loads.loaded[:3]):
        torque = len(teeth) * rb
        energy = _strain_energy(model, u[:, column])
        assert work.c_ru_positions[column] == pytest.approx(
            torque ** 2 / (2 * energy) / rb ** 2, rel=1e-8), "Clapeyron's theorem, 1e-8"
    energies = [_strain_energy(model, u[:, -2]), _strain_energy(model, u[:, -1])]
    assert work.c_r == pytest.approx(np.mean([1 / (2 * e) for e in energies]), rel=1e-8), \
        "Clapeyron's theorem for c_r (1 N), 1e-8"


def test_rim_and_tooth_add_up_in_series_to_the_work_conjugate_c_ru(raba_coarse):
    """1 / c_ru_work = 1 / c_ru_rim + 1 / c_ru_tooth at every carrier position of the real
    Raba ring to round-off (1e-12): the lumped model's series of ring body and tooth pair
    adds up to what the FE sees; each part is stiffer than the whole."""
    work = raba_coarse[-1]
    series = 1 / (1 / work.c_ru_rim_positions + 1 / work.c_ru_tooth_positions)
    np.testing.assert_allclose(work.c_ru_positions, series, rtol=1e-12,
                               err_msg="series identity of rim and tooth, 1e-12")
    assert np.all(work.c_ru_rim_positions > work.c_ru_positions)
    assert np.all(work.c_ru_tooth_positions > work.c_ru_positions)


def test_land_rigid_motion_reproduces_a_rigid_displacement(raba_coarse):
    """The rigid motion fitted on the root lands of a rigid displacement is that motion
    (exact: the rim part of the work then is all the work), to 1e-9."""
    ring, _, model, _, _, _ = raba_coarse
    modes = rigid_body_modes(model.basis)
    motion = modes @ np.array([1e-6, -2e-6, 3e-5])
    lands = root_lands(model, range(ring.teeth))
    fitted = land_rigid_motions(model, lands, [0, 5], motion[:, None])[:, :, 0]
    np.testing.assert_allclose(fitted, [[1e-6, -2e-6, 3e-5]] * 2, rtol=1e-9, atol=1e-15,
                               err_msg="rigid motion reproduced, 1e-9")


def test_ring_stiffness_carries_the_work_conjugate_values(raba_coarse):
    """``ring_stiffness`` gives the same work-conjugate values as the pieces (1e-10), and
    its root-land c_ru (a secondary output now) is the reading on the same
    solution."""
    ring, mesh, _, _, _, work = raba_coarse
    result = ring_stiffness(ring, mesh)
    np.testing.assert_allclose(result.work.c_ru_positions, work.c_ru_positions, rtol=1e-10)
    assert result.work.c_r == pytest.approx(work.c_r, rel=1e-10)
    assert result.work.c_r_rim == pytest.approx(work.c_r_rim, rel=1e-10)
    assert result.c_ru > result.work.c_ru_rim > result.work.c_ru


def test_c_r_rim_is_the_work_on_the_land_rigid_motions(raba_coarse):
    """c_r_rim (the lumped model's c_r now) recomputed another way: each tooth's
    share of the translation load as a load vector (``ToothForces.loads``) times the rigid
    displacement field of its root lands (``rigid_body_modes``), to 1e-10; it is stiffer
    than the whole c_r_work (the teeth left out), and within 2 % of the root-land c_r, an
    independent reading of the rim's translation (1.1 % apart on the fine Raba mesh,
    measured)."""
    ring, _, model, loads, u, work = raba_coarse
    z = ring.teeth
    positions = len(loads.loaded)
    modes = rigid_body_modes(model.basis)
    lands = root_lands(model, range(z))
    rigid = land_rigid_motions(model, lands, list(range(z)), u[:, positions:positions + 2])
    rim = []
    for axis in (0, 1):
        forces = np.zeros((z, 2, z))
        forces[np.arange(z), axis, np.arange(z)] = 1.0 / z  # tooth k's share in column k
        per_tooth = loads.forces.loads(forces)  # (ndofs, z)
        rim.append(sum(per_tooth[:, k] @ (modes @ rigid[k, :, axis]) for k in range(z)))
    assert work.c_r_rim == pytest.approx(np.mean([1 / w for w in rim]), rel=1e-10), \
        "rim work of the translation loads by load vectors, 1e-10"
    assert work.c_r_rim > work.c_r, "the rim part is stiffer than the whole"
    c_r_land = ring_response(model, ring, loads, u)[1]
    assert work.c_r_rim == pytest.approx(c_r_land, rel=0.02), "root-land c_r, 2 %"


@pytest.mark.slow
def test_root_land_reading_is_unchanged():
    """The root-land c_ru (a secondary output now) equals the committed convergence
    table at scale 4 (docs/data/convergence/convergence_c_ru.csv) to 1e-9."""
    from hubvib.validation.convergence import _ring_level

    with open(ROOT / "docs/data/convergence/convergence_c_ru.csv", newline="") as handle:
        rows = {float(r["scale"]): float(r["value"]) for r in csv.DictReader(handle)}
    value = _ring_level(4.0, "c_ru", raba118.ring_gear())["value"]
    assert math.isclose(value, rows[4.0], rel_tol=1e-9), \
        f"root-land c_ru {value} vs committed {rows[4.0]} (convergence_c_ru.csv), 1e-9"
