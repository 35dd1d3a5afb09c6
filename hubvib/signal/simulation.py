"""One operating point in time: step size, periodic steady state, mesh forces (SI).

The step divides one carrier revolution exactly (``steps_per_revolution``), so the
excitation (mesh cycles and the cracked tooth, both locked to the carrier with the
ring fixed) repeats after that many steps, and the steady state is the state
that repeats: ``y_0 = (I - Phi)^-1 c`` with the one-revolution map of the
integrator.  No run-in is simulated and no transient is left in the record.

Step size: the smaller of one period of the highest natural frequency and one
mesh period, each divided by ``steps_per_period`` (average acceleration keeps a
mode's frequency to ``(omega h)^2 / 12``: 0.8 % at 20 steps per period).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.foundation.bounds import upper_bound
from hubvib.lumped import PlanetaryParameters

from .contact import MAX_PASSES, force_ratio, in_contact, mesh_names
from .dynamics import (MeshState, PlanetaryDynamics, excitation, mesh_forces, mesh_state,
                       planetary_dynamics, transmission_error_of)
from .manufacturing import planet_shift, runout_error
from .mesh_curves import MeshCurves
from .mesh_phase import MeshPhasing
from .options import SignalOptions
from .time_response import (TimeResponse, acceleration, central_stability_limit, integrate,
                            periodic_start)

RING_X, RING_Y = 4, 5


@dataclass(frozen=True)
class Simulation:
    """Response over whole carrier revolutions on the step grid ``t_k = k h``.

    Attributes
    ----------
    dynamics : PlanetaryDynamics
    carrier_speed : float
        [rad/s].
    steps_per_revolution : int
    state : MeshState
        Mesh stiffness and roll length at every step.
    response : TimeResponse
        Displacement [m] and velocity [m/s] of every coordinate.
    forces : ndarray (steps + 1, 2N)
        Dynamic part of every mesh force [N] (sun meshes, then ring meshes).
    ring_acceleration : ndarray (steps + 1, 2)
        x_r'', y_r'' [m/s^2].
    linear_min_force_ratio : ndarray (2N,)
        Smallest total over static force of every mesh in the linear model [-]
        (below 0: the mesh would pull; then the piecewise contact model is solved).
    separated : ndarray (2N,)
        Fraction of the revolution each mesh spends separated [-] (0: always in contact).
    """

    dynamics: PlanetaryDynamics
    carrier_speed: float
    steps_per_revolution: int
    state: MeshState
    response: TimeResponse
    forces: np.ndarray
    ring_acceleration: np.ndarray
    linear_min_force_ratio: np.ndarray | None = None
    separated: np.ndarray | None = None

    @property
    def step(self) -> float:
        """[s]"""
        return self.response.step

    @property
    def time(self) -> np.ndarray:
        """[s]"""
        return self.response.time

    @property
    def carrier_angle(self) -> np.ndarray:
        """[rad]"""
        return self.carrier_speed * self.time

    @property
    def ring_forces(self) -> np.ndarray:
        """Dynamic ring-planet mesh forces [N], one column per planet."""
        return self.forces[:, self.dynamics.n_planets:]


def carrier_speed(options: SignalOptions, ring_teeth: int, sun_teeth: int) -> float:
    """Carrier speed [rad/s] with the ring fixed: omega_s z_s / (z_s + z_r)."""
    return options.sun_speed * sun_teeth / (sun_teeth + ring_teeth)


def steps_per_revolution(omega_max: float, speed: float, ring_teeth: int,
                         options: SignalOptions, n_planets: int = 1) -> int:
    """Integrator steps per carrier revolution (see the module docstring), a multiple of
    z_r and N: every mesh cycle then has the same steps and planet i's excitation is
    planet 1's shifted by whole steps, so the discrete model keeps the cyclic symmetry.

    Raises
    ------
    ValueError
        ``[signal] time_step_s`` longer than half a mesh period, or, with
        ``integrator = "central"``, above its stability limit.
    """
    revolution = 2 * math.pi / speed
    mesh_period = revolution / ring_teeth
    limit = central_stability_limit(omega_max, options.damping_ratio)
    if options.time_step_s > 0:
        if options.time_step_s > mesh_period / 2:
            raise ValueError(f"[signal] time_step_s = {options.time_step_s:g}; allowed: <= "
                             f"{upper_bound(mesh_period / 2, 4)} s (half a mesh period)")
        if options.integrator == "central" and options.time_step_s >= limit:
            raise ValueError(
                f"[signal] time_step_s = {options.time_step_s:g}; allowed: < "
                f"{upper_bound(limit, 4, strict=True)} s "
                f"(the central difference scheme is unstable above 2 (sqrt(1 + zeta^2) - "
                f"zeta) / omega_max, omega_max = {omega_max:.6g} rad/s)")
        step = options.time_step_s
    else:
        step = min(2 * math.pi / omega_max, mesh_period) / options.steps_per_period
        if options.integrator == "central":
            step = min(step, 0.9 * limit)
    unit = math.lcm(ring_teeth, n_planets)
    return unit * int(math.ceil(revolution / step / unit - 1e-9))


def simulate(params: PlanetaryParameters, curves: MeshCurves, phasing: MeshPhasing,
             options: SignalOptions, crack_tooth: int | None = None, revolutions: int = 1,
             sun_teeth: int = 26) -> Simulation:
    """Periodic steady state over ``revolutions`` carrier revolutions.

    Parameters
    ----------
    params : PlanetaryParameters
    curves : MeshCurves
        Already scaled as the options ask (``"ratio"`` or ``"direct"``).
    phasing : MeshPhasing
    options : SignalOptions
    crack_tooth : int or None
        Cracked ring tooth (its curve is ``curves.cracked_*``).
    revolutions : int
        Carrier revolutions to march (the first starts on the steady state).
    sun_teeth : int
        z_s (the carrier speed follows from it and ``phasing.ring_teeth``).
    """
    errors = options.errors
    dynamics = planetary_dynamics(params, curves, options.damping_ratio, options.sun_torque_N_m,
                                  errors)
    speed = carrier_speed(options, phasing.ring_teeth, sun_teeth)
    per_rev = steps_per_revolution(float(dynamics.omega.max()), speed, phasing.ring_teeth,
                                   options, params.n_planets)
    h = 2 * math.pi / speed / per_rev
    tooth = crack_tooth if curves.cracked_s is not None else None
    shift = planet_shift(errors, params.n_planets, phasing.centre_distance) \
        if errors.any() else None

    def run(steps, contact, y0=None):
        """Mesh state, loads, response and mesh forces over ``steps`` steps; ``contact``
        (per_rev + 1, 2N) zeroes the stiffness of separated meshes (tiled per revolution)."""
        angle = speed * h * np.arange(steps + 1)
        runout = runout_error(dynamics.system.rows, angle, errors, params.n_planets)
        state = mesh_state(dynamics, curves, phasing, angle, tooth, shift,
                           _roll(runout, params.n_planets))
        if contact is not None:
            mask = np.vstack([np.tile(contact[:-1], (steps // per_rev, 1)), contact[-1:]])
            state = MeshState(state.stiffness * mask, state.roll)
        loads = excitation(dynamics, state, curves.base_pitch, options.transmission_error_m,
                           runout)
        if y0 is None:
            y0 = periodic_start(dynamics.system, h, loads, options.integrator)
        response = integrate(dynamics.system, h, loads, scheme=options.integrator, y0=y0)
        error = _error(state, curves.base_pitch, options.transmission_error_m, runout)
        forces = mesh_forces(dynamics, state, response.displacement, curves.base_pitch,
                             options.transmission_error_m, runout)
        return state, loads, response, forces, error, y0

    # one revolution, linear; then, where a mesh would pull, the piecewise contact model
    contact = None
    state, loads, response, forces, error, y0 = run(per_rev, None)
    linear_min = force_ratio(dynamics, forces).min(axis=0)
    for _ in range(MAX_PASSES if options.contact == "piecewise" else 0):
        touching = in_contact(dynamics, response.displacement, error)
        if not touching[:-1].any(axis=0).all():
            lost = [i for i in range(touching.shape[1]) if not touching[:-1, i].any()]
            raise ValueError(f"contact loss: mesh spring(s) {lost} never touch over a "
                             f"revolution (a planet without load); allowed: errors and "
                             f"transmission error smaller than the static mesh deflection "
                             f"({np.abs(dynamics.preload).min():.3g} m), or [signal] "
                             f"contact = \"linear\"")
        if (contact is None and touching.all()) or (contact is not None
                                                    and np.array_equal(touching, contact)):
            break
        contact = touching
        try:
            state, loads, response, forces, error, y0 = run(per_rev, contact)
        except ValueError as exc:
            raise ValueError(
                f"contact loss: with the separated meshes {_lost(contact)} the model has no "
                f"damped steady state (a planet unloads: static mesh forces "
                f"{np.round(dynamics.static_force, 1).tolist()} N); allowed: smaller "
                f"[signal] planet_position_errors_m or a larger sun_torque_N_m") from exc
    else:
        if options.contact == "piecewise":
            raise ValueError(f"contact loss: the separation pattern did not settle in "
                             f"{MAX_PASSES} passes (the meshes separate for long; lower "
                             f"[signal] planet_position_errors_m or raise sun_torque_N_m)")
    if revolutions > 1:
        state, loads, response, forces, error, _ = run(per_rev * revolutions, contact, y0)
    ring = acceleration(dynamics.system, loads, response, [RING_X, RING_Y])
    separated = np.zeros(2 * params.n_planets) if contact is None else \
        1.0 - contact[:-1].mean(axis=0)
    return Simulation(dynamics, speed, per_rev, state, response, forces, ring, linear_min,
                      separated)


def _lost(contact: np.ndarray) -> list[str]:
    names = mesh_names(contact.shape[1] // 2)
    return [names[j] for j in range(contact.shape[1]) if not contact[:, j].all()]


def _error(state: MeshState, base_pitch: float, amplitude: float,
           runout: np.ndarray | None) -> np.ndarray | None:
    """Every mesh deflection error [m]: first-harmonic transmission error plus run-out."""
    out = transmission_error_of(state, base_pitch, amplitude) if amplitude else None
    if runout is not None:
        out = runout if out is None else out + runout
    return out


def _roll(runout: np.ndarray | None, n_planets: int) -> np.ndarray | None:
    """Roll shift of each ring contact from the run-out error: the ring's tooth moved by
    ``d`` moves the contact by ``g . d = -e`` along the line of action [m]."""
    return None if runout is None else -runout[:, n_planets:]
