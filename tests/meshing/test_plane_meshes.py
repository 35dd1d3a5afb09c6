"""Ring-gear profile, mesh and crack checks (sources and tolerances in each assertion)."""
import math
from pathlib import Path

import numpy as np
import pytest

from hubvib.reducer import raba118

from hubvib.meshing import measure
from hubvib.meshing.crack import Crack
from hubvib.meshing.gear import GearGeometryError, SpurGear
from hubvib.meshing.profile import ShaperCutter, ToothProfile
from hubvib.meshing.ring_gear import RingGear, Supports

pytest.importorskip("gmsh")
from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh  # noqa: E402

RING = raba118.ring_gear()
COARSE = MeshOptions(size=4e-3, tooth_size=1e-3, tip_size=1e-4, load_size=2e-4)


@pytest.fixture(scope="module")
def intact():
    return ring_mesh(RING, None, COARSE)


@pytest.fixture(scope="module")
def cracked():
    return ring_mesh(RING, Crack(2, 6e-3, angle=math.radians(10)), COARSE)


@pytest.mark.parametrize("gear", [raba118.sun(), raba118.planet(), raba118.ring()],
                         ids=["sun", "planet", "ring"])
def test_fillet_meets_the_involute_tangentially(gear):
    """Generated fillet: its end (form point) lies on the involute to 1e-12 m and the two
    curves share the tangent there (cross product of unit tangents < 1e-8)."""
    prof = ToothProfile(gear)
    end = prof.fillet_points(1.0)[0]
    r = np.hypot(*end)
    assert np.linalg.norm(end - gear.flank([r])[0]) < 1e-12
    tangent = prof.fillet_tangents(1.0)[0]
    h = 1e-7
    flank = gear.flank([r + h])[0] - gear.flank([r - h])[0]
    t, f = tangent / np.linalg.norm(tangent), flank / np.linalg.norm(flank)
    assert abs(t[0] * f[1] - t[1] * f[0]) < 1e-8
    start = prof.fillet_points(0.0)[0]
    assert np.hypot(*start) == pytest.approx(prof.root_radius, abs=1e-12)


@pytest.mark.parametrize("gear", [raba118.planet(), raba118.ring()], ids=["planet", "ring"])
def test_fillet_points_are_on_the_tool_envelope(gear):
    """Every fillet point is exactly rho from the tip-round centre's path and the contact
    normal passes through the pitch point (envelope condition), to 1e-9 m."""
    prof = ToothProfile(gear)
    gen = prof._generator
    t = np.linspace(0, 1, 50)
    u = gen.u_root + (gen.u_form - gen.u_root) * t
    c, _, n, _ = gen.normal(u)
    contact = c + gen.rho * n
    d = contact - gen.pitch_point
    assert np.abs(d[:, 0] * n[:, 1] - d[:, 1] * n[:, 0]).max() < 1e-9
    assert np.abs(np.hypot(*(contact - c).T) - gen.rho).max() < 1e-12


def test_fillet_tangent_is_the_derivative():
    """Analytic d(point)/dt against a central difference (rtol 1e-6)."""
    for gear in (raba118.sun(), raba118.ring()):
        prof = ToothProfile(gear)
        for t in (0.1, 0.5, 0.9):
            h = 1e-6
            numeric = (prof.fillet_points(t + h)[0] - prof.fillet_points(t - h)[0]) / (2 * h)
            assert np.allclose(prof.fillet_tangents(t)[0], numeric, rtol=1e-6, atol=1e-12)


def test_internal_root_circle_is_cut_by_the_shaper():
    """ISO 21771: d_f2 = 2 a_0 + d_a0 with inv a_w0 = inv a + 2 tan a (x2 - x0)/(z2 - z0)."""
    from hubvib.meshing.gear import inverse_involute, involute
    g, cut = raba118.ring(), ShaperCutter()
    a = g.pressure_angle
    aw = inverse_involute(float(involute(a)) + 2 * math.tan(a) * g.profile_shift / (64 - 25))
    a0 = g.module * 39 / 2 * math.cos(a) / math.cos(aw)
    d_a0 = g.module * (25 + 2 * 1.25)
    assert ToothProfile(g, cutter=cut).root_radius == pytest.approx(a0 + d_a0 / 2, rel=1e-14)


