"""Stress intensity factors from the interaction integral against handbook solutions, and the
maximum-tangential-stress kink angle against its closed form (``fem.fracture``)."""
import math

import numpy as np
import pytest

from hubvib.fem.edge_crack import brown_srawley
from hubvib.fem.elasticity import plane_model, solve
from hubvib.fem.fracture import (FractureError, hoop_stress, interaction_integral, mts_angle,
                                 williams)
from hubvib.meshing.crack_plate import centre_crack_plate
from hubvib.meshing.strip import edge_crack_strip

#: Tada, Paris & Irwin, The Stress Analysis of Cracks Handbook (3rd ed.) 2.10 (Gross &
#: Brown-Srawley): single-edge crack in tension, within 0.5 % for a/W <= 0.6, H/W >= 1
TADA_TENSION = (1.12, -0.231, 10.55, -21.72, 30.39)


def tada_tension(x: float) -> float:
    return sum(c * x ** k for k, c in enumerate(TADA_TENSION))


def _end_tractions(model, shape):
    """Load vector of the traction ``shape(y)`` [Pa] along x on the right end, minus it on
    the left end."""
    import skfem

    out = 0
    for end, sign in (("right", 1.0), ("left", -1.0)):
        @skfem.LinearForm
        def traction(v, w, sign=sign):
            return sign * shape(w.x[1]) * v[0]
        out = out + traction.assemble(model.facet_basis([end]))
    return out


@pytest.fixture(scope="module", params=[0.2, 0.4, 0.55])
def edge_strip(request):
    """A single-edge-cracked strip, W = 1 m, half length 2 m (H/W = 2), coarse P2 mesh:
    its tension and pure-bending solutions."""
    width, ratio = 1.0, request.param
    depth = ratio * width
    mesh = edge_crack_strip(width, 2 * width, depth, width / 10, width / 200, 2)
    model = plane_model(mesh, thickness=1.0)
    tension = _end_tractions(model, lambda y: 1.0 + 0.0 * y)
    # unit outer-fibre bending stress 6 M / (t W^2) = 1 Pa, tension at the cracked edge
    bending = _end_tractions(model, lambda y: 2.0 * (width / 2 - y) / width)
    pins = np.concatenate([model.node_dofs(mesh.points_of["pin"], 0),
                           model.node_dofs(mesh.points_of["pin"], 1),
                           model.node_dofs(mesh.points_of["roller"], 1)])
    u = solve(model, np.column_stack([tension, bending]), [], fixed_dofs=pins,
              solver="superlu").u
    return ratio, depth, model, u


def test_edge_crack_tension_matches_tada(edge_strip):
    ratio, depth, model, u = edge_strip
    reference = tada_tension(ratio) * math.sqrt(math.pi * depth)
    for r_out in (0.1 * depth, 0.3 * depth):
        k = interaction_integral(model, u[:, 0], (0.0, depth), (0.0, 1.0), r_out)
        assert k.k_i == pytest.approx(reference, rel=0.02), (
            f"K_I of the edge crack in tension, a/W = {ratio}, r_out = {r_out:g} m vs Tada "
            "2.10 (Brown-Srawley), tolerance 2 %")
        assert abs(k.k_ii) < 0.005 * reference, (
            f"K_II of the symmetric edge crack in tension, a/W = {ratio}: 0 by symmetry "
            "(tolerance 0.5 % of K_I)")


def test_edge_crack_bending_matches_brown_srawley(edge_strip):
    ratio, depth, model, u = edge_strip
    reference = brown_srawley(ratio) * math.sqrt(math.pi * depth)
    for r_out in (0.1 * depth, 0.3 * depth):
        k = interaction_integral(model, u[:, 1], (0.0, depth), (0.0, 1.0), r_out)
        assert k.k_i == pytest.approx(reference, rel=0.02), (
            f"K_I of the edge crack in pure bending, a/W = {ratio}, r_out = {r_out:g} m vs "
            "Brown & Srawley (1966) / Tada 2.13, tolerance 2 %")
        assert abs(k.k_ii) < 0.005 * reference, (
            f"K_II of the edge crack in bending, a/W = {ratio}: 0 by symmetry (0.5 % of K_I)")


