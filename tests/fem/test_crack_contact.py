"""Frictionless contact of crack faces: the LCP solver against enumeration, the pairs of a
cracked strip, and the strip in bending with its crack on the tension and on the
compression side against the handbook and the uncracked strip (``fem.crack_pairs``,
``fem.signorini``)."""
import itertools

import numpy as np
import pytest
import scipy.sparse as sp

pytest.importorskip("skfem")

from hubvib.fem.crack_pairs import CrackPairsError, pairs_of_model  # noqa: E402
from hubvib.fem.signorini import signorini  # noqa: E402


def _random_lcp(seed, n=8):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(n, n))
    C = A @ A.T + 0.1 * n * np.eye(n)  # SPD, not an M-matrix
    return C * 1e-9, rng.normal(size=n) * 1e-6


def _enumerated(C, q):
    """The LCP's solution by trying every pressed set (the solution is unique)."""
    n = q.size
    for mask in itertools.product([False, True], repeat=n):
        A = np.flatnonzero(mask)
        lam = np.zeros(n)
        if A.size:
            lam[A] = np.linalg.solve(C[np.ix_(A, A)], -q[A])
        w = q + C @ lam
        if lam.min() >= -1e-12 * np.abs(lam).max(initial=1) and np.delete(w, A).min(
                initial=0) >= -1e-12 * np.abs(q).max():
            return lam
    raise AssertionError("no pressed set solves the LCP")


@pytest.mark.parametrize("seed", range(6))
def test_signorini_equals_enumeration(seed):
    C, q = _random_lcp(seed)
    solution = signorini(C, q)
    expected = _enumerated(C, q)
    np.testing.assert_allclose(solution.force, expected, rtol=1e-9, atol=1e-12 * np.abs(
        expected).max(), err_msg="active-set LCP solution vs enumeration of the 2^8 pressed "
        "sets (unique for SPD C), rtol 1e-9")
    w = q + C @ solution.force
    scale = np.abs(q).max()
    assert w.min() >= -1e-12 * scale and solution.force.min() >= 0, (
        "Signorini: gap >= 0 and force >= 0 to round-off (1e-12 of the opening scale)")
    assert abs(solution.force @ w) <= 1e-12 * scale * np.abs(solution.force).sum(), (
        "complementarity force . gap = 0 to round-off")


@pytest.mark.parametrize("seed", range(3))
def test_fallback_gives_the_same_solution(seed):
    C, q = _random_lcp(seed)
    fallback = signorini(C, q, max_steps=0)
    assert fallback.method == "nnls"
    np.testing.assert_allclose(fallback.force, signorini(C, q).force, rtol=1e-7,
                               atol=1e-9 * np.abs(fallback.force).max(),
                               err_msg="Lawson-Hanson NNLS vs the active-set method: one "
                               "unique LCP solution, rtol 1e-7")


def test_signorini_refuses_a_shape_mismatch():
    with pytest.raises(ValueError, match="3 x 3"):
        signorini(np.eye(2), np.ones(3))


WIDTH, THICKNESS = 0.01, 0.002


def _strip(depth, tip_size=WIDTH / 100):
    from hubvib.fem.elasticity import plane_model
    from hubvib.meshing.strip import edge_crack_strip

    mesh = edge_crack_strip(WIDTH, 2 * WIDTH, depth, WIDTH / 10, tip_size, 2)
    return mesh, plane_model(mesh, thickness=THICKNESS, plane="stress")


def _bending(mesh, model, moment):
    """Free stiffness, the expand map and the end load of a pure bending moment."""
    import skfem

    stress = 12.0 / (THICKNESS * WIDTH ** 3)
    f = np.zeros(model.ndofs)
    for end, sign in (("right", 1.0), ("left", -1.0)):
        @skfem.LinearForm
        def traction(v, w, sign=sign):
            return sign * moment * THICKNESS * stress * (WIDTH / 2 - w.x[1]) * v[0]
        f += traction.assemble(model.facet_basis([end]))
    held = np.concatenate([model.node_dofs(mesh.points_of["pin"], 0),
                           model.node_dofs(mesh.points_of["pin"], 1),
                           model.node_dofs(mesh.points_of["roller"], 1)])
    free = np.setdiff1d(np.arange(model.ndofs), held)
    expand = sp.csr_matrix((np.ones(free.size), (free, np.arange(free.size))),
                           shape=(model.ndofs, free.size))
    K = (expand.T @ model.K @ expand).tocsc()
    return K, expand, expand.T @ f


