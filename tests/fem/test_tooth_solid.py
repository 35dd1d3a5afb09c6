"""The ring tooth's compliance in the solid ring under a line load across the face
(``fem.tooth_solid``) and the c_rp ratio it gives (``fem.engaged_solid``), against the plane
tooth model (plane stress, as ``fem.tooth_fe`` solves it, and plane strain), the slice
method, and its own symmetry and mesh convergence, on the Raba 118/76 ring."""
from __future__ import annotations

import numpy as np
import pytest

from hubvib.reducer.stages import gear_body, material, ring_gear
from hubvib.design import preset_design
from hubvib.fem.elasticity import plane_model, rigid_body_modes, solve
from hubvib.fem.engaged_solid import solid_engaged_mesh
from hubvib.fem.mesh_cycle import GearPair
from hubvib.fem.ring_stiffness import ring_stiffness
from hubvib.fem.solid import solid_model
from hubvib.fem.tooth_fe import tooth_compliance, tooth_probe
from hubvib.fem.tooth_solid import (SolidToothLoad, element_finder, solid_probes,
                                    solid_tooth_compliance, solid_tooth_probe)
from hubvib.fem.tooth_stiffness import (chebyshev_radii, contact_radii, engaged_mesh, fe_curve)
from hubvib.meshing.crack import Crack, CrackFront
from hubvib.meshing.levels import SOLID_LEVELS, scaled_options, solid_options
from hubvib.meshing.ring_mesh import ring_mesh
from hubvib.meshing.ring_mesh_3d import ring_mesh_3d
from hubvib.studies.crack_growth import slice_ratio

DEPTH = 3e-3  # [m] the crack of the comparisons
PLANE = scaled_options(1.0)  # the plane study's default mesh


class _Model:
    """The part of a ``SolidModel`` that ``solid_probes`` reads."""

    def __init__(self, basis):
        self.basis = basis


def test_probes_reproduce_a_quadratic_field_exactly():
    """P2 tetrahedra interpolate a quadratic displacement exactly: the probe matrix gives it
    at arbitrary points to round-off (tolerance 1e-12 of the field's size)."""
    import skfem

    mesh = skfem.MeshTet2.from_mesh(skfem.MeshTet.init_tensor(*(np.linspace(0, 1, 4),) * 3))
    basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementTetP2()))

    def field(x):
        return np.array([x[0] ** 2 + x[1], x[1] * x[2] - 0.5, 2 * x[2] ** 2 - x[0] * x[1]])

    dofs = basis.project(field)
    rng = np.random.default_rng(1)
    points = rng.uniform(0.05, 0.95, (20, 3))
    model = _Model(basis)
    values = solid_probes(model, points, element_finder(model)) @ dofs
    expected = field(points.T).ravel()
    assert np.abs(values - expected).max() < 1e-12 * np.abs(expected).max(), \
        "P2 interpolation of a quadratic field is exact (tolerance 1e-12)"


