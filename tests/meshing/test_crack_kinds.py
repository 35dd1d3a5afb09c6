"""Crack start kinds and front shapes, root cracks turned -90..+60 deg
and the ``[crack] path`` key: geometry against independent
computations, and every refusal naming its key and range.  Meshing at large angles and
the predicted path's FE cases are in tests/studies/test_crack_path_sweep.py (slow)."""
import math

import numpy as np
import pytest

from hubvib.reducer.stages import ring_gear
from hubvib.design.presets import raba118
from hubvib.foundation.errors import SceneError
from hubvib.meshing.crack import FRONT_SHAPES, STARTS, Crack, CrackFront
from hubvib.meshing.crack_kinds import (FRONTS, START_KINDS, TOOTH_GAP, RimStart, RootStart,
                                        SemiEllipticFront, ThroughFront, front_shape,
                                        start_kind)
from hubvib.meshing.gear import GearGeometryError
from hubvib.meshing.ring_outline import boundary_segments, distance_to_segments
from hubvib.cases.predicted_path import (BASE_STEP, PathDepthError, arc_lengths,
                                           refined_step, truncated)
from hubvib.studies.scene import parse_scene

RABA = raba118()


@pytest.fixture(scope="module")
def ring():
    return ring_gear(RABA)


def test_registry_maps_the_file_strings_to_classes():
    """Scene/JSON strings stay as they were; each maps to its class at the edge."""
    assert STARTS == ("root", "rim") and FRONT_SHAPES == ("through", "semi_elliptic")
    assert isinstance(start_kind("root"), RootStart) and isinstance(start_kind("rim"), RimStart)
    assert isinstance(front_shape("through"), ThroughFront)
    assert isinstance(front_shape("semi_elliptic"), SemiEllipticFront)
    assert Crack(0, 1e-3).kind is START_KINDS["root"]
    assert CrackFront("semi_elliptic").kind is FRONTS["semi_elliptic"]
    with pytest.raises(GearGeometryError, match=r"crack.start = 'web', allowed: root, rim"):
        Crack(0, 1e-3, start="web")
    with pytest.raises(GearGeometryError, match=r"crack.front = 'oval', allowed: through, "):
        CrackFront("oval")


def test_root_and_rim_profiles_against_hand_geometry(ring):
    """A straight root crack is mouth + depth x the radial turned by the angle; a rim crack
    starts on the outer circle at the critical point's polar angle and runs inwards (the
    same numbers as before the classes: exact to 1e-15 m)."""
    mouth = ring.profile.critical_point()
    radial = mouth / np.hypot(*mouth)
    a = math.radians(-30)
    turned = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]) @ radial
    path = Crack(0, 3e-3, a).path(ring)
    np.testing.assert_allclose(path, [mouth, mouth + 3e-3 * turned], atol=1e-15,
                               err_msg="root crack = mouth + depth x turned radial")
    rim = Crack(0, 3e-3, start="rim").path(ring)
    np.testing.assert_allclose(rim[0], ring.outer_radius * radial, atol=1e-15)
    np.testing.assert_allclose(rim[1], rim[0] - 3e-3 * radial, atol=1e-15,
                               err_msg="rim crack runs radially inwards")


def test_plus_sixty_is_the_fillet_tangent(ring):
    """The root crack's +60 deg limit is the ISO 6336-3 fillet tangent at the mouth, 60 deg
    to the tooth axis of an internal gear (measured from the fillet's own derivative,
    1e-6 rad); beyond it the crack points into the tooth space.  The crack's angle is
    measured from the radial through the mouth, which is turned from the tooth axis by the
    mouth's polar angle (2.5 deg on Raba): at +60 the first few micrometres run along the
    fillet's chord, below every element size, and from 0.1 mm on the crack is in the
    body (point-in-polygon against the toothed outline)."""
    from matplotlib.path import Path

    from hubvib.meshing.ring_outline import tooth_outline

    prof = ring.profile
    tangent = prof.fillet_tangents(np.array([prof.critical_parameter()]))[0]
    axis_angle = math.atan2(abs(tangent[1]), abs(tangent[0]))
    assert axis_angle == pytest.approx(math.radians(60), abs=1e-6), "ISO 6336-3 tangent"
    assert START_KINDS["root"].angle_range[1] == pytest.approx(axis_angle, abs=1e-6)
    space = Path(np.vstack([tooth_outline(ring, 0), [0.0, 0.0]]))
    crack = Crack(0, 1e-3, math.radians(60))
    for s in (1e-4, 3e-4, 1e-3):
        assert not space.contains_point(crack.polyline(crack.mouth(ring), s)[-1]), s
    for degrees in (61, 75, 90):
        with pytest.raises(GearGeometryError, match=r"allowed -90..60 deg for a root crack"):
            Crack(0, 1e-3, math.radians(degrees))
    with pytest.raises(GearGeometryError, match=r"allowed -60..60 deg for a rim crack"):
        Crack(0, 1e-3, math.radians(-75), start="rim")