def test_circular_fillet_touches_root_and_flank():
    gear = raba118.planet()
    prof = ToothProfile(gear, "circular")  # radius rho_fP* m
    pts = prof.fillet_points(np.linspace(0, 1, 20))
    centre, _, end, rho = prof._circle
    assert np.allclose(np.hypot(*(pts - centre).T), rho, atol=1e-15)
    assert np.hypot(*pts[0]) == pytest.approx(prof.root_radius, abs=1e-12)
    assert np.linalg.norm(end - gear.flank([np.hypot(*end)])[0]) < 1e-12
    with pytest.raises(GearGeometryError, match="fillet_radius"):
        ToothProfile(raba118.ring(), "circular", 3e-3)


def test_raba_ring_mass_and_exact_area():
    """The preset's outer diameter gives the paper's 6.8 kg (1e-12); the exact area equals a
    polygon of 2e5 profile points per flank (1e-9)."""
    assert RING.mass() == pytest.approx(6.8, rel=1e-12)
    prof, g = RING.profile, RING.gear
    f = prof.fillet_points(np.linspace(1, 0, 200001))
    inv = g.flank(np.linspace(prof.tip_radius, prof.form_radius, 200001))
    a = np.linspace(0, float(g.half_tooth_angle(prof.tip_radius)), 20001)
    b = np.linspace(prof.root_land_angle, prof.space_angle, 20001)
    poly = np.vstack([[0, 0], prof.tip_radius * np.column_stack([np.cos(a), np.sin(a)]), inv, f,
                      prof.root_radius * np.column_stack([np.cos(b), np.sin(b)]), [0, 0]])
    shoelace = np.sum(poly[:-1, 0] * poly[1:, 1] - poly[1:, 0] * poly[:-1, 1])
    assert shoelace == pytest.approx(RING.tooth_space_area(), rel=1e-9)


def test_load_force_has_the_base_radius_as_arm():
    """The mesh force acts along the line of action: its moment arm is r_b exactly."""
    for k in (0, 17):
        p, d = RING.load_point(k)
        assert abs(p[0] * d[1] - p[1] * d[0]) == pytest.approx(RING.gear.base_diameter / 2, rel=1e-13)
        assert np.hypot(*p) == pytest.approx(RING.load_radius, rel=1e-14)


def test_curved_p2_mesh_area_matches_exact(intact):
    """Curved P2 mesh area within 1e-5 of the exact geometry; mass likewise."""
    assert measure.area(intact) == pytest.approx(RING.area(), rel=1e-5)
    assert measure.mass(intact, RING.gear.face_width, RING.density) == pytest.approx(6.8, rel=1e-5)


def test_p1_area_is_the_polygon_area():
    """Straight P1 triangles cut the curved boundary by chords: area within 1e-4 at the
    default sizes, against the exact geometry."""
    m = ring_mesh(RING, None, MeshOptions(order=1))
    assert measure.area(m) == pytest.approx(RING.area(), rel=1e-4)


def _distance_to_polyline(points, line):
    """Distance of each point to a dense polyline (point-to-segment, chord error ~ h^2 k / 8)."""
    a, b = line[:-1], line[1:]
    out = []
    for p in points:
        i = int(np.argmin(np.hypot(*(line - p).T)))
        best = np.inf
        for j in (i - 1, i):
            if 0 <= j < len(a):
                ab = b[j] - a[j]
                s = np.clip((p - a[j]) @ ab / (ab @ ab), 0, 1)
                best = min(best, np.hypot(*(a[j] + s * ab - p)))
        out.append(best)
    return np.array(out)


def test_boundary_nodes_lie_on_the_exact_profile(intact):
    """Vertex and mid-edge nodes of tooth 5's flank lie on the exact involute or fillet
    within 2e-8 m (splines through 32/48 exact points per piece)."""
    prof, g = RING.profile, RING.gear
    nodes = np.unique(intact.boundaries["tooth5_flank_pos"])
    a = -RING.tooth_angle(5)
    xy = intact.points[nodes] @ np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]])
    involute = g.flank(np.linspace(prof.tip_radius, prof.form_radius, 20001))
    fillet = prof.fillet_points(np.linspace(0, 1, 20001))
    distance = np.minimum(_distance_to_polyline(xy, involute), _distance_to_polyline(xy, fillet))
    assert distance.max() < 2e-8


def test_named_groups(intact):
    names = set(intact.boundaries)
    for k in (0, 63):
        assert {f"tooth{k}_flank_pos", f"tooth{k}_flank_neg", f"tooth{k}_load"} <= names
    assert {f"support_{j}" for j in range(6)} | {"supports", "outer_free"} <= names
    outer = intact.points[np.unique(intact.boundaries["supports"])]
    assert np.allclose(np.hypot(*outer.T), RING.outer_radius, rtol=1e-12)
    angles = np.degrees(np.arctan2(outer[:, 1], outer[:, 0]))
    assert np.all(np.min(np.abs(((angles[:, None] - np.arange(0, 360, 60)[None]) + 180) % 360
                                - 180), axis=1) <= 10 + 1e-9)


