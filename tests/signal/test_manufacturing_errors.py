"""Manufacturing errors, load sharing, the energy off the multiples of N, and contact loss."""
import math
from dataclasses import replace

import numpy as np
import pytest

from hubvib.design import preset_design
from hubvib.reducer import lumped_preset
from hubvib.signal.dynamics import planetary_dynamics
from hubvib.signal.contact import force_ratio, in_contact
from hubvib.signal.manufacturing import StageErrors, load_sharing, rigid_centre_sharing
from hubvib.signal.mesh_curves import synthetic_curves
from hubvib.signal.mesh_phase import design_phasing
from hubvib.signal.options import SignalOptions, parse_signal_table
from hubvib.signal.accelerometer import sensor_signal
from hubvib.signal.simulation import simulate
from hubvib.signal.spectral import non_multiple_fraction, order_spectrum
from hubvib.studies.scene import SceneError

RABA = preset_design("raba118")
FAST = SignalOptions(sun_speed_rpm=6000.0)
PHASING = design_phasing(RABA)
N = 3


def _run(options, params=None, crack=False):
    params = params or lumped_preset("raba118")
    curves = synthetic_curves(RABA, crack_factor=1.5 if crack else 1.0,
                              depth=0.01 if crack else 0.0).to_preset(params.c_sp, params.c_rp)
    sim = simulate(params, curves, PHASING, options, 0 if crack else None, 1, 26)
    return sim, order_spectrum(sensor_signal(sim, options.sensor_angle)[:-1]), curves


def test_load_sharing_against_the_quasi_static_closed_form():
    """Centre members held in translation and stiff planet bearings (1e13 N/m): the model's
    static mesh forces against F_i = F - k_sr [c_t de_t + c_r de_r] (errors module)."""
    big = 1e13
    params = lumped_preset("raba118").replace(c_s=big, c_c=big, c_r=big, c_p=big)
    for tangential, radial in (((20e-6, 0.0, 0.0), ()),
                               ((10e-6, -20e-6, 5e-6), (5e-6, 0.0, -7e-6))):
        options = replace(FAST, planet_position_errors_m=tangential,
                          pin_hole_radial_errors_m=radial)
        curves = synthetic_curves(RABA).to_preset(params.c_sp, params.c_rp)
        dynamics = planetary_dynamics(params, curves, 0.05, options.sun_torque_N_m,
                                      options.errors)
        closed = rigid_centre_sharing(params, options.errors, options.sun_torque_N_m,
                                      curves.sun_mean, curves.ring_mean)
        model = np.abs(dynamics.static_force[N:])
        np.testing.assert_allclose(model, closed, rtol=1e-3,
                                   err_msg="static ring-mesh forces vs the rigid-centre "
                                           "closed form (errors module docstring), 1e-3")
        assert np.ptp(load_sharing(dynamics.static_force, N)) > 0.01


def test_a_floating_sun_shares_equally_among_three_planets():
    """Raba preset (c_s = 0): the sun's force balance with three lines of action 120 deg
    apart leaves only equal forces (Kahraman 1994), whatever the pin-hole errors."""
    options = replace(FAST, planet_position_errors_m=(50e-6, 0.0, 0.0),
                      pin_hole_radial_errors_m=(0.0, 30e-6, 0.0))
    sim, _, _ = _run(options)
    np.testing.assert_allclose(load_sharing(sim.dynamics.static_force, N), 1.0, atol=1e-9,
                               err_msg="floating sun, N = 3: equal sharing, 1e-9")


