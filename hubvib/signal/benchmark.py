"""Cost of the time-domain stage: hubvib's fixed-step scheme against ``scipy.integrate.solve_ivp``.

The Raba reducer with a cracked ring tooth (synthetic mesh curves: the FE curves
have the same form and cost nothing more here), 10 carrier revolutions, the
sensor signal at 20 kHz (43 samples per mesh period).  Three ways, same run:

- ``newmark``: periodic start, then all revolutions marched step by step;
- ``periodic``: periodic start, one revolution, the record extended by its
  Fourier series (what ``hubvib signal`` does: the steady state repeats);
- ``solve_ivp``: RK45 on the first-order system from the same start state,
  stiffnesses read from the same tables (the plain baseline);
- ``periodic_quarter_step``: the periodic path (one revolution) at h/4, to compare
  at about solve_ivp's accuracy.

Both integrators solve the same problem, the stiffness and loads linear between
the points of the step table (the mesh stiffness jumps where a tooth pair enters
or leaves contact, and this is how both see the jumps).  Errors of the sensor
signal over the last revolution, relative to its largest value, are against the
Richardson extrapolation of the average-acceleration steady states at h and h/2
on that problem.
"""
from __future__ import annotations

import math
import time

import numpy as np

from hubvib.signal.dynamics import excitation
from hubvib.signal.mesh_curves import synthetic_curves
from hubvib.signal.mesh_phase import design_phasing, design_teeth
from hubvib.signal.options import SignalOptions
from hubvib.signal.accelerometer import hann_window, sampled, sensor_signal
from hubvib.signal.simulation import simulate
from hubvib.signal.time_response import Excitation, integrate, periodic_start


def benchmark_signal(design, params, revolutions: int = 10, sample_rate_hz: float = 20000.0,
                     rtol: float = 1e-6, elastic: bool = False) -> dict:
    """Timings [s], their ratio and the errors of both integrators (see the module), for a
    design and its lumped parameters (the benchmark: Raba 118/76); with ``elastic``, also
    the elastic ring's record (:func:`benchmark_elastic_signal`, keys ``signal_elastic_*``)
    beside the rigid route's record of the same length (``signal_rigid_seconds``)."""
    from scipy.integrate import solve_ivp  # the baseline only: not with the package



    curves = synthetic_curves(design, crack_factor=1.5, depth=0.01).to_preset(params.c_sp,
                                                                               params.c_rp)
    phasing, teeth = design_phasing(design), design_teeth(design)
    options = SignalOptions(sample_rate_hz=sample_rate_hz, revolutions=revolutions)

    started = time.perf_counter()
    marched = simulate(params, curves, phasing, options, 0, revolutions, teeth["sun"])
    signal = sensor_signal(marched, options.sensor_angle)
    carrier_hz = marched.carrier_speed / (2 * math.pi)
    M = marched.steps_per_revolution
    sampled(signal[:M], carrier_hz, sample_rate_hz, revolutions / carrier_hz)
    newmark_s = time.perf_counter() - started

    started = time.perf_counter()
    one = simulate(params, curves, phasing, options, 0, 1, teeth["sun"])
    record = sampled(sensor_signal(one, options.sensor_angle)[:-1], carrier_hz, sample_rate_hz,
                     revolutions / carrier_hz)[1]
    periodic_s = time.perf_counter() - started

    # baseline: solve_ivp on y' = F(t) y + g(t) from the same periodic state

    dyn, h = marched.dynamics, marched.step
    system = dyn.system
    loads = excitation(dyn, marched.state, curves.base_pitch)
    n = system.n
    minv = 1.0 / system.mass
    G, K0, C = system.rows, system.stiffness, system.damping

    def table(values, t):
        position = t / h
        i = min(int(position), values.shape[0] - 2)
        w = position - i
        return values[i] * (1 - w) + values[i + 1] * w

    def rhs(t, y):
        x, v = y[:n], y[n:]
        dk, r = table(loads.dk, t), table(loads.r, t)
        force = G.T @ (r - dk * (G @ x)) - K0 @ x - C @ v
        return np.concatenate([v, minv * force])

    y0 = np.concatenate([marched.response.displacement[0], marched.response.velocity[0]])
    last = (revolutions - 1) * M + np.arange(M)
    started = time.perf_counter()
    solution = solve_ivp(rhs, (0.0, revolutions * M * h), y0, method="RK45", rtol=rtol,
                         atol=rtol * np.abs(y0).max(), t_eval=last * h)
    solve_ivp_s = time.perf_counter() - started
    # the problem both solve: stiffness and loads linear between the step points of the
    # table; reference: Richardson extrapolation of the scheme at h and h/2 on it (O(h^4))
    one_rev = Excitation(loads.dk[:M + 1], loads.r[:M + 1])
    half = Excitation(_halved(one_rev.dk), _halved(one_rev.r))
    x_h = integrate(system, h, one_rev, y0=periodic_start(system, h, one_rev)).displacement
    x_half = integrate(system, h / 2, half,
                       y0=periodic_start(system, h / 2, half)).displacement[::2]
    angle = marched.carrier_speed * h * np.arange(M + 1)

    def sensor(x):
        return _sensor(dyn, one_rev.dk, x, angle, options.sensor_angle)[:M]

    s_h = sensor(x_h)
    reference = (4 * sensor(x_half) - s_h) / 3
    scale = np.abs(reference).max()
    s_ivp = sensor(np.vstack([solution.y[:n].T, solution.y[:n, :1].T]))
    # the periodic path at a quarter of the step, near solve_ivp's accuracy
    quarter = Excitation(_halved(half.dk), _halved(half.r))
    started = time.perf_counter()
    x_quarter = integrate(system, h / 4, quarter,
                          y0=periodic_start(system, h / 4, quarter)).displacement[::4]
    quarter_s = time.perf_counter() - started
    s_quarter = sensor(x_quarter)
    mesh_hz = carrier_hz * teeth["ring"]
    extra = benchmark_elastic_signal(design, sample_rate_hz=sample_rate_hz) if elastic else {}
    if elastic:
        started = time.perf_counter()
        rigid = simulate(params, curves, phasing, options, 0, 1, teeth["sun"])
        sampled(sensor_signal(rigid, options.sensor_angle)[:-1], carrier_hz, sample_rate_hz,
                extra["signal_elastic_record_s"])
        extra["signal_rigid_seconds"] = time.perf_counter() - started
    return extra | {
        "revolutions": revolutions, "sample_rate_hz": sample_rate_hz,
        "samples_per_mesh_period": sample_rate_hz / mesh_hz, "record_samples": record.size,
        "steps_per_revolution": M, "time_step_s": h,
        "newmark_s": newmark_s, "periodic_s": periodic_s, "solve_ivp_s": solve_ivp_s,
        "solve_ivp_over_newmark": solve_ivp_s / newmark_s,
        "solve_ivp_over_periodic": solve_ivp_s / periodic_s,
        "newmark_error": float(np.abs(s_h - reference).max() / scale),
        "periodic_quarter_step_s": quarter_s,
        "periodic_quarter_step_error": float(np.abs(s_quarter - reference).max() / scale),
        "solve_ivp_error": float(np.abs(s_ivp - reference).max() / scale),
        "solve_ivp_method": "RK45", "solve_ivp_rtol": rtol,
        "solve_ivp_evaluations": int(solution.nfev),
    }


