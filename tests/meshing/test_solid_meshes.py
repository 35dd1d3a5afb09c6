"""Solid ring meshes: extrusion, through-width and semi-elliptic cracks, skfem hand-off."""
import math

import numpy as np
import pytest

from hubvib.meshing import measure
from hubvib.meshing.crack import Crack, CrackFront
from hubvib.meshing.gear import GearGeometryError, SpurGear
from hubvib.meshing.ring_gear import RingGear, Supports

pytest.importorskip("gmsh")
from hubvib.meshing.ring_mesh import MeshOptions  # noqa: E402
from hubvib.meshing.ring_mesh_3d import ring_mesh_3d  # noqa: E402

# A small ring (40 teeth, 8 mm wide) keeps the solid meshes to a few seconds.
GEAR = SpurGear(40, 3.25e-3, math.radians(20), 0.3, face_width=8e-3, internal=True)
RING = RingGear(GEAR, GEAR.root_diameter + 2 * 12e-3, Supports(count=4, width=math.radians(30)))
COARSE = MeshOptions(size=8e-3, tooth_size=2.5e-3, tip_size=0.6e-3, load_size=1.2e-3,
                     load_patch=2e-3)
SEMI = CrackFront("semi_elliptic", centre=0.45, half_length=2.5e-3)


@pytest.fixture(scope="module")
def intact():
    return ring_mesh_3d(RING, None, options=COARSE)


@pytest.fixture(scope="module")
def through():
    return ring_mesh_3d(RING, Crack(3, 5e-3), options=COARSE)


@pytest.fixture(scope="module")
def semi():
    return ring_mesh_3d(RING, Crack(3, 4e-3), SEMI, options=COARSE)


def _face_nodes(mesh, name):
    return set(np.unique(mesh.boundaries[name]).tolist())


@pytest.mark.slow
def test_solid_volume_matches_exact(intact):
    # exact: plane area (closed forms + quadrature, test_meshing) x face width; P2 to 1e-5
    assert intact.cell_type == "tetra10"
    assert abs(measure.volume(intact) / intact.info["exact_volume"] - 1) < 1e-5
    assert intact.info["min_quality"] > 0  # every curved tetrahedron valid


@pytest.mark.slow
def test_solid_groups_are_swept_curves(intact):
    b = GEAR.face_width
    for k in (0, RING.teeth - 1):
        for side in ("flank_pos", "flank_neg", "root", "load"):
            assert len(intact.boundaries[f"tooth{k}_{side}"])
    z = intact.points[:, 2]
    assert np.allclose(z[np.unique(intact.boundaries["face_0"])], 0.0, atol=1e-12)
    assert np.allclose(z[np.unique(intact.boundaries["face_1"])], b, atol=1e-12)
    r = np.hypot(*intact.points[np.unique(intact.boundaries["supports"])][:, :2].T)
    assert np.allclose(r, RING.outer_radius, rtol=1e-9)
    # the load patch is on the involute around the load radius, over the whole width
    load = intact.points[np.unique(intact.boundaries["tooth0_load"])]
    assert np.ptp(load[:, 2]) == pytest.approx(b)
    assert np.abs(np.hypot(*load[:, :2].T) - RING.load_radius).max() <= 1e-3 + 1e-12


@pytest.mark.slow
def test_through_width_crack_is_open_except_its_front(through):
    a, b = _face_nodes(through, "crack_a"), _face_nodes(through, "crack_b")
    front = set(through.points_of["crack_front"].tolist())
    assert len(through.boundaries["crack_a"]) == len(through.boundaries["crack_b"])
    assert a & b == front
    tip = np.array(through.info["crack_path"][-1])
    xy = through.points[through.points_of["crack_front"], :2]
    assert np.abs(xy - tip).max() < 1e-9  # the front is the tip line, to 1e-9 m
    assert np.ptp(through.points[through.points_of["crack_front"], 2]) == pytest.approx(
        GEAR.face_width)
    mouth = through.points_of["crack_mouth"]
    assert len(mouth) == 2 * len(np.unique(np.round(through.points[mouth], 12), axis=0))


