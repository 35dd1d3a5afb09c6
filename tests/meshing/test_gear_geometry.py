import math

import numpy as np
import pytest

from hubvib.reducer import raba118
from hubvib.meshing.gear import (GearGeometryError, SpurGear, centre_distance, involute,
                          inverse_involute, working_pressure_angle)

DEG = math.pi / 180
GEARS = [
    SpurGear(19, 3.25e-3, profile_shift=0.4),
    SpurGear(40, 2e-3, profile_shift=-0.3),
    SpurGear(64, 3.25e-3, profile_shift=1.398, internal=True),
    SpurGear(80, 5e-3, profile_shift=0.0, internal=True),
]


@pytest.mark.parametrize("gear", GEARS, ids=lambda g: f"z{g.teeth}{'i' if g.internal else 'e'}")
def test_flank_points_lie_on_the_involute(gear):
    """Defining property: the tangent from P to the base circle has length equal to the
    base-circle arc unwound from the involute's origin (to 1e-9 m)."""
    rb = gear.base_diameter / 2
    radii = np.linspace(rb * (1 + 1e-6), gear.tip_diameter / 2, 50)
    points = gear.flank(radii)
    origin = float(gear.half_tooth_angle(rb))
    for P in points:
        r = np.hypot(*P)
        a_r = math.acos(rb / r)
        phi_p = math.atan2(P[1], P[0])
        # the two tangent points from P to the base circle; PT is tangent at both
        mismatch = []
        for t in (phi_p - a_r, phi_p + a_r):
            T = np.array([rb * math.cos(t), rb * math.sin(t)])
            assert abs(np.dot(P - T, T)) < 1e-12
            mismatch.append(abs(np.linalg.norm(P - T) - rb * abs(t - origin)))
        assert min(mismatch) < 1e-9


@pytest.mark.parametrize("internal", [False, True])
def test_unshifted_tooth_is_half_the_pitch(internal):
    gear = SpurGear(60, 4e-3, internal=internal)
    assert gear.reference_tooth_thickness == pytest.approx(math.pi * 4e-3 / 2, rel=1e-15)
    assert float(gear.tooth_thickness(gear.reference_diameter)) == pytest.approx(
        math.pi * 4e-3 / 2, rel=1e-14)


@pytest.mark.parametrize("gear", GEARS, ids=lambda g: f"z{g.teeth}{'i' if g.internal else 'e'}")
@pytest.mark.parametrize("k", [2, 3, 5])
def test_span_measurement_from_profile_matches_din3960(gear, k):
    """W_k (DIN 3960 / ISO 21771) equals the base-circle arc between the flank origins."""
    rb = gear.base_diameter / 2
    psi_b = float(gear.half_tooth_angle(rb))
    if gear.internal:  # over k spaces: (k - 1) pitches plus one space, on the base circle
        from_profile = (k - 1) * gear.base_pitch + (gear.base_pitch - 2 * psi_b * rb)
    else:
        from_profile = (k - 1) * gear.base_pitch + 2 * psi_b * rb
    assert from_profile == pytest.approx(gear.span_measurement(k), rel=1e-13)


def test_khk_external_example():
    """KHK Gear Technical Reference, profile-shifted external pair: m 3, z 12/24,
    x 0.6/0.36 -> alpha_w = 26.0886 deg, a = 56.4999 mm."""
    g1 = SpurGear(12, 3e-3, profile_shift=0.6)
    g2 = SpurGear(24, 3e-3, profile_shift=0.36)
    assert working_pressure_angle(g1, g2) / DEG == pytest.approx(26.0886, abs=5e-5)
    assert centre_distance(g1, g2) == pytest.approx(56.4999e-3, abs=1e-6)


@pytest.mark.parametrize("pinion, gear", [
    (raba118.sun(), raba118.planet()),
    (raba118.planet(), raba118.ring()),
    (SpurGear(12, 3e-3, profile_shift=0.6), SpurGear(24, 3e-3, profile_shift=0.36)),
    (SpurGear(16, 3e-3, profile_shift=0.1), SpurGear(24, 3e-3, profile_shift=0.516, internal=True)),
])
def test_zero_backlash_on_working_circles(pinion, gear):
    """At the working angle, tooth of one + tooth of the other = working circular pitch
    (external) or tooth of pinion = space of ring (internal): s_w1 + s_w2 = p_w."""
    a_w = working_pressure_angle(pinion, gear)
    d_w1 = pinion.base_diameter / math.cos(a_w)
    d_w2 = gear.base_diameter / math.cos(a_w)
    p_w = math.pi * d_w1 / pinion.teeth
    assert math.pi * d_w2 / gear.teeth == pytest.approx(p_w, rel=1e-14)
    total = float(pinion.tooth_thickness(d_w1) + gear.tooth_thickness(d_w2))
    assert total == pytest.approx(p_w, rel=1e-12)


def test_raba_gears_match_paper_base_diameters_and_working_angle():
    """Paper's table: d_b 79.404 / 58.026 / 195.45 mm; alpha_w = 25.28 deg for both meshes."""
    for gear, d_b in ((raba118.sun(), 79.404e-3), (raba118.planet(), 58.026e-3),
                      (raba118.ring(), 195.45e-3)):
        assert gear.base_diameter == pytest.approx(d_b, abs=0.01e-3)
    sp = working_pressure_angle(raba118.sun(), raba118.planet())
    rp = working_pressure_angle(raba118.planet(), raba118.ring())
    assert sp / DEG == pytest.approx(25.28, abs=1e-10) and rp / DEG == pytest.approx(25.28, abs=1e-10)
    assert centre_distance(raba118.sun(), raba118.planet()) == pytest.approx(
        centre_distance(raba118.planet(), raba118.ring()), rel=1e-14)


def test_internal_circles():
    ring = SpurGear(64, 3.25e-3, profile_shift=0.5, internal=True)
    assert ring.tip_diameter == pytest.approx(64 * 3.25e-3 - 2 * 3.25e-3 * 0.5)
    assert ring.root_diameter == pytest.approx(64 * 3.25e-3 + 2 * 3.25e-3 * 1.75)
    assert float(ring.tooth_thickness(ring.root_diameter)) > ring.reference_tooth_thickness


@pytest.mark.parametrize("value", [0.0, 1e-4, 0.0149, 0.5, 3.0])
def test_inverse_involute_round_trip(value):
    assert float(involute(inverse_involute(value))) == pytest.approx(value, rel=1e-12, abs=1e-300)


@pytest.mark.parametrize("kwargs, message", [
    (dict(teeth=26, module=3e-3, profile_shift=1.6), "pointed tooth"),
    (dict(teeth=8, module=3e-3, profile_shift=0.0), "undercuts"),
    (dict(teeth=20, module=3e-3, profile_shift=-2.0, internal=True), "inside the base circle"),
    (dict(teeth=5, module=3e-3), r"teeth = 5, but it must be an integer >= 6"),
    (dict(teeth=20.0, module=3e-3), "teeth = 20.0"),
    (dict(teeth=20, module=0.0), "module = 0.0"),
    (dict(teeth=20, module=3e-3, pressure_angle=0.9), "pressure_angle"),
    (dict(teeth=20, module=3e-3, dedendum_coefficient=0.9), "dedendum_coefficient"),
])
def test_bad_gear_parameters(kwargs, message):
    with pytest.raises(GearGeometryError, match=message):
        SpurGear(**kwargs)