def test_element_finder_finds_the_cell_of_every_point():
    """The per-point finder (``element_finder``) against an independent check: every point
    drawn inside a known cell of a P2 tetrahedral mesh is given that cell (interior points:
    the cell is unique), the same cells as scikit-fem's own ``MeshTet1.element_finder``
    (the finder it replaced), also for points on shared faces and corners where any cell
    holding the point is right (barycentric coordinates >= -3 eps, as scikit-fem tests);
    a point outside the mesh raises ValueError."""
    import skfem

    mesh = skfem.MeshTet2.from_mesh(skfem.MeshTet.init_tensor(*(np.linspace(0, 1, 7),) * 3))
    model = _Model(skfem.Basis(mesh, skfem.ElementVector(skfem.ElementTetP2())))
    corners = mesh.p[:, mesh.t[:4]]
    rng = np.random.default_rng(3)
    cells = rng.integers(0, mesh.t.shape[1], 500)
    weights = rng.dirichlet(np.ones(4), len(cells))
    points = np.einsum("dkn,nk->dn", corners[:, :, cells], weights)
    finder = element_finder(model)
    assert np.array_equal(finder(*points), cells), \
        "interior points: their own cell (exact, the cell is unique)"
    reference = skfem.MeshTet1(mesh.p, mesh.t[:4]).element_finder()
    assert np.array_equal(finder(*points), reference(*points)), \
        "same cells as scikit-fem's finder on interior points (exact)"
    # on faces, edges and nodes: any cell that holds the point
    shared = np.vstack([mesh.p.T[rng.integers(0, mesh.p.shape[1], 30)],
                        corners[:, :3, :30].mean(axis=1).T])
    found = finder(*shared.T)
    local = np.linalg.solve((corners[:, 1:, found] - corners[:, :1, found]).transpose(2, 0, 1),
                            (shared - corners[:, 0, found].T)[:, :, None])[:, :, 0]
    eps = np.finfo(float).eps
    assert np.all(local >= -eps) and np.all(1 - local.sum(axis=1) >= -3 * eps), \
        "points on shared faces, edges and nodes lie in the cell found (barycentric >= -3 eps)"
    with pytest.raises(ValueError, match="outside of the mesh"):
        finder(np.array([0.5, 1.5]), np.array([0.5, 0.5]), np.array([0.5, 0.5]))


def test_bad_loads_are_refused():
    ring = ring_gear(preset_design("raba118"))
    with pytest.raises(ValueError, match="samples = 1, allowed integers >= 2"):
        SolidToothLoad(0, (0.107,), samples=1)
    with pytest.raises(ValueError, match="radii must lie on the involute"):
        solid_tooth_probe(ring, None, SolidToothLoad(0, (0.2,)))
    z = ring.teeth
    with pytest.raises(ValueError, match=f"tooth = {z}, allowed integers 0..{z - 1}"):
        solid_tooth_probe(ring, None, SolidToothLoad(z, (0.107,)))


def test_solid_engaged_mesh_refuses_mismatched_values():
    design = preset_design("raba118")
    ring, planet = ring_gear(design), gear_body(design, "planet")
    with pytest.raises(ValueError, match="one value per radius"):
        solid_engaged_mesh(planet, ring, [0.106, 0.108], [1e-10], [1e-10, 1e-10], PLANE)
    with pytest.raises(ValueError, match="finite and > 0"):
        solid_engaged_mesh(planet, ring, [0.106], [-1e-10], [1e-10], PLANE)


# --- the real ring (slow) -------------------------------------------------------------------

class _Raba:
    design = preset_design("raba118")
    ring = ring_gear(design)
    planet = gear_body(design, "planet")
    steel = material(design)
    radii = chebyshev_radii(*contact_radii(ring, [GearPair(planet, ring)]))


_SOLVED = {}


def solid(level: int, depth: float = 0.0, half_length: float | None = None):
    """(tooth compliance, model, probe) of the solid ring on ``SOLID_LEVELS[level]`` with a
    crack of ``depth`` [m] on tooth 0, through the width or semi-elliptic centred of
    ``half_length`` [m]; one carrier position (the tooth columns do not depend on it)."""
    key = (level, depth, half_length)
    if key not in _SOLVED:
        crack = Crack(0, depth) if depth > 0 else None
        front = CrackFront() if half_length is None else CrackFront("semi_elliptic", 0.5,
                                                                    half_length)
        mesh = ring_mesh_3d(_Raba.ring, crack, front, solid_options(*SOLID_LEVELS[level]))
        result = ring_stiffness(_Raba.ring, mesh, _Raba.steel, _Raba.design.n_planets,
                                carrier_teeth=[0],
                                tooth=SolidToothLoad(0, tuple(_Raba.radii)))
        _SOLVED[key] = result.tooth
    return _SOLVED[key]