@pytest.mark.parametrize("degrees", [30.0, 45.0, 60.0])
def test_inclined_centre_crack_mixed_mode(degrees):
    """Inclined centre crack (2a, at beta to the plate's x axis) under remote tension
    sigma along y: K_I = sigma sqrt(pi a) cos^2 beta, K_II = sigma sqrt(pi a) sin beta
    cos beta (Tada 1.6 for an infinite plate; the plate here is 40 a square: the finite-
    width correction sqrt(sec(pi a / 2W)) = 1.0015)."""
    import skfem

    a, beta = 1.0, math.radians(degrees)
    mesh = centre_crack_plate(20 * a, 20 * a, a, beta, 4 * a, a / 100)
    model = plane_model(mesh)
    load = 0
    for end, sign in (("top", 1.0), ("bottom", -1.0)):
        @skfem.LinearForm
        def traction(v, w, sign=sign):
            return sign * v[1]
        load = load + traction.assemble(model.facet_basis([end]))
    pins = np.concatenate([model.node_dofs(mesh.points_of["corner_bl"], 0),
                           model.node_dofs(mesh.points_of["corner_bl"], 1),
                           model.node_dofs(mesh.points_of["corner_br"], 1)])
    u = solve(model, load, [], fixed_dofs=pins, solver="superlu").u
    scale = math.sqrt(math.pi * a)
    for tip, direction in (((a * math.cos(beta), a * math.sin(beta)),
                            (math.cos(beta), math.sin(beta))),
                           ((-a * math.cos(beta), -a * math.sin(beta)),
                            (-math.cos(beta), -math.sin(beta)))):
        k = interaction_integral(model, u, tip, direction, 0.2 * a)
        assert k.k_i == pytest.approx(scale * math.cos(beta) ** 2, rel=0.02), (
            f"K_I of the inclined centre crack, beta = {degrees} deg, tip {tip} vs Tada "
            "(sigma sqrt(pi a) cos^2 beta), tolerance 2 %")
        assert k.k_ii == pytest.approx(scale * math.sin(beta) * math.cos(beta), rel=0.02), (
            f"K_II of the inclined centre crack, beta = {degrees} deg, tip {tip} vs Tada "
            "(sigma sqrt(pi a) sin beta cos beta), tolerance 2 %")


@pytest.mark.parametrize("k_i, k_ii", [(1.0, 0.0), (1.0, 0.1), (1.0, 0.5), (1.0, -0.5),
                                       (0.3, 1.0), (0.0, 1.0), (0.0, -1.0), (2.0, 3.0)])
def test_mts_angle_maximises_the_hoop_stress(k_i, k_ii):
    """The kink angle is the closed form 2 atan[(K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II)]
    and the maximum of sigma_theta_theta of the Williams field, found independently by a
    grid search over (-pi, pi) refined by a golden-section search."""
    from scipy.optimize import minimize_scalar

    theta = mts_angle(k_i, k_ii)
    if k_ii == 0:
        closed = 0.0
    else:
        closed = 2 * math.atan((k_i - math.sqrt(k_i ** 2 + 8 * k_ii ** 2)) / (4 * k_ii))
    assert theta == pytest.approx(closed, abs=1e-12), (
        "mts_angle vs the closed form of Erdogan & Sih (1963), tolerance 1e-12 rad")
    grid = np.linspace(-math.pi + 1e-6, math.pi - 1e-6, 20001)
    start = grid[np.argmax(hoop_stress(grid, k_i, k_ii))]
    best = minimize_scalar(lambda t: -hoop_stress(t, k_i, k_ii),
                           bounds=(start - 1e-3, start + 1e-3), method="bounded",
                           options={"xatol": 1e-10}).x
    assert theta == pytest.approx(best, abs=1e-6), (
        "MTS angle vs the numerical maximum of the Williams hoop stress, tolerance 1e-6 rad")


def test_mts_angle_pure_shear_limit():
    assert math.degrees(mts_angle(0.0, 1.0)) == pytest.approx(-70.5288, abs=1e-3), (
        "pure mode II kink angle -arccos(1/3) = -70.53 deg (Erdogan & Sih 1963), 1e-3 deg")


def test_mts_angle_rejects_closed_and_unloaded_cracks():
    with pytest.raises(FractureError, match="press together"):
        mts_angle(-1.0, 0.2)
    with pytest.raises(FractureError, match="unloaded"):
        mts_angle(0.0, 0.0)


def test_williams_field_satisfies_hooke_and_traction_free_faces():
    """Identities of the auxiliary fields: sigma_12 = sigma_22 = 0 on the crack faces
    (theta = +-pi) in both modes, and the mode-I field's sigma_22 ahead of the tip is
    K / sqrt(2 pi r) (Williams 1957)."""
    mu, kappa = 80e9, 1.8
    for mode in (1, 2):
        for face in (math.pi - 1e-12, -math.pi + 1e-12):
            _, (s11, s22, s12) = williams(0.01, face, mode, mu, kappa)
            assert abs(s22) < 1e-9 and abs(s12) < 1e-9, (
                f"mode {mode}: the crack faces carry no traction (exact, tolerance 1e-9 Pa)")
    _, (s11, s22, s12) = williams(0.01, 0.0, 1, mu, kappa)
    assert s22 == pytest.approx(1 / math.sqrt(2 * math.pi * 0.01), rel=1e-12), (
        "sigma_22 ahead of a unit mode-I tip = 1/sqrt(2 pi r), exact")


def test_interaction_integral_rejects_bad_radii(edge_strip):
    ratio, depth, model, u = edge_strip
    with pytest.raises(FractureError, match="r_in"):
        interaction_integral(model, u[:, 0], (0.0, depth), (0.0, 1.0), 0.1, r_in=0.2)
    with pytest.raises(FractureError, match="non-zero"):
        interaction_integral(model, u[:, 0], (0.0, depth), (0.0, 0.0), 0.1)