def _contact_compliance(mesh, model, moment):
    """Rotation compliance f.u / M^2 of the strip with its crack faces in frictionless
    contact, and the contact solution."""
    from scipy.sparse.linalg import splu

    K, expand, f = _bending(mesh, model, moment)
    pairs = pairs_of_model(model, expand)
    lu = splu(K)
    Y = lu.solve(pairs.G_n.T.toarray())
    C = pairs.G_n @ Y
    g0 = pairs.G_n @ lu.solve(f)
    solution = signorini(0.5 * (C + C.T), g0)
    u = lu.solve(f + pairs.G_n.T @ solution.force)
    return float(f @ u) / moment ** 2, solution, pairs


def test_strip_pairs():
    depth = 0.3 * WIDTH
    mesh, model = _strip(depth)
    pairs = pairs_of_model(model)
    assert np.allclose(np.abs(pairs.normal[:, 0]), 1.0, atol=1e-12), (
        "the strip's crack runs along y at x = 0: its faces' normal is +-x exactly")
    edge = pairs.length.max() * 2
    assert pairs.length.sum() == pytest.approx(depth, abs=0.5 * edge), (
        "the pairs' path lengths sum to the crack length but the tip node's quarter edge")
    assert np.all(pairs.points[:, 0] == pytest.approx(0.0, abs=1e-12)) and pairs.points[
        :, 1].min() == pytest.approx(0.0, abs=1e-12), "every pair on the crack, one at the mouth"
    u = np.zeros(model.ndofs)
    u[pairs.dofs_b[:, 0]] = 1e-6 * np.sign(pairs.normal[:, 0])  # face b moved across
    np.testing.assert_allclose(pairs.G_n @ u, 1e-6, rtol=1e-12,
                               err_msg="face b moved 1 um along the normal opens every pair "
                               "by 1 um")
    np.testing.assert_allclose(pairs.G_t @ u, 0.0, atol=1e-18,
                               err_msg="a normal motion slips no pair")


def test_intact_strip_has_no_pairs():
    _, model = _strip(0.0)
    with pytest.raises(CrackPairsError, match="no crack faces"):
        pairs_of_model(model)


def test_strip_bending_open_and_closed():
    from hubvib.fem.edge_crack import handbook_added_compliance

    ratio = 0.3
    mesh0, model0 = _strip(0.0)
    K0, _, f0 = _bending(mesh0, model0, 1.0)
    from scipy.sparse.linalg import spsolve

    c0 = float(f0 @ spsolve(K0, f0))
    mesh, model = _strip(ratio * WIDTH)
    tension, open_, _ = _contact_compliance(mesh, model, 1.0)
    assert not open_.pressed.any(), "the crack on the tension side stays open"
    assert tension - c0 == pytest.approx(handbook_added_compliance(ratio * WIDTH, WIDTH,
                                                                   THICKNESS), rel=0.01), (
        "open crack in bending: added rotation compliance vs Tada/Brown-Srawley handbook, "
        "1 % (the tolerance of tests/fem/test_tooth_stiffness.py)")
    compression, closed, pairs = _contact_compliance(mesh, model, -1.0)
    assert closed.pressed.mean() > 0.9, "the crack on the compression side presses shut"
    added = tension - c0
    assert abs(compression - c0) < 1e-8 * added, (
        f"closed crack in bending: compliance {compression:.6g} vs the uncracked strip "
        f"{c0:.6g} within 1e-8 of what the open crack adds ({added:.3g}): P2 holds pure "
        "bending exactly on both meshes, so the mesh error is round-off")