def test_minus_ninety_stops_before_the_opposite_fillet(ring):
    """At -90 deg the root crack runs along the root circle under its own tooth and passes
    the tooth's -psi fillet; it may go as deep as keeps TOOTH_GAP (0.5 mm) to it.  Checked
    with the gap computed independently (distance to every toothed segment around the
    tooth, ``ring_outline``): >= 0.5 mm up to the limit, < 0.5 mm 0.1 mm beyond; and the
    refusal names the key and the allowed range."""
    crack = Crack(0, 1e-3, -math.pi / 2)
    reach = crack.kind.tooth_reach(crack, ring)
    assert 5e-3 < reach < crack.through_depth(ring), f"reach {reach} m"
    segments = boundary_segments(ring, 0)
    mouth = crack.mouth(ring)
    for s in np.linspace(2e-3, reach, 20):
        point = crack.polyline(mouth, s)[-1]
        assert distance_to_segments(point, segments) >= TOOTH_GAP - 1e-12, f"s = {s} m"
    beyond = crack.polyline(mouth, reach + 0.1e-3)[-1]
    assert distance_to_segments(beyond, segments) < TOOTH_GAP
    Crack(0, reach, -math.pi / 2).path(ring)
    with pytest.raises(GearGeometryError, match=r"crack.depth = .* at crack.angle = -90 deg "
                       r"comes within 0.5 mm of the tooth surface .*allowed 0\.\.0\.00"):
        Crack(0, reach + 0.1e-3, -math.pi / 2).path(ring)


def _scene(crack_lines: str):
    return parse_scene(f"[reducer]\npreset = \"raba118\"\n[crack]\n{crack_lines}\n", "t")


def test_path_key_values():
    """``path`` = "radial" (today's sweep, angle 0), a number (= angle_deg) or "predicted";
    without it the sweep is exactly today's."""
    base = _scene("depths = [0.0, 0.003]").crack
    assert (base.path, base.angle) == ("straight", 0.0)
    assert _scene("depths = [0.0, 0.003]\npath = \"radial\"").crack == base
    turned = _scene("depths = [0.0, 0.003]\npath = -75").crack
    assert (turned.path, turned.angle) == ("straight", math.radians(-75))
    assert turned == _scene("depths = [0.0, 0.003]\nangle_deg = -75").crack


@pytest.mark.slow
def test_predicted_path_key(shared_cache):
    """``path = "predicted"``: parsing checks every depth against the grown LEFM path (on a
    cold cache the growth's 23 FE solutions, minutes: slow; the run's shared cache holds the
    same path when test_every_scene_runs[raba118_crack_path] grew it first, or the reverse)."""
    predicted = _scene("depths = [0.0, 0.003]\npath = \"predicted\"\nangle_deg = 0.0").crack
    assert predicted.path == "predicted" and predicted.angle == 0.0


@pytest.mark.parametrize("lines, message", [
    ("path = \"curvy\"", r"path = 'curvy'; allowed: \"predicted\", \"radial\" or an angle "
                         r"-90..60 \[deg\]"),
    ("path = 75", r"path = 75; allowed: .* -90..60"),
    ("path = true", r"path = True; allowed"),
    ("path = 30\nangle_deg = 20", r"angle_deg = 20 and path = 30 disagree"),
    ("path = \"predicted\"\nangle_deg = 10", r"angle_deg = 10 and path = 'predicted' disagree"),
    ("path = \"predicted\"\nthrough_rim = true", r"through_rim = false \(got true\)"),
    ("path = \"predicted\"\nstart = \"rim\"", r"allowed start = \"root\" \(got 'rim'\)"),
    ("angle_deg = -95", r"angle_deg = -95; allowed -90..60 for start = 'root'"),
    ("start = \"rim\"\nangle_deg = -75", r"angle_deg = -75; allowed -60..60 for start = 'rim'"),
    ("depths = [0.0, 0.012]\nangle_deg = -90", r"depths\[1\]: .*comes within 0.5 mm of the "
                                               r"tooth surface"),
])
def test_path_key_refusals(lines, message):
    text = lines if "depths" in lines else "depths = [0.0, 0.003]\n" + lines
    with pytest.raises(SceneError, match=message):
        _scene(text)


