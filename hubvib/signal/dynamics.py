"""The lumped planetary model in time: mean-stiffness system, mesh preload, mesh excitation (SI).

Coordinates and springs are those of :func:`hubvib.lumped.network.spring_network`.
Each sun-planet and ring-planet mesh spring ``j`` varies in time,
``k_j(t) = kbar_j + dk_j(t)``, from the mesh curves at its place in the mesh cycle
(:mod:`hubvib.signal.mesh_phase`); all other springs are constant.

Load: the input torque ``T_s`` enters through the sun's torsional spring ``c_su``
(its far end is the motor, turning at constant speed), the output through the
carrier's ``c_cu`` (far end: the wheel) and the ring's ``c_ru`` holds the ring, so
each mesh carries ``T_s / (N r_bs)`` at equal load sharing.  With ``q0`` the static
state of the mean system, ``x = q - q0`` obeys

    M x'' + C x' + K(t) x = -sum_j dk_j(t) delta_j g_j + sum_j k_j(t) e_j(t) g_j,

``delta_j = g_j . q0`` the static mesh deflection, ``e_j`` an optional static
transmission error plus the run-out errors of :mod:`hubvib.signal.manufacturing`; pin-hole
errors of the planets pre-deform their bearings and enter ``q0`` (the static load
sharing).  Damping is modal: ``C = M Phi diag(2 zeta omega) Phi^T M``
with the mass-normalised modes of the mean system.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.lumped import PlanetaryParameters, natural_modes, spring_network
from hubvib.lumped.network import mass_diagonal

from .manufacturing import StageErrors, error_load
from .mesh_curves import MeshCurves
from .mesh_phase import MeshPhasing
from .time_response import Excitation, LinearSystem

SUN_ROTATION = 6  # index of u_s


@dataclass(frozen=True)
class PlanetaryDynamics:
    """Mean-stiffness system of one reducer at one load.

    Attributes
    ----------
    params : PlanetaryParameters
        Lumped parameters with the mean mesh stiffnesses of the curves [SI].
    system : LinearSystem
        Rows: the N sun-planet meshes, then the N ring-planet meshes.
    mean : ndarray (2N,)
        Mean mesh stiffnesses kbar [N/m].
    preload : ndarray (2N,)
        Static mesh deflections delta [m]; ``mean * preload`` are the static mesh forces.
    omega : ndarray
        Natural frequencies of the mean system [rad/s].
    damping_ratio : float
        Modal damping ratio [-].
    """

    params: PlanetaryParameters
    system: LinearSystem
    mean: np.ndarray
    preload: np.ndarray
    omega: np.ndarray
    damping_ratio: float

    @property
    def n_planets(self) -> int:
        return self.params.n_planets

    @property
    def static_force(self) -> np.ndarray:
        """Static mesh forces [N] (sun meshes, then ring meshes)."""
        return self.mean * self.preload


def planetary_dynamics(params: PlanetaryParameters, curves: MeshCurves, damping_ratio: float,
                       sun_torque: float, errors: StageErrors | None = None) -> PlanetaryDynamics:
    """Assemble the mean system with modal damping and the static preload.

    Parameters
    ----------
    params : PlanetaryParameters
        The reducer; ``c_sp``, ``c_rp`` and ``c_rp_factors`` are replaced by the
        curves' intact means.
    curves : MeshCurves
        Mesh stiffness curves [N/m].
    damping_ratio : float
        Modal damping ratio [-], in [0, 1).
    sun_torque : float
        Input torque on the sun [N m], > 0.
    errors : StageErrors, optional
        Pin-hole errors pre-deform the planet bearings (static state, load sharing).
    """
    if not 0 <= damping_ratio < 1:
        raise ValueError(f"damping_ratio = {damping_ratio!r}; allowed: [0, 1)")
    if not (math.isfinite(sun_torque) and sun_torque > 0):
        raise ValueError(f"sun_torque = {sun_torque!r}; allowed: > 0 [N m]")
    params = params.replace(c_sp=curves.sun_mean, c_rp=curves.ring_mean, c_rp_factors=())
    network = spring_network(params)
    sun = np.flatnonzero(np.array(network.parameter) == "c_sp")
    ring = np.flatnonzero(np.array(network.parameter) == "c_rp")
    order = np.concatenate([sun, ring])
    rows, mean = network.G[order], network.k[order]
    K = network.stiffness_matrix()
    mass = mass_diagonal(params)
    spectrum = natural_modes(params)
    if spectrum.n_rigid:
        raise ValueError("the time model needs every member held (c_su, c_cu, c_ru > 0): "
                         f"{spectrum.n_rigid} rigid-body mode(s)")
    Phi = spectrum.shapes
    MPhi = mass[:, None] * Phi
    C = MPhi @ np.diag(2 * damping_ratio * spectrum.omega) @ MPhi.T
    C = 0.5 * (C + C.T)
    # torque through the sun's torsional spring: its far end (the motor) is moved until
    # the spring carries T_s / r_bs; the carrier's and ring's far ends stay put
    unit = np.linalg.solve(K, np.eye(K.shape[0])[SUN_ROTATION])
    transmitted = 1.0 - params.c_su * unit[SUN_ROTATION]
    q0 = (sun_torque / (params.d_s / 2)) / transmitted * unit
    if errors is not None and errors.any():
        q0 = q0 + np.linalg.solve(K, error_load(params, errors))
    return PlanetaryDynamics(params, LinearSystem(mass, C, K, rows), mean, rows @ q0,
                             spectrum.omega, float(damping_ratio))


@dataclass(frozen=True)
class MeshState:
    """Every mesh at the step times: stiffness [N/m] and roll length on the planet [m].

    Columns: the N sun meshes, then the N ring meshes.
    """

    stiffness: np.ndarray
    roll: np.ndarray


def mesh_state(dynamics: PlanetaryDynamics, curves: MeshCurves, phasing: MeshPhasing,
               carrier_angle: np.ndarray, crack_tooth: int | None,
               planet_shift: np.ndarray | None = None,
               ring_roll_shift: np.ndarray | None = None) -> MeshState:
    """Mesh stiffnesses at carrier angles ``carrier_angle`` [rad] (planet i at
    ``theta_i + carrier_angle``, plus ``planet_shift[i]`` [rad] in its mesh cycles);
    ``crack_tooth`` is the cracked ring tooth (or None); ``ring_roll_shift``
    (steps, N) [m] moves each ring contact along its line of action (ring run-out) and
    the planet's sun contact as much back (the roll sum of a rigid planet stays)."""
    angles = np.array(dynamics.params.theta)
    if planet_shift is not None:
        angles = angles + planet_shift
    theta = np.asarray(carrier_angle)[:, None] + angles[None, :]
    s_ring = phasing.ring_roll(theta)
    s_sun = phasing.sun_roll(theta)
    s_cracked = None if crack_tooth is None else phasing.ring_roll(theta, crack_tooth)
    if ring_roll_shift is not None:
        s_ring, s_sun = s_ring + ring_roll_shift, s_sun - ring_roll_shift
        s_cracked = None if s_cracked is None else s_cracked + ring_roll_shift
    k_sun = curves.sun(s_sun)
    k_ring = curves.ring(s_ring, s_cracked)
    return MeshState(np.hstack([k_sun, k_ring]), np.hstack([s_sun, s_ring]))


