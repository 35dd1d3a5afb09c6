"""The elastic-ring planetary model prepared for time integration, one state per carrier
position (SI).

The coupled model of :mod:`hubvib.lumped.elastic_ring` (reduced FE ring + lumped sun,
carrier, planets) changes as the carrier turns in two ways:

* the planets' ring contacts move around the FE ring: with planet 1 nearest ring tooth
  ``p`` (the *carrier position*), every planet meshes with the tooth
  :func:`hubvib.lumped.elastic_ring.engagement` gives, and the contact switches to the next
  position half way between two load points; the ring's own stiffness may depend on the
  position too (``ring_stiffness``: a crack whose faces close under some positions' load);
* every sun-planet and ring-planet mesh stiffness varies over its mesh cycle (the signal
  route's mesh curves, ``"ratio"`` scaling: the sun's mean is the lumped ``c_sp``, the
  ring's the rest spring ``k_rest`` of the elastic model, which leaves out the ring body).

Per position ``p`` this module keeps the mean system's mass-normalised modes ``Phi_p``,
frequencies, static state ``q0_p`` under the sun torque and the mesh rows in modal
coordinates; within a position the system is ``diag(omega_p^2) + sum_j dk_j(t) g_j g_j^T``
(rank 2N), so the natural frequencies of every position are those of the coupled model
there, exactly.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla

from hubvib.lumped.elastic_ring import (RingOperators, coupled_matrices, engagement,
                                        lumped_coupling)
from hubvib.lumped.network import dof_names, spring_network
from hubvib.lumped.parameters import PlanetaryParameters

#: the lumped coordinates the ambient forces act on (sun and carrier)
CENTRAL = ("x_s", "y_s", "x_c", "y_c", "u_s", "u_c")


@dataclass(frozen=True, eq=False)
class ElasticTimeModel:
    """The coupled model at every carrier position, in its modal coordinates.

    Attributes
    ----------
    omega : ndarray (z, n)
        Natural frequencies of each position's mean system [rad/s], ascending.
    kept : int
        Modes integrated in time (the lowest); the others respond quasi-statically.
    damping_ratio : float
        Modal damping of every mode [-].
    shapes : ndarray (z, n, n)
        Mass-normalised modes of each position [m/sqrt(kg) per unit].
    mass : ndarray (n,)
        Diagonal of the coupled mass matrix [kg] (ring coordinates: 1).
    static : ndarray (z, n)
        Static state of each position under the sun torque [m].
    rows : ndarray (z, 2N, n)
        Modal rows of the sun-planet, then ring-planet meshes [m per unit].
    preload : ndarray (z, 2N)
        Static mesh deflections ``g_j . q0_p`` [m].
    mean : ndarray (2N,)
        Mean mesh stiffnesses [N/m].
    central : ndarray (z, 6, n)
        Modal rows of the sun's and carrier's x, y, u (``CENTRAL``).
    probe : ndarray (2 P, n_ring)
        The ring's radial, then tangential mid-rim displacement at P angles [m per unit].
    n_ring : int
    patch_angles : ndarray (z,)
        Polar angle of each ring tooth's load point [rad].
    theta : ndarray (N,)
        Planet angles at carrier angle 0 [rad].
    """

    omega: np.ndarray
    kept: int
    damping_ratio: float
    shapes: np.ndarray
    mass: np.ndarray
    static: np.ndarray
    rows: np.ndarray
    preload: np.ndarray
    mean: np.ndarray
    central: np.ndarray
    probe: np.ndarray
    n_ring: int
    patch_angles: np.ndarray
    theta: np.ndarray

    @property
    def modes(self) -> int:
        """Modes integrated in time."""
        return self.kept

    @property
    def n_planets(self) -> int:
        return self.theta.size

    @property
    def teeth(self) -> int:
        return self.patch_angles.size

    def frequency_hz(self, position: int) -> np.ndarray:
        """The kept modes' frequencies at a carrier position [Hz]."""
        return self.omega[position, :self.kept] / (2 * math.pi)

    def sensor_rows(self, angle: float) -> np.ndarray:
        """Per position, the modal row of the ring's radial displacement at polar angle
        ``angle`` [rad] (linear between the two nearest probe points), (z, n)."""
        points = self.probe.shape[0] // 2
        position = (angle % (2 * math.pi)) / (2 * math.pi) * points
        low = int(math.floor(position)) % points
        w = position - math.floor(position)
        row = (1 - w) * self.probe[low] + w * self.probe[(low + 1) % points]
        return np.einsum("r,zrm->zm", row, self.shapes[:, :self.n_ring])


def mesh_rows(params: PlanetaryParameters, ring: RingOperators, position: int) -> np.ndarray:
    """Physical rows (2N, n) of the sun-planet, then ring-planet meshes with planet 1 on
    ring tooth ``position`` (ring coordinates first, as ``coupled_matrices`` orders them)."""
    eng = engagement(params, ring, position)
    snapped = params.replace(theta=eng.theta)
    network = spring_network(snapped)
    full = dof_names(snapped.n_planets)
    names = [name for i, name in enumerate(full) if i not in (4, 5, 8)]
    keep = [full.index(name) for name in names]
    sun = network.G[[j for j, p in enumerate(network.parameter) if p == "c_sp"]][:, keep]
    n_ring = ring.size
    rows = np.zeros((2 * params.n_planets, n_ring + len(names)))
    rows[:params.n_planets, n_ring:] = sun
    contact = np.asarray(ring.contact)[:, list(eng.teeth)] * ring.moment_sign[list(eng.teeth)]
    rows[params.n_planets:, :n_ring] = contact.T
    rows[params.n_planets:, n_ring:] = lumped_coupling(ring, eng.teeth, eng.theta, names).T
    return rows