def test_truncated_polyline():
    """The crack at depth d is the polyline up to arc length d: a vertex is kept exactly,
    a depth inside a segment ends on it at length d (1e-12 m)."""
    points = np.array([[0.0, 0.0], [1e-3, 0.0], [1e-3, 2e-3], [0.0, 2e-3]])
    at_vertex = truncated(points, 3e-3, 4)
    assert at_vertex.tooth == 4 and np.array_equal(at_vertex.array, points[:3])
    inside = truncated(points, 3.25e-3, 0)
    assert inside.depth == pytest.approx(3.25e-3, abs=1e-12)
    np.testing.assert_allclose(inside.array, [*points[:3], [0.75e-3, 2e-3]], atol=1e-15)
    assert arc_lengths(points)[-1] == pytest.approx(4e-3, abs=1e-15)
    with pytest.raises(PathDepthError, match=r"allowed 0..0.004 m"):
        truncated(points, 4.5e-3, 0)


def test_refined_step_hits_every_depth():
    """The growth step: 0.5 mm / k, the largest of which every depth is a multiple."""
    assert refined_step([0.0, 3e-3, 6e-3, 9e-3]) == BASE_STEP
    assert refined_step([0.0, 1.25e-3, 2.5e-3]) == pytest.approx(BASE_STEP / 2, rel=1e-15)
    assert refined_step([0.0, 1e-4]) == pytest.approx(BASE_STEP / 5, rel=1e-15)
    assert refined_step([0.0, math.pi * 1e-3]) == BASE_STEP


@pytest.mark.slow
def test_signal_study_refuses_the_predicted_path(tmp_path, capsys):
    """The signal study's mesh curves come from straight cracks: ``hubvib signal`` on the
    shipped predicted-path scene is one line naming the key, exit 2, nothing written."""
    from hubvib.cli import main

    out = tmp_path / "out"
    assert main(["signal", "raba118_crack_path", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("hubvib: error: ") and "[crack] path = 'predicted'" in err
    assert len(err.strip().splitlines()) == 1 and not out.exists()


@pytest.mark.parametrize("lines, degrees", [
    ("angle_deg = 60", 60), ("path = 60", 60), ("angle_deg = -90", -90),
    ("start = \"rim\"\nangle_deg = -60", -60), ("start = \"rim\"\nangle_deg = 60", 60)])
def test_range_ends_of_the_crack_angle_are_accepted(lines, degrees):
    """The printed ranges are closed: -90..60 (root) and -60..60 (rim) accept their ends
    (math.degrees(math.radians(60)) = 59.99999999999999 refused 60 itself)."""
    crack = _scene(f"depths = [0.0]\n{lines}").crack
    assert crack.angle == pytest.approx(math.radians(degrees), abs=1e-15)


def test_engaged_ratio_is_the_mean_while_the_cracked_tooth_is_in_contact():
    """Synthetic cycles: intact 1 N/m everywhere, cracked 0.5 N/m on the contact window
    [1, 2] m only; the cycles run one pitch (1 m) beyond it on each side, as
    ``mesh_cycle`` does. The ratio over the contact is 0.5 exactly; over the whole span it
    would be diluted to (0.5 * 101 + 200) / 301."""
    from hubvib.fem.mesh_cycle import MeshCycle
    from hubvib.fem.tooth_stiffness import EngagedMesh

    s = np.linspace(0.0, 3.0, 301)
    inside = (s >= 1.0) & (s <= 2.0)
    intact = MeshCycle(s, np.ones_like(s), np.ones(s.shape, dtype=int))
    cracked = MeshCycle(s, np.where(inside, 0.5, 1.0), np.ones(s.shape, dtype=int))
    engaged = EngagedMesh(cracked, intact, (1.0, 2.0))
    assert engaged.mean_ratio == pytest.approx(0.5, rel=1e-15)
    assert cracked.mean / intact.mean == pytest.approx((0.5 * 101 + 200) / 301, rel=1e-12)