def test_crack_faces_are_disconnected(cracked):
    """Crack plugin: every crack node is duplicated except the tip, which both faces share."""
    a = np.unique(cracked.boundaries["crack_a"])
    b = np.unique(cracked.boundaries["crack_b"])
    assert len(a) == len(b)
    assert list(np.intersect1d(a, b)) == list(cracked.points_of["crack_tip"])
    assert np.allclose(np.sort(cracked.points[a], axis=0), np.sort(cracked.points[b], axis=0),
                       atol=0)
    assert len(cracked.points_of["crack_mouth"]) == 2


def test_crack_tip_is_where_asked(cracked):
    crack = Crack(2, 6e-3, angle=math.radians(10))
    path = crack.path(RING)
    tip = cracked.points[cracked.points_of["crack_tip"][0]]
    assert np.linalg.norm(tip - path[-1]) < 1e-9
    assert np.linalg.norm(path[-1] - path[0]) == pytest.approx(6e-3, rel=1e-12)
    mouth = RING.profile.critical_point()
    turned = np.array([[math.cos(RING.tooth_angle(2)), -math.sin(RING.tooth_angle(2))],
                       [math.sin(RING.tooth_angle(2)), math.cos(RING.tooth_angle(2))]]) @ mouth
    assert np.linalg.norm(path[0] - turned) < 1e-15


def test_crack_adds_no_area(intact, cracked):
    """A zero-width slit: same area as the intact ring (P2 mesh, 1e-5); zero depth = intact."""
    assert measure.area(cracked) == pytest.approx(RING.area(), rel=1e-5)
    zero = ring_mesh(RING, Crack(2, 0.0), COARSE)
    assert len(zero.points) == len(intact.points)
    assert np.array_equal(zero.points, intact.points)


@pytest.mark.parametrize("crack", [
    Crack(7, 0.0, start="root"), Crack(11, 8e-3, start="rim"),
    Crack(4, 10e-3, angle=math.radians(15), kink_fraction=0.5, kink_angle=math.radians(-30)),
], ids=["through", "rim", "kinked"])
@pytest.mark.slow
def test_crack_variants_mesh(crack):
    if crack.depth == 0:
        crack = Crack(7, Crack(7, 1.0).through_depth(RING))
    m = ring_mesh(RING, crack, COARSE)
    assert measure.area(m) == pytest.approx(RING.area(), rel=1e-5)
    a, b = (np.unique(m.boundaries[f"crack_{s}"]) for s in "ab")
    shared = np.intersect1d(a, b)
    if crack.is_through(RING):
        assert len(shared) == 0  # the rim is split: no node joins the faces
    else:
        assert list(shared) == list(m.points_of["crack_tip"])
    assert m.info["min_quality"] > 0.1


@pytest.mark.slow
@pytest.mark.parametrize("crack", [None, Crack(0, 5e-3)], ids=["intact", "cracked"])
def test_mesh_quality_of_the_preset(crack):
    """gmsh minSICN above 0.5 with the default mesh options (tip refined to 10 um)."""
    m = ring_mesh(RING, crack, MeshOptions(tip_size=1e-5))
    assert m.info["min_quality"] > 0.5


def test_mesh_is_deterministic(intact):
    again = ring_mesh(RING, None, COARSE)
    assert np.array_equal(again.points, intact.points)
    assert np.array_equal(again.cells, intact.cells)


def test_skfem_sees_the_groups(cracked):
    skfem = pytest.importorskip("skfem")
    from hubvib.meshing.to_skfem import to_skfem
    fe, _ = to_skfem(cracked)
    assert isinstance(fe, skfem.MeshTri2)
    facets = fe.boundaries["crack_a"]
    assert len(facets) == len(cracked.boundaries["crack_a"])
    assert set(facets).isdisjoint(fe.boundaries["crack_b"])
    # crack faces are boundary facets of the skfem mesh (one element each side)
    boundary = set(fe.boundary_facets())
    assert set(facets) <= boundary


@pytest.mark.parametrize("kwargs, message", [
    (dict(tooth=64, depth=1e-3), "crack.tooth = 64"),
    (dict(tooth=0, depth=0.1), "deeper than the rim"),
    (dict(tooth=0, depth=-1e-3), "crack.depth"),
    (dict(tooth=0, depth=1e-3, angle=math.radians(70)), "-90..60"),
    (dict(tooth=0, depth=0.03, start="rim"), "runs out of the rim"),
])
def test_bad_crack(kwargs, message):
    with pytest.raises(GearGeometryError, match=message):
        Crack(**kwargs).path(RING)


