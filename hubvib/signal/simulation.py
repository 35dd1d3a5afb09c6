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

from hubvib.lumped import PlanetaryParameters

from .dynamics import (MeshState, PlanetaryDynamics, excitation, mesh_forces, mesh_state,
                       planetary_dynamics)
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
    """

    dynamics: PlanetaryDynamics
    carrier_speed: float
    steps_per_revolution: int
    state: MeshState
    response: TimeResponse
    forces: np.ndarray
    ring_acceleration: np.ndarray

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
                             f"{mesh_period / 2:.4g} s (half a mesh period)")
        if options.integrator == "central" and options.time_step_s >= limit:
            raise ValueError(
                f"[signal] time_step_s = {options.time_step_s:g}; allowed: < {limit:.4g} s "
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
    dynamics = planetary_dynamics(params, curves, options.damping_ratio, options.sun_torque_N_m)
    speed = carrier_speed(options, phasing.ring_teeth, sun_teeth)
    per_rev = steps_per_revolution(float(dynamics.omega.max()), speed, phasing.ring_teeth,
                                   options, params.n_planets)
    h = 2 * math.pi / speed / per_rev
    tooth = crack_tooth if curves.cracked_s is not None else None
    one = mesh_state(dynamics, curves, phasing, speed * h * np.arange(per_rev + 1), tooth)
    te = options.transmission_error_m
    y0 = periodic_start(dynamics.system, h, excitation(dynamics, one, curves.base_pitch, te),
                        options.integrator)
    steps = per_rev * revolutions
    state = mesh_state(dynamics, curves, phasing, speed * h * np.arange(steps + 1), tooth)
    loads = excitation(dynamics, state, curves.base_pitch, te)
    response = integrate(dynamics.system, h, loads, scheme=options.integrator, y0=y0)
    forces = mesh_forces(dynamics, state, response.displacement, curves.base_pitch, te)
    ring = acceleration(dynamics.system, loads, response, [RING_X, RING_Y])
    return Simulation(dynamics, speed, per_rev, state, response, forces, ring)
