"""Time integration of the lumped model against independent references."""
import math
from dataclasses import replace

import numpy as np
import pytest

from hubvib.lumped import natural_modes
from hubvib.reducer import lumped_preset
from hubvib.lumped.network import mass_diagonal, spring_network
from hubvib.signal.dynamics import planetary_dynamics
from hubvib.signal.mesh_curves import synthetic_curves
from hubvib.design import preset_design
from hubvib.signal.mesh_phase import design_phasing

from hubvib.signal.options import SignalOptions
from hubvib.signal.simulation import simulate
from hubvib.signal.signature_study import step_halving_change
from hubvib.signal.time_response import (Excitation, LinearSystem, integrate,
                                         periodic_start)

RABA = preset_design("raba118")  # the reference case (hubvib.design.presets)


#: a fast operating point for tests: a shorter carrier revolution, fewer steps
FAST = SignalOptions(sun_speed_rpm=6000.0, sample_rate_hz=20000.0)


def _raba_system(damping=None):
    params = lumped_preset("raba118")
    network = spring_network(params)
    n = params.n_dof
    rows = network.G[[p == "c_rp" for p in network.parameter]]
    C = np.zeros((n, n)) if damping is None else damping
    return params, LinearSystem(mass_diagonal(params), C, network.stiffness_matrix(), rows)


def _unforced(system, steps):
    m = system.rows.shape[0]
    return Excitation(np.zeros((steps + 1, m)), np.zeros((steps + 1, m)))


def _discrete_angle(eta):
    """Angle per step of a sampled cosine: cos(theta) = (e[k+1] + e[k-1]) / (2 e[k])."""
    middle = eta[1:-1]
    return math.acos(np.dot(middle, eta[2:] + eta[:-2]) / (2 * np.dot(middle, middle)))


@pytest.mark.parametrize("scheme", ["newmark", "central"])
def test_free_response_gives_the_modal_frequencies(scheme):
    params, system = _raba_system()
    spectrum = natural_modes(params)
    h = 2e-6
    x0 = spectrum.shapes @ np.ones(params.n_dof)       # every mode, unit amplitude
    response = integrate(system, h, _unforced(system, 600), x0=x0, scheme=scheme)
    eta = response.displacement @ (spectrum.mass[:, None] * spectrum.shapes)
    theta = np.array([_discrete_angle(eta[:, i]) for i in range(params.n_dof)])
    # exact dispersion of each scheme (Hughes 1987, sec. 9.3): average acceleration turns a
    # mode by 2 arctan(omega h / 2) per step, central difference by 2 arcsin(omega h / 2)
    omega = (2 / h) * (np.tan(theta / 2) if scheme == "newmark" else np.sin(theta / 2))
    np.testing.assert_allclose(
        omega, spectrum.omega, rtol=1e-6,
        err_msg=f"{scheme} free response vs lumped.natural_modes, through the scheme's "
                "exact dispersion relation, 1e-6")
    # and the raw discrete frequency converges to omega at second order
    raw = theta / h
    error = abs(raw[-1] / spectrum.omega[-1] - 1)
    bound = (spectrum.omega[-1] * h) ** 2 / 12 * 1.01
    assert error <= bound, f"{scheme}: highest mode off by {error:.3g} > (omega h)^2/12"


def test_harmonic_force_gives_the_frf_amplitude():
    params, _ = _raba_system()
    spectrum = natural_modes(params)
    mass = spectrum.mass
    zeta = 0.05
    MPhi = mass[:, None] * spectrum.shapes
    C = MPhi @ np.diag(2 * zeta * spectrum.omega) @ MPhi.T
    _, system = _raba_system(C)
    omega_f = 0.8 * spectrum.omega[1]
    steps = 4000                                       # one forcing period, h = T / 4000
    h = 2 * math.pi / omega_f / steps
    n, m = params.n_dof, system.rows.shape[0]
    force = np.zeros(n)
    force[6] = 100.0                                   # on the sun rotation u_s [N]
    f_ext = np.outer(np.cos(omega_f * h * np.arange(steps + 1)), force)
    loads = Excitation(np.zeros((steps + 1, m)), np.zeros((steps + 1, m)), f_ext)
    y0 = periodic_start(system, h, loads)
    x = integrate(system, h, loads, y0=y0).displacement
    frf = np.linalg.solve(system.stiffness - omega_f ** 2 * np.diag(mass) + 1j * omega_f * C,
                          force)
    amplitude = np.abs(np.fft.rfft(x[:-1], axis=0)[1]) * 2 / steps
    tolerance = 1e-3 * np.abs(frf).max()
    np.testing.assert_allclose(amplitude, np.abs(frf), atol=tolerance,
                               err_msg="steady amplitude vs the analytic FRF "
                                       "(K - w^2 M + i w C)^-1 f, 1e-3 of the largest")


