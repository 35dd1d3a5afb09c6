"""Mesh phasing from the gear geometry and the planet-phasing cancellation at a fixed sensor."""
import math

import numpy as np

from hubvib.reducer import raba118 as geometry
from hubvib.reducer import lumped_preset
from hubvib.meshing.gear import centre_distance, rotation
from hubvib.signal.mesh_curves import synthetic_curves
from hubvib.design import preset_design
from hubvib.signal.mesh_phase import design_phasing

from hubvib.signal.options import SignalOptions
from hubvib.signal.accelerometer import sensor_signal
from hubvib.signal.simulation import simulate
from hubvib.signal.spectral import order_spectrum

RABA = preset_design("raba118")  # the reference case (hubvib.design.presets)


FAST = SignalOptions(sun_speed_rpm=6000.0)


def _crossings(points, origin, direction):
    """Signed distances along ``direction`` from ``origin`` where the polyline crosses the
    line through ``origin``."""
    normal = np.array([-direction[1], direction[0]])
    d = (points - origin) @ normal
    out = []
    for i in np.flatnonzero(np.sign(d[:-1]) != np.sign(d[1:])):
        w = d[i] / (d[i] - d[i + 1])
        out.append(float((points[i] + w * (points[i + 1] - points[i]) - origin) @ direction))
    return out


def test_roll_lengths_match_the_involute_flanks_intersected_with_the_lines_of_action():
    """Independent check: flank polylines of the real gears cut by the lines of action."""
    ph = design_phasing(RABA)
    ring, planet = geometry.ring(), geometry.planet()
    a = centre_distance(planet, ring)
    rb_p = planet.base_diameter / 2
    theta, beta = 0.3, 0.123                          # planet position and spin angle
    centre = a * np.array([math.cos(theta), math.sin(theta)])
    tau_r = theta + ph.alpha_r                       # ring line touches the planet here
    T_r = centre + rb_p * np.array([math.cos(tau_r), math.sin(tau_r)])
    t_r = np.array([-math.sin(tau_r), math.cos(tau_r)])
    radii = np.linspace(ring.base_diameter / 2, ring.root_diameter / 2, 20000)
    found = 0
    for k in range(ring.teeth):
        flank = (rotation(2 * math.pi * k / ring.teeth) @ ring.flank(radii).T).T
        for s in _crossings(flank, T_r, t_r):
            if 0 < -s < 0.03:
                found += 1
                assert abs(-s - float(ph.ring_roll(theta, k))) < 1e-9, \
                    f"ring tooth {k}: roll length by flank intersection vs mesh_phase, 1 nm"
    assert found >= 2
    # the planet's two flanks: sun mesh on the +psi flanks, ring mesh on the -psi flanks
    tau_s = theta + math.pi - ph.alpha_s
    T_s = centre + rb_p * np.array([math.cos(tau_s), math.sin(tau_s)])
    t_s = np.array([-math.sin(tau_s), math.cos(tau_s)])
    r = np.linspace(rb_p * (1 + 1e-9), planet.tip_diameter / 2, 20000)
    sun_side, ring_side = [], []
    for k in range(planet.teeth):
        R = rotation(beta + 2 * math.pi * k / planet.teeth)
        sun_side += [s for s in _crossings(centre + (R @ planet.flank(r).T).T, T_s, t_s) if s > 0]
        ring_side += [-s for s in _crossings(centre + (R @ (planet.flank(r) * [1, -1]).T).T,
                                             T_r, t_r) if s < 0]
    total = (min(sun_side) + min(ring_side)) % ph.base_pitch
    assert abs(total - ph.roll_sum % ph.base_pitch) < 1e-9, \
        "s_sun + s_ring of one planet must be the constant roll_sum (mod p_b), 1 nm"


def test_parker_lin_phases_of_equally_spaced_planets():
    """Parker & Lin 2004: planet i's ring mesh leads planet 1's by z_r psi_i / 2 pi cycles and
    its sun mesh by -z_s psi_i / 2 pi, the same fraction when (z_s + z_r) / N is whole."""
    ph = design_phasing(RABA)
    z_s, z_r = geometry.sun().teeth, geometry.ring().teeth
    assert (z_s + z_r) % 3 == 0
    for i in range(1, 3):
        psi = 2 * math.pi * i / 3
        ring = (ph.ring_roll(0.2 + psi) - ph.ring_roll(0.2)) / ph.base_pitch % 1
        sun = (ph.sun_roll(0.2 + psi) - ph.sun_roll(0.2)) / ph.base_pitch % 1
        assert abs(ring - (z_r * psi / (2 * math.pi)) % 1) < 1e-12
        assert abs((-sun) % 1 - (-z_s * psi / (2 * math.pi)) % 1) < 1e-12 or \
            abs(sun - (z_s * psi / (2 * math.pi)) % 1) < 1e-12


def _sensor_spectrum(params, crack_factor=1.0):
    curves = synthetic_curves(RABA, crack_factor=crack_factor,
                              depth=0.01 if crack_factor != 1 else 0.0)
    curves = curves.to_preset(params.c_sp, params.c_rp)
    sim = simulate(params, curves, design_phasing(RABA), FAST, crack_tooth=0)
    return order_spectrum(sensor_signal(sim, math.radians(30.0))[:-1])


def test_equally_spaced_planets_cancel_every_order_that_is_not_a_multiple_of_n():
    """Rule (McFadden & Smith 1985, Proc. IMechE 199 C, eq. for the summed planet signals;
    Parker & Lin 2004 phasing): with N identical, equally spaced planets whose meshes are
    phased as the geometry sets them, planet i's signal at a sensor fixed on the ring is
    planet 1's delayed by i/N of a carrier revolution, so the sum keeps only carrier orders
    k with k = 0 (mod N); the mesh order z_r = 64 itself (not a multiple of 3) vanishes and
    its energy appears at 63 and 66.  A ring crack, met by every planet in turn, keeps the
    rule.  Unequal spacing breaks it."""
    params = lumped_preset("raba118")
    for factor in (1.0, 1.5):
        spectrum = _sensor_spectrum(params, factor)
        a = spectrum.amplitude[1:]
        k = spectrum.orders[1:]
        off = a[k % 3 != 0].max() / a.max()
        assert off < 1e-9, f"crack factor {factor}: a non-multiple of N carries {off:.2e}"
        assert spectrum.amplitude[64] < 1e-9 * spectrum.amplitude[63]
        band = spectrum.amplitude[44:85]
        assert band.argmax() + 44 == 63, "the nearest multiple of N carries the mesh line"
    uneven = params.replace(theta=(0.0, math.radians(118.0), math.radians(241.0)))
    spectrum = _sensor_spectrum(uneven)
    a, k = spectrum.amplitude[1:], spectrum.orders[1:]
    assert a[k % 3 != 0].max() > 1e-3 * a.max(), "unequal spacing must break the cancellation"
    assert spectrum.amplitude[64] > 1e-3 * a.max()