def plane(depth: float, kind: str) -> np.ndarray:
    """The plane tooth compliance [m/N] at the same radii, plane ``kind`` over the width."""
    crack = Crack(0, depth) if depth > 0 else None
    model = plane_model(ring_mesh(_Raba.ring, crack, PLANE), _Raba.steel,
                        _Raba.ring.gear.face_width, kind)
    probe = tooth_probe(_Raba.ring, model, _Raba.radii)
    return tooth_compliance(probe, solve(model, probe.loads, ["supports"]).u)


def engaged_3d(level: int, depth: float, half_length: float | None) -> float:
    cracked, intact = solid(level, depth, half_length), solid(level)
    return solid_engaged_mesh(_Raba.planet, _Raba.ring, _Raba.radii, cracked.compliance,
                              intact.compliance, PLANE, _Raba.steel).mean_ratio


@pytest.mark.slow
def test_intact_tooth_in_3d_against_the_plane_model():
    """The intact tooth under a line load across the face lies between plane strain and plane
    stress (the plane code's assumption: ``fem.tooth_fe`` solves plane stress) up to the solid
    mesh's own stiffness: P2 tetrahedra converge from the stiff side, the coarser level is
    stiffer than the finer one at every radius, and the default level is within 8 % below plane
    strain (measured 3-6 %) and below plane stress."""
    stress, strain = plane(0.0, "stress"), plane(0.0, "strain")
    coarse, fine = solid(1).compliance, solid(2).compliance
    print("intact: coarse/strain", coarse / strain, "fine/strain", fine / strain,
          "fine/stress", fine / stress)
    assert np.all(strain < stress), "plane strain is stiffer than plane stress"
    assert np.all(coarse < fine), "P2 solid levels converge from the stiff side"
    assert np.all(fine < stress), "3D below plane stress (Timoshenko & Goodier: a wide plate)"
    assert np.all(fine > 0.92 * strain), \
        f"3D within 8 % of plane strain (solid mesh error); ratios {fine / strain}"


@pytest.mark.slow
def test_through_width_crack_ratio_in_3d_against_the_plane_model():
    """A crack through the width: the 3D cracked/intact compliance ratio at every radius lies
    within 15 % of the crack's effect (ratio - 1) of the plane-stress and plane-strain ratios
    (which differ by 1 % of it). Measured on the default solid level: 7-12 % above them, as
    much as the solid mesh's intact tooth is too stiff (3-6 %, the test above), which scales
    the effect up; the engaged c_rp ratio, its level error, is checked below."""
    ratio = {kind: plane(DEPTH, kind) / plane(0.0, kind) for kind in ("stress", "strain")}
    low = np.minimum(ratio["stress"], ratio["strain"])
    high = np.maximum(ratio["stress"], ratio["strain"])
    three_d = solid(2, DEPTH).compliance / solid(2).compliance
    print("through: 3D", three_d, "stress", ratio["stress"], "strain", ratio["strain"])
    assert np.all(three_d > 1), "a crack softens the tooth"
    assert np.all(three_d >= low - 0.15 * (high - 1)) and np.all(
        three_d <= high + 0.15 * (high - 1)), (
        f"3D through-crack ratio {three_d} against plane stress {ratio['stress']} and plane "
        f"strain {ratio['strain']} (tolerance 15 % of the crack's effect)")