def test_undamped_energy_is_conserved_exactly_by_average_acceleration():
    params, system = _raba_system()
    rng = np.random.default_rng(1)
    x0, v0 = 1e-4 * rng.standard_normal(params.n_dof), 1e-2 * rng.standard_normal(params.n_dof)
    response = integrate(system, 1e-5, _unforced(system, 2000), x0=x0, v0=v0)
    x, v = response.displacement, response.velocity
    energy = 0.5 * np.einsum("ki,i,ki->k", v, system.mass, v) + 0.5 * np.einsum(
        "ki,ij,kj->k", x, system.stiffness, x)
    drift = np.abs(energy / energy[0] - 1).max()
    # exact in exact arithmetic; what is left is round-off, ~1e-14 per step over 2000 steps
    assert drift < 1e-10, f"Newmark average acceleration keeps the energy of an undamped " \
                          f"linear system exactly (Hughes 1987); drift {drift:.2e} > 1e-10"


def test_static_preload_carries_the_input_torque_through_every_mesh():
    params = lumped_preset("raba118")
    curves = synthetic_curves(RABA).to_preset(params.c_sp, params.c_rp)
    dynamics = planetary_dynamics(params, curves, 0.05, 1000.0)
    expected = 1000.0 / (params.d_s / 2) / params.n_planets   # T_s / (N r_bs)
    np.testing.assert_allclose(np.abs(dynamics.static_force), expected, rtol=1e-10,
                               err_msg="static mesh forces vs the torque balance T_s/(N r_bs)")


def _cracked():
    params = lumped_preset("raba118")
    return params, synthetic_curves(RABA, crack_factor=1.5, depth=0.01).to_preset(params.c_sp,
                                                                            params.c_rp)


def test_periodic_start_repeats_every_revolution():
    params, curves = _cracked()
    sim = simulate(params, curves, design_phasing(RABA), FAST, crack_tooth=0, revolutions=2)
    M = sim.steps_per_revolution
    f = sim.ring_forces
    assert np.abs(f[M:] - f[:M + 1]).max() < 1e-9 * np.abs(f).max(), \
        "the periodic steady state must repeat after one carrier revolution"


def test_halving_the_time_step_changes_the_spectrum_little():
    params, curves = _cracked()
    change = step_halving_change(params, curves, design_phasing(RABA), FAST, 3 * 64 + 18, None, 26)
    assert change["relative_change"] < 0.02, \
        f"halving the time step moved the order amplitudes by {change['relative_change']:.3g} " \
        "of the largest (stated tolerance 0.02)"


def test_static_transmission_error_drives_the_meshes_linearly():
    """With (almost) no load the stiffness variation excites nothing and the static
    transmission error is the only source: the response scales with its amplitude and sits
    at the mesh harmonics' planet-pass lines."""
    params, curves = _cracked()
    responses = []
    for amplitude in (1e-6, 2e-6):
        options = replace(FAST, sun_torque_N_m=1e-9, transmission_error_m=amplitude,
                          contact="linear")   # unloaded: the linear springs may pull
        sim = simulate(params, curves, design_phasing(RABA), options, crack_tooth=None)
        responses.append(sim.ring_forces)
    scale = np.abs(responses[0]).max()
    assert scale > 1.0, "a 1 um transmission error must load the meshes"
    np.testing.assert_allclose(responses[1], 2 * responses[0], atol=1e-6 * scale,
                               err_msg="linear model: twice the error, twice the force")


@pytest.mark.slow
def test_benchmark_runs_both_integrators_on_the_same_problem():
    from hubvib.signal import benchmark_signal

    result = benchmark_signal(RABA, lumped_preset("raba118"), revolutions=1)
    assert result["samples_per_mesh_period"] >= 20
    # accuracy only (never timings): both within 5 % of the Richardson reference
    assert result["newmark_error"] < 0.05 and result["solve_ivp_error"] < 0.05, result