def elastic_time_model(params: PlanetaryParameters, ring: RingOperators, k_rest: float,
                       damping_ratio: float, sun_torque: float, keep_hz: float,
                       ring_stiffness=None) -> ElasticTimeModel:
    """Prepare the coupled model (dense ``ring``, ``M = I``, its ``contact`` serving every
    tooth) at every carrier position.

    Parameters
    ----------
    params : PlanetaryParameters
        The lumped bodies; ``c_sp`` is the sun mesh's mean stiffness [N/m].
    ring : RingOperators
    k_rest : float
        Mean ring-planet spring without the ring body [N/m].
    damping_ratio : float
        Modal damping [-], in (0, 1).
    sun_torque : float
        Input torque on the sun [N m] (the static mesh deflections).
    keep_hz : float
        Modes integrated in time up to this frequency [Hz] (counted at position 0); the
        higher ones respond quasi-statically.
    ring_stiffness : sequence of ndarray, callable or None
        Reduced ring stiffness per carrier position ``p = 0 .. z - 1`` [N/m]: a list, or
        ``ring_stiffness(p)``; None: the ring's own ``K`` at every position.
    """
    if not 0 < damping_ratio < 1:
        raise ValueError(f"damping_ratio = {damping_ratio!r}; allowed: (0, 1)")
    if not (math.isfinite(sun_torque) and sun_torque > 0):
        raise ValueError(f"sun_torque = {sun_torque!r} N m; allowed: > 0")
    from hubvib.foundation.blas import blas_threads

    with blas_threads(1):  # many small dense problems: threads only contend
        return _time_model(params, ring, k_rest, damping_ratio, sun_torque, keep_hz,
                           ring_stiffness)


def _time_model(params, ring, k_rest, damping_ratio, sun_torque, keep_hz, ring_stiffness):
    get = None
    if ring_stiffness is not None:
        get = ring_stiffness if callable(ring_stiffness) else (lambda p: ring_stiffness[p])
    z = ring.teeth
    omega, shapes, static, rows, central = [], [], [], [], []
    mass = None
    for p in range(z):
        ring_p = ring if get is None else replace(ring, K=np.asarray(get(p)))
        mats = coupled_matrices(params, ring_p, p, k_rest)
        K, M = np.asarray(mats.K), np.asarray(mats.M)
        values, vectors = sla.eigh(K, M)
        if values[0] <= 0:
            raise ValueError("the coupled model has a rigid-body mode: every member must be "
                             "held (c_su, c_cu > 0)")
        vectors = vectors / np.sqrt(np.einsum("ij,ij->j", vectors, M @ vectors))
        # sign: the largest entry of each mode positive (repeatable shapes)
        big = np.argmax(np.abs(vectors), axis=0)
        vectors = vectors * np.sign(vectors[big, np.arange(vectors.shape[1])])
        names = mats.lumped_names
        sun = mats.n_ring + names.index("u_s")
        unit = sla.solve(K, np.eye(K.shape[0])[sun], assume_a="sym")
        transmitted = 1.0 - params.c_su * unit[sun]
        q0 = (sun_torque / (params.d_s / 2)) / transmitted * unit
        physical = mesh_rows(params, ring_p, p)
        omega.append(np.sqrt(values))
        shapes.append(vectors)
        static.append(q0)
        rows.append(physical)
        central.append(vectors[[mats.n_ring + names.index(n) for n in CENTRAL]])
        mass = np.diag(M).copy()
    omega, shapes, static = np.array(omega), np.array(shapes), np.array(static)
    physical = np.array(rows)
    preload = np.einsum("zjn,zn->zj", physical, static)
    N = params.n_planets
    kept = int(np.count_nonzero(omega[0] <= 2 * math.pi * keep_hz))
    return ElasticTimeModel(
        omega, kept, float(damping_ratio), shapes, mass, static,
        np.einsum("zjn,znm->zjm", physical, shapes), preload,
        np.concatenate([np.full(N, float(params.c_sp)), np.full(N, float(k_rest))]),
        np.array(central), np.asarray(ring.probe), ring.size,
        np.asarray(ring.patch_angles, dtype=float), np.asarray(params.theta, dtype=float))


def carrier_position(model: ElasticTimeModel, carrier_angle) -> np.ndarray:
    """Ring tooth whose load point is nearest planet 1 at each carrier angle [rad]."""
    return carrier_offset(model, carrier_angle)[0]


def carrier_offset(model: ElasticTimeModel, carrier_angle) -> tuple[np.ndarray, np.ndarray]:
    """The carrier position (:func:`carrier_position`) and planet 1's angle past its load
    point in tooth pitches, in [-1/2, 1/2)."""
    a = model.patch_angles
    pitch = 2 * math.pi / a.size
    position = ((model.theta[0] + np.asarray(carrier_angle) - a[0]) % (2 * math.pi)) / pitch
    nearest = np.floor(position + 0.5)
    return nearest.astype(int) % a.size, position - nearest