@pytest.mark.slow
def test_semi_elliptic_front_is_the_ellipse(semi):
    mouth, tip = (np.array(p) for p in semi.info["crack_path"])
    direction = (tip - mouth) / np.hypot(*(tip - mouth))
    x = semi.points[semi.points_of["crack_front"]]
    s = (x[:, :2] - mouth) @ direction
    z_c = SEMI.centre * GEAR.face_width
    # nodes (corner and mid-edge) on s^2/a^2 + (z - z_c)^2/c^2 = 1 to 1e-9 m
    radius = np.hypot(s / 4e-3, (x[:, 2] - z_c) / SEMI.half_length)
    assert np.abs(radius - 1).max() * SEMI.half_length < 1e-9
    assert s.max() == pytest.approx(4e-3, abs=1e-9)
    a, b = _face_nodes(semi, "crack_a"), _face_nodes(semi, "crack_b")
    assert a & b == set(semi.points_of["crack_front"].tolist())
    assert semi.info["min_quality"] > 0


@pytest.mark.slow
def test_crack_adds_no_volume(intact, through, semi):
    exact = intact.info["exact_volume"]
    for mesh in (through, semi):
        assert abs(measure.volume(mesh) / exact - 1) < 1e-5


@pytest.mark.slow
def test_zero_depth_crack_gives_the_intact_mesh(intact):
    zero = ring_mesh_3d(RING, Crack(3, 0.0), SEMI, options=COARSE)
    assert zero.info["nodes"] == intact.info["nodes"]
    assert np.array_equal(zero.points, intact.points)


@pytest.mark.slow
def test_skfem_sees_solid_groups_and_volume(semi):
    skfem = pytest.importorskip("skfem")
    from hubvib.meshing.to_skfem import to_skfem

    fe, _ = to_skfem(semi)
    basis = skfem.Basis(fe, fe.elem())
    volume = skfem.Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(basis)
    # an independent integral (skfem's isoparametric quadrature) of the same mesh
    assert volume == pytest.approx(measure.volume(semi), rel=1e-10)
    assert len(fe.boundaries["crack_a"]) == len(semi.boundaries["crack_a"])
    assert set(fe.boundaries) >= {"face_0", "face_1", "supports", "crack_b", "tooth3_load"}


@pytest.mark.parametrize("crack, front, message", [
    (Crack(3, 4e-3), CrackFront("semi_elliptic", 0.5, 3.9e-3), "front_half_length"),
    (Crack(3, 30e-3), CrackFront("semi_elliptic", 0.5, 2e-3), "crack.depth"),
    (Crack(3, 4e-3, kink_fraction=0.5, kink_angle=0.3), CrackFront("semi_elliptic", 0.5, 2e-3),
     "kink_fraction"),
])
def test_bad_part_width_crack(crack, front, message):
    with pytest.raises(GearGeometryError, match=message):
        ring_mesh_3d(RING, crack, front, COARSE)


@pytest.mark.parametrize("kwargs, message", [
    ({"shape": "corner"}, "crack.front"), ({"centre": 1.0}, "front_centre"),
    ({"half_length": 0.0}, "front_half_length"),
])
def test_bad_front(kwargs, message):
    with pytest.raises(GearGeometryError, match=message):
        CrackFront(**kwargs)


@pytest.mark.slow
def test_vtu_has_vtk_tetra10_order(semi, tmp_path):
    meshio = pytest.importorskip("meshio")
    from hubvib.meshing.export import write_png, write_vtu

    back = meshio.read(write_vtu(semi, tmp_path / "semi.vtu"))
    cells = back.cells_dict["tetra10"]
    x = back.points[cells]
    # VTK: node 8 on edge 1-3, node 9 on edge 2-3 (gmsh has them the other way round)
    on_13 = np.linalg.norm(x[:, 8] - (x[:, 1] + x[:, 3]) / 2, axis=1)
    on_23 = np.linalg.norm(x[:, 8] - (x[:, 2] + x[:, 3]) / 2, axis=1)
    assert np.all(on_13 < on_23)
    assert write_png(semi, tmp_path / "semi.png").stat().st_size > 10_000