def excitation(dynamics: PlanetaryDynamics, state: MeshState, base_pitch: float,
               transmission_error: float = 0.0, mesh_error: np.ndarray | None = None
               ) -> Excitation:
    """Right-hand side of the equation in the module docstring, per step;
    ``mesh_error`` (steps + 1, 2N) [m] adds to the transmission error."""
    dk = state.stiffness - dynamics.mean[None, :]
    r = -dk * dynamics.preload[None, :]
    if transmission_error:
        r = r + state.stiffness * transmission_error_of(state, base_pitch, transmission_error)
    if mesh_error is not None:
        r = r + state.stiffness * mesh_error
    return Excitation(dk, r)


def transmission_error_of(state: MeshState, base_pitch: float, amplitude: float) -> np.ndarray:
    """First-harmonic static transmission error of every mesh [m]: a cos(2 pi s / p_b)."""
    return amplitude * np.cos(2 * np.pi * state.roll / base_pitch)


def mesh_forces(dynamics: PlanetaryDynamics, state: MeshState, displacement: np.ndarray,
                base_pitch: float, transmission_error: float = 0.0,
                mesh_error: np.ndarray | None = None) -> np.ndarray:
    """Dynamic part of every mesh force [N]: ``k_j (delta_j + g_j . x - e_j) - kbar_j delta_j``."""
    deflection = dynamics.preload[None, :] + displacement @ dynamics.system.rows.T
    if transmission_error:
        deflection = deflection - transmission_error_of(state, base_pitch, transmission_error)
    if mesh_error is not None:
        deflection = deflection - mesh_error
    return state.stiffness * deflection - dynamics.static_force[None, :]