@pytest.mark.slow
def test_part_width_ratio_against_the_slice_ratio_and_the_through_crack():
    """A centred semi-elliptic 3 mm crack: the engaged c_rp ratio from the solid tooth is
    below 1, lower for the longer crack, and above the through-width crack's (it tends to it as
    the half-length grows to the face width). Against the slice method (Chen & Shao 2011):
    within the 3D ratio's own level error (fine against coarse solid level) of the slice ratio.
    Measured: 0.9792 (level 2), 0.9743 (level 1) against slices 0.9811 at 8 mm: the expected
    order (slices overstating) is not resolved at this depth by the solid mesh."""
    width = _Raba.ring.gear.face_width
    plane_ratio = engaged_mesh(_Raba.planet, _Raba.ring,
                               fe_curve(_Raba.ring, contact_radii(
                                   _Raba.ring, [GearPair(_Raba.planet, _Raba.ring)]),
                                   _Raba.steel, PLANE, Crack(0, DEPTH)), PLANE,
                               _Raba.steel).mean_ratio
    ratios = {half: engaged_3d(2, DEPTH, half) for half in (8e-3, 16e-3)}
    through = engaged_3d(2, DEPTH, None)
    print("engaged: plane", plane_ratio, "3D", ratios, "through 3D", through)
    assert through < ratios[16e-3] < ratios[8e-3] < 1, \
        f"longer cracks approach the through-width ratio {through}: {ratios}"
    level_error = abs(ratios[8e-3] - engaged_3d(1, DEPTH, 8e-3))
    sliced = slice_ratio(DEPTH, 8e-3, width, [0.0, DEPTH], [1.0, plane_ratio])
    assert abs(ratios[8e-3] - sliced) < level_error, (
        f"3D ratio {ratios[8e-3]} within its level error {level_error} of the slice ratio "
        f"{sliced}")


@pytest.mark.slow
def test_centred_crack_deflects_the_tooth_symmetrically():
    """The extra deflection of a centred 3 mm x 8 mm crack across the width (default solid
    level) is symmetric about mid-width: the means of the two halves agree within 10 % (the
    mesh is not symmetric: measured up to 9.5 %, on the coarsest level 10 %), and it is
    largest in the middle third."""
    cracked, intact = solid(2, DEPTH, 8e-3), solid(2)
    extra = cracked.profile - intact.profile
    half = extra.shape[1] // 2
    left, right = extra[:, :half].mean(axis=1), extra[:, half:][:, ::-1].mean(axis=1)
    print("symmetry", (left - right) / (left + right) * 2,
          [np.argmax(r) / (len(r) - 1) for r in extra])
    assert np.all(np.abs(left - right) < 0.1 * 0.5 * (left + right)), \
        "symmetric about mid-width within 10 %"
    for row in extra:
        peak = np.argmax(row) / (len(row) - 1)
        assert 1 / 3 < peak < 2 / 3, "largest at the deepest point, mid-width"


@pytest.mark.slow
def test_3d_ratio_converges_over_two_mesh_levels():
    """The engaged c_rp ratio of a 3 mm x 8 mm crack on the last two solid levels (the
    scene's error estimate): measured 0.9743 (level 1) and 0.9792 (level 2), a difference of
    24 % of the crack's effect; bound 30 %. The ratio rises with the finer mesh (its effect
    falls), as the intact tooth's compliance converges from the stiff side."""
    coarse, fine = engaged_3d(1, DEPTH, 8e-3), engaged_3d(2, DEPTH, 8e-3)
    print("convergence", coarse, fine)
    assert coarse < fine < 1, "the crack's effect falls with the finer solid level"
    assert abs(fine - coarse) < 0.3 * (1 - fine), \
        f"3D ratio {fine} (level 2) against {coarse} (level 1): within 30 % of the effect"


@pytest.mark.slow
def test_rigid_motion_reads_no_deflection():
    """Each of the six rigid motions of the whole ring (1 m translations, 1 rad rotations
    about the three axes: in each strip an in-plane rigid motion) moves the section and the
    root lands alike: the reading is 0 to round-off (1e-9 m against motions of ~0.1 m)."""
    mesh = ring_mesh_3d(_Raba.ring, None, CrackFront(), solid_options(*SOLID_LEVELS[0]))
    model = solid_model(mesh, _Raba.steel)
    probe = solid_tooth_probe(_Raba.ring, model, SolidToothLoad(0, tuple(_Raba.radii[:2])))
    for mode in rigid_body_modes(model.basis).T:
        read = solid_tooth_compliance(probe, np.column_stack([mode, mode]))
        assert np.abs(read.profile).max() < 1e-9, "a rigid motion reads no deflection"