def _halved(table: np.ndarray) -> np.ndarray:
    """A step table at twice the rate, linear between the given points."""
    out = np.empty((2 * table.shape[0] - 1, table.shape[1]))
    out[::2] = table
    out[1::2] = 0.5 * (table[:-1] + table[1:])
    return out


def _sensor(dyn, dk, x, angle, sensor_angle):
    """Sensor signal from displacements and the stiffness table (as ``sensor_signal``)."""
    N = dyn.n_planets
    k = dyn.mean[None, :] + dk
    forces = k * (dyn.preload[None, :] + x @ dyn.system.rows.T) - dyn.static_force[None, :]
    theta = angle[:, None] + np.array(dyn.params.theta)[None, :]
    window = hann_window(theta - sensor_angle, N)
    return (window * forces[:, N:]).sum(axis=1) / dyn.params.m_r


def benchmark_elastic_signal(design, record_s: float = 10.0, sample_rate_hz: float = 20000.0,
                             depth: float = 0.0) -> dict:
    """Cost [s] of one elastic-ring record of ``record_s`` [s] (the design's FE ring with
    every tooth's contact response, its model at every carrier position, the time
    integration, synthetic mesh curves): ``signal_elastic_seconds`` in all,
    ``signal_elastic_integration_seconds`` of the time integration alone."""
    from dataclasses import replace

    from hubvib.elastic.options import ElasticScene
    from hubvib.elastic.rest import rest_stiffness
    from hubvib.meshing.crack import Crack

    from .elastic_record import depth_record, elastic_ring_all_teeth

    scene = ElasticScene(ring="elastic", sensor_angle=0.0)
    started = time.perf_counter()
    k_rest = rest_stiffness(design, scene.options.rest)
    er = elastic_ring_all_teeth(design, Crack(0, depth, 0.0, "root") if depth else None, scene,
                                k_rest)
    ring_s = time.perf_counter() - started
    curves = synthetic_curves(design).to_preset(er.params.c_sp, er.params.c_rp)
    teeth = design_teeth(design)
    carrier_hz = 1500.0 / 60 * teeth["sun"] / (teeth["sun"] + teeth["ring"])
    options = replace(SignalOptions(sample_rate_hz=sample_rate_hz, damping_ratio=0.02,
                                    ambient_force_psd_N2_Hz=100.0),
                      revolutions=record_s * carrier_hz)
    record, _ = depth_record(design, er, curves, options, 0.0, 0, 0)
    return {"signal_elastic_seconds": time.perf_counter() - started,
            "signal_elastic_ring_seconds": ring_s,
            "signal_elastic_integration_seconds": record.integration_seconds,
            "signal_elastic_steps": record.steps, "signal_elastic_modes": record.modes,
            "signal_elastic_ring_dofs": er.operators.size,
            "signal_elastic_record_s": record.values.size / sample_rate_hz}