def test_a_position_error_puts_energy_off_the_multiples_of_n_as_theory_says():
    """Zero errors: the non-multiple energy share is round-off.  50 um tangential error of
    planet 1: its meshes run delta = r_br e / a ahead (ring) in roll length, a phase
    psi_m = 2 pi m delta / p_b at mesh harmonic m.  Planet contributions c_i e^{i psi_i}
    with one planet shifted put the share (2/9) |e^{i psi} - 1|^2 = (8/9) sin^2(psi / 2)
    of harmonic m's energy off the multiples of N (first order in the spread of the
    planets, smooth per-planet spectrum); weighted by each harmonic's energy E_m in the
    error-free spectrum this gives the expected share."""
    _, clean, _ = _run(FAST)
    f0 = non_multiple_fraction(clean, N)
    assert f0 < 1e-20, f"ideal planets: round-off only, got {f0:.3g}"
    error = 50e-6
    _, spectrum, _ = _run(replace(FAST, planet_position_errors_m=(error, 0.0, 0.0)))
    measured = non_multiple_fraction(spectrum, N)
    delta = PHASING.ring_base_radius * error / PHASING.centre_distance
    energy = clean.amplitude[1:] ** 2
    harmonic = np.rint(clean.orders[1:] / 64).astype(int)
    expected = sum(energy[harmonic == m].sum() * 8 / 9
                   * math.sin(m * math.pi * delta / PHASING.base_pitch) ** 2
                   for m in range(harmonic.max() + 1)) / energy.sum()
    assert 1e-3 < expected < 1e-1, expected
    assert 0.5 < measured / expected < 2.0, \
        f"non_multiple_fraction {measured:.3g} vs theory {expected:.3g} (factor 2)"
    assert measured > 1e15 * f0, "orders of magnitude above round-off"


def test_ring_runout_keeps_the_cancellation_but_changes_the_lines():
    """A ring error fixed in space reaches every planet alike as it passes: the record
    keeps the 2 pi / N symmetry, so no energy leaves the multiples of N, while the lines
    at the multiples change (the run-out modulates the mesh)."""
    _, clean, _ = _run(FAST)
    _, spectrum, _ = _run(replace(FAST, ring_runout_m=20e-6, ring_runout_phase_deg=30.0))
    assert non_multiple_fraction(spectrum, N) < 1e-20, "symmetry: multiples of N only"
    change = np.abs(spectrum.amplitude - clean.amplitude).max() / clean.amplitude.max()
    assert change > 1e-3, f"the run-out must change the spectrum, changed {change:.3g}"


@pytest.mark.slow
def test_contact_loss_is_modelled_by_separation():
    """Held sun, light load, 50 um on planet 1: the linear ring mesh of planet 1 would pull
    (min total/static force < 0); the piecewise model separates it there, carries no
    tension anywhere, and its contact pattern is the one its deflections give."""
    options = replace(FAST, sun_torque_N_m=100.0,
                      planet_position_errors_m=(50e-6, 0.0, 0.0))
    params = lumped_preset("raba118").replace(c_s=1e8)
    sim, _, _ = _run(options, params, crack=True)
    assert sim.linear_min_force_ratio[N] < 0, sim.linear_min_force_ratio
    assert sim.separated[N] > 0.01 and sim.separated[[0, 1, 2, 4, 5]].max() == 0
    ratio = force_ratio(sim.dynamics, sim.forces)
    assert ratio.min() > -1e-9, "a separated mesh carries no force, never tension"
    touching = in_contact(sim.dynamics, sim.response.displacement, None)
    assert np.array_equal(ratio > 1e-12, touching), "active set consistent with deflections"
    linear, _, _ = _run(replace(options, contact="linear"), params, crack=True)
    np.testing.assert_allclose(linear.linear_min_force_ratio, sim.linear_min_force_ratio)
    assert linear.separated.max() == 0


def test_a_planet_that_unloads_is_said_clearly():
    options = replace(FAST, sun_torque_N_m=60.0, planet_position_errors_m=(50e-6, 0.0, 0.0))
    with pytest.raises(ValueError, match="contact loss"):
        _run(options, lumped_preset("raba118").replace(c_s=1e8), crack=True)


@pytest.mark.parametrize("table, message", [
    ({"planet_position_errors_m": [1e-2]}, "[signal] planet_position_errors_m = [0.01]; "
                                           "allowed: a list of 1 to 12 numbers in [-0.001"),
    ({"pin_hole_radial_errors_m": "5e-6"}, "[signal] pin_hole_radial_errors_m = '5e-6'"),
    ({"ring_runout_m": -1e-6}, "[signal] ring_runout_m = -1e-06; allowed"),
    ({"contact": "hertz"}, "[signal] contact = 'hertz'; allowed: piecewise, linear"),
])
def test_bad_error_keys(table, message):
    with pytest.raises(SceneError) as error:
        parse_signal_table(table)
    assert message in str(error.value)


def test_one_error_per_planet():
    with pytest.raises(ValueError, match="has 2 value"):
        StageErrors((1e-6, 2e-6)).per_planet(3)
    assert parse_signal_table({"planet_position_errors_m": [5e-5, 0, 0]}).errors.any()