def test_bad_ring_and_options():
    with pytest.raises(GearGeometryError, match="outer_diameter"):
        RingGear(raba118.ring(), 0.2)
    with pytest.raises(GearGeometryError, match="internal"):
        RingGear(SpurGear(30, 2e-3), 0.2)
    with pytest.raises(GearGeometryError, match="supports.width"):
        Supports(count=6, width=math.radians(70))
    with pytest.raises(GearGeometryError, match="mesh.order"):
        MeshOptions(order=3)
    with pytest.raises(GearGeometryError, match="cutter.teeth"):
        ToothProfile(raba118.ring(), cutter=ShaperCutter(teeth=60))


def test_cache_reuses_meshes(tmp_path):
    from hubvib.meshing.cache import cached
    calls = []

    def build():
        calls.append(1)
        return ring_mesh(RING, None, COARSE)

    first, hit1 = cached(build, RING, None, COARSE, folder=tmp_path)
    second, hit2 = cached(build, RING, None, COARSE, folder=tmp_path)
    assert (hit1, hit2, len(calls)) == (False, True, 1)
    assert np.array_equal(first.points, second.points)
    assert second.boundaries.keys() == first.boundaries.keys()


@pytest.mark.parametrize("name", ["sun", "planet"])
def test_external_gear_body_mesh(name):
    # exact area: the same closed forms as the ring, external sign of the involute
    # term, minus the bore; a 2e5-point polygon of the tooth checks the closed forms
    body = raba118.gear_body(name)
    mesh = ring_mesh(body)
    assert abs(measure.area(mesh) / body.area() - 1) < 1e-5
    assert mesh.info["min_quality"] > 0.5
    r = np.hypot(*mesh.points[np.unique(mesh.boundaries["supports"])].T)
    assert np.allclose(r, body.held_radius, rtol=1e-12)
    load = mesh.points[np.unique(mesh.boundaries["tooth0_load"])]
    assert np.abs(np.hypot(*load.T) - body.load_radius).max() <= MeshOptions().load_patch / 2 + 1e-12
    t = np.linspace(0, 1, 200001)
    prof, g = body.profile, body.gear
    flank = g.flank(np.linspace(prof.tip_radius, prof.form_radius, 200001))
    def arc(radius, a, b):
        angles = np.linspace(a, b, 20001)
        return radius * np.column_stack([np.cos(angles), np.sin(angles)])

    fillet = prof.fillet_points(t[::-1])
    half = np.vstack([arc(prof.tip_radius, 0.0, math.atan2(*flank[0][::-1])), flank, fillet,
                      arc(prof.root_radius, math.atan2(*fillet[-1][::-1]), prof.space_angle)])
    x, y = half.T
    polygon = 0.5 * abs(np.sum(x[:-1] * y[1:] - x[1:] * y[:-1]))  # fan from the centre
    assert 2 * polygon == pytest.approx(body.tooth_space_area(), rel=1e-9)


def test_external_gear_body_rejects_bad_input():
    with pytest.raises(GearGeometryError, match="bore_diameter"):
        from hubvib.meshing.gear_body import GearBody
        GearBody(raba118.planet(), 0.07)
    with pytest.raises(GearGeometryError, match="crack"):
        ring_mesh(raba118.gear_body("sun"), Crack(0, 1e-3))


def _ignored_signals() -> int:
    """The kernel's mask of ignored signals for this process (Linux /proc)."""
    line = next(l for l in Path("/proc/self/status").read_text().splitlines()
                if l.startswith("SigIgn:"))
    return int(line.split()[1], 16)


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs Linux /proc")
def test_gmsh_session_keeps_sigpipe_ignored():
    """gmsh.initialize resets SIGPIPE to its default (kill the process); Python ignores it so
    that a write to a closed pipe raises BrokenPipeError.  The session puts it back."""
    import signal

    from hubvib.meshing.session import gmsh_model

    bit = 1 << (signal.SIGPIPE - 1)
    assert _ignored_signals() & bit, "Python ignores SIGPIPE at start-up"
    with gmsh_model():
        assert _ignored_signals() & bit, "SIGPIPE no longer ignored inside a gmsh session"
    assert _ignored_signals() & bit, "SIGPIPE no longer ignored after a gmsh session"
