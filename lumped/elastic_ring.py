"""The planetary model with an elastic ring: the lumped sun, carrier and planets coupled to
a ring given by its own stiffness and mass (a reduced or a full FE ring), SI units.

The ring's three rigid coordinates x_r, y_r, u_r and their springs c_r, c_ru leave the
9 + 3N model: the ring's mounting is in its own matrices.  Planet i meshes with ring tooth
``k_i``; the mesh spring's deformation is

    delta_i = e_i . (u_ring(P_i) - u_planet centre) + u_i,      e_i = s_i d_i,

``u_ring(P_i) = s_i b_{k_i}^T u`` the mean displacement of the tooth's load patch along
its line of action ``d_i`` (``b`` the ring's contact functional), ``s_i = +-1`` chosen so
that a rigid ring rotation ``phi`` gives ``-r_b phi`` (the lumped model's ``-u_r``).  For a
rigid ring this is the lumped ring-planet spring exactly.  The planet's angle is the polar
angle of its tooth's load point (on the working pitch circle): the line of action of the
planet at that angle passes through it.  The spring ``k_rest`` carries what the ring body
does not: the planet tooth and the contact (the ring tooth and rim deform in the ring).

Only numpy and scipy: the ring comes in as matrices (``RingOperators``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from .network import dof_names, mass_diagonal, spring_network
from .parameters import ParameterError, PlanetaryParameters

RING_DOFS = (4, 5, 8)  # x_r, y_r, u_r of the 9 + 3N model
RING_SPRINGS = ("c_r", "c_ru", "c_rp")


@dataclass(frozen=True, eq=False)
class RingOperators:
    """A ring as the coupled model sees it (dense reduced or sparse full).

    Attributes
    ----------
    K, M : ndarray or sparse (n, n)
        Stiffness with its mounting [N/m] and mass [kg].
    contact : ndarray or sparse (n, z)
        Column k: tooth k's contact functional (patch mean along the line of action) [-].
    moment_sign : ndarray (z,)
        ``s_k``: +-1 so that ``s_k contact[:, k]`` reads ``-r_b phi`` for a rigid rotation.
    patch_angles : ndarray (z,)
        Polar angle of each tooth's load point [rad].
    directions : ndarray (z, 2)
        Line of action of each tooth's load [-].
    probe : ndarray or sparse (2 P, n)
        Radial then tangential displacement on the ring's mid-rim circle at P equally
        spaced angles [m per unit coordinate].
    """

    K: object
    M: object
    contact: object
    moment_sign: np.ndarray
    patch_angles: np.ndarray
    directions: np.ndarray
    probe: object

    @property
    def size(self) -> int:
        return self.K.shape[0]

    @property
    def teeth(self) -> int:
        return len(self.patch_angles)


@dataclass(frozen=True)
class Engagement:
    """Which ring tooth each planet meshes with, and the planets' angles there [rad]."""

    teeth: tuple
    theta: tuple


def engagement(params: PlanetaryParameters, ring: RingOperators, carrier_tooth: int
               ) -> Engagement:
    """Planet 1 on tooth ``carrier_tooth``; every other planet on the tooth whose load point
    lies nearest its angle with the carrier turned so (``theta`` snapped to those points)."""
    z = ring.teeth
    if isinstance(carrier_tooth, bool) or not isinstance(carrier_tooth, (int, np.integer)) or not (
            0 <= carrier_tooth < z):
        raise ParameterError(f"carrier_tooth = {carrier_tooth!r}, allowed 0..{z - 1}")
    turn = ring.patch_angles[carrier_tooth] - params.theta[0]
    teeth = []
    for theta in params.theta:
        gap = np.angle(np.exp(1j * (ring.patch_angles - (theta + turn))))
        teeth.append(int(np.argmin(np.abs(gap))))
    if len(set(teeth)) < len(teeth):
        raise ParameterError(f"two planets mesh with one ring tooth ({teeth}): the ring has "
                             f"too few teeth for {len(teeth)} planets")
    return Engagement(tuple(teeth), tuple(float(ring.patch_angles[k]) for k in teeth))


@dataclass(frozen=True, eq=False)
class CoupledMatrices:
    """``K``, ``M`` of the coupled model: ring coordinates first, then the lumped DOFs
    ``lumped_names`` (the 9 + 3N model without x_r, y_r, u_r)."""

    K: object
    M: object
    n_ring: int
    lumped_names: tuple
    lumped_mass: np.ndarray
    engagement: Engagement


def coupled_matrices(params: PlanetaryParameters, ring: RingOperators, carrier_tooth: int,
                     k_rest: float) -> CoupledMatrices:
    """Assemble the coupled model (sparse if the ring is, dense otherwise).

    ``k_rest`` [N/m]: the ring-planet spring without the ring body (``c_rp_factors`` scale
    it per planet, as in the lumped model)."""
    if not (math.isfinite(k_rest) and k_rest > 0):
        raise ParameterError(f"k_rest = {k_rest!r} N/m, allowed > 0")
    eng = engagement(params, ring, carrier_tooth)
    snapped = params.replace(theta=eng.theta)
    network = spring_network(snapped)
    n_full = snapped.n_dof
    keep = np.array([i for i in range(n_full) if i not in RING_DOFS])
    rows = [j for j, p in enumerate(network.parameter) if p not in RING_SPRINGS]
    G = network.G[np.ix_(rows, keep)]
    k = network.k[rows]
    K_lumped = G.T @ (k[:, None] * G)
    n_ring, n_l = ring.size, keep.size
    factors = snapped.c_rp_factors or (1.0,) * snapped.n_planets
    signs = ring.moment_sign[list(eng.teeth)]
    B = ring.contact[:, list(eng.teeth)]
    coupling_ring = (sp.csr_matrix(B) @ sp.diags(signs)).tocsr() if sp.issparse(B) else (
        np.asarray(B) * signs[None, :])  # (n_ring, N)
    coupling_lumped = lumped_coupling(ring, eng.teeth, eng.theta,
                                      np.array(dof_names(snapped.n_planets))[keep])
    stiff = k_rest * np.asarray(factors, dtype=float)
    if sp.issparse(coupling_ring):
        weighted = coupling_ring @ sp.diags(stiff)
        K_rr, K_rl = weighted @ coupling_ring.T, weighted @ sp.csr_matrix(coupling_lumped.T)
    else:
        K_rr = (coupling_ring * stiff) @ coupling_ring.T
        K_rl = (coupling_ring * stiff) @ coupling_lumped.T
    K_ll = K_lumped + (coupling_lumped * stiff) @ coupling_lumped.T
    mass = mass_diagonal(snapped)[keep]
    if sp.issparse(ring.K):
        K = sp.bmat([[ring.K + K_rr, K_rl], [K_rl.T, sp.csr_matrix(K_ll)]]).tocsr()
        M = sp.block_diag([ring.M, sp.diags(mass)]).tocsr()
    else:
        K = np.block([[np.asarray(ring.K) + K_rr, K_rl], [K_rl.T, K_ll]])
        K = 0.5 * (K + K.T)
        M = sla.block_diag(np.asarray(ring.M), np.diag(mass))
    names = tuple(np.array(dof_names(snapped.n_planets))[keep])
    return CoupledMatrices(K, M, n_ring, names, mass, eng)


def lumped_coupling(ring: RingOperators, teeth, theta, names) -> np.ndarray:
    """The lumped end of each ring-planet mesh deformation, (len(names), N): planet i on
    ring tooth ``teeth[i]`` at angle ``theta[i]`` [rad]; ``names`` the lumped DOFs' names
    (the 9 + 3N model's without the ring's)."""
    index = {name: i for i, name in enumerate(names)}
    out = np.zeros((len(names), len(teeth)))
    for i, (tooth, angle) in enumerate(zip(teeth, theta)):
        e = ring.moment_sign[tooth] * ring.directions[tooth]
        radial = np.array([math.cos(angle), math.sin(angle)])
        tangential = np.array([-math.sin(angle), math.cos(angle)])
        out[index[f"tau_{i + 1}"], i] = -e @ tangential
        out[index[f"eta_{i + 1}"], i] = -e @ radial
        out[index[f"u_{i + 1}"], i] = 1.0
    return out


@dataclass(frozen=True, eq=False)
class CoupledModes:
    """Natural modes of the coupled model.

    Attributes
    ----------
    omega : ndarray
        [rad/s], ascending.
    ring : ndarray (n_ring, m)
        Ring coordinates of each mass-normalised mode.
    lumped : ndarray (n_lumped, m)
        The lumped DOFs (``lumped_names``) [m/sqrt(kg)].
    ring_kinetic : ndarray (m,)
        Share of each mode's kinetic energy in the ring [-].
    probe : ndarray (2 P, m)
        Radial, then tangential ring displacement on the mid-rim circle [m/sqrt(kg)].
    """

    omega: np.ndarray
    ring: np.ndarray
    lumped: np.ndarray
    lumped_names: tuple
    lumped_mass: np.ndarray
    ring_kinetic: np.ndarray
    probe: np.ndarray
    engagement: Engagement

    @property
    def frequency_hz(self) -> np.ndarray:
        return self.omega / (2 * np.pi)


def coupled_modes(params: PlanetaryParameters, ring: RingOperators, carrier_tooth: int,
                  k_rest: float, max_hz: float | None = None, count: int | None = None
                  ) -> CoupledModes:
    """Modes of the coupled model below ``max_hz`` [Hz] (a dense ring: all of them when
    None) or the lowest ``count`` (a sparse ring: shift-invert Lanczos)."""
    mats = coupled_matrices(params, ring, carrier_tooth, k_rest)
    if sp.issparse(mats.K):
        values, vectors = _sparse_eigen(mats, max_hz, count)
    else:
        values, vectors = sla.eigh(mats.K, mats.M)
        if max_hz is not None:
            keep = values <= (2 * np.pi * max_hz) ** 2
            values, vectors = values[keep], vectors[:, keep]
        if count is not None:
            values, vectors = values[:count], vectors[:, :count]
    scale = np.sqrt(np.einsum("ij,ij->j", vectors, mats.M @ vectors))
    vectors = vectors / scale
    ring_part, lumped_part = vectors[:mats.n_ring], vectors[mats.n_ring:]
    ring_energy = np.einsum("ij,ij->j", ring_part, _top_left(mats.M, mats.n_ring) @ ring_part)
    probe = ring.probe @ ring_part
    return CoupledModes(np.sqrt(np.clip(values, 0.0, None)), ring_part, lumped_part,
                        mats.lumped_names, mats.lumped_mass, ring_energy, np.asarray(probe),
                        mats.engagement)


def _top_left(M, n):
    """The ring block of the coupled mass matrix."""
    return M[:n, :n]


def _sparse_eigen(mats: CoupledMatrices, max_hz, count):
    import scipy.sparse.linalg as spla

    count = count or 30
    sigma = -1e4  # K may have rigid-body modes (a floating sun with c_su = 0)
    values, vectors = spla.eigsh(mats.K, k=count, M=mats.M, sigma=sigma, which="LM",
                                 v0=np.ones(mats.K.shape[0]))
    order = np.argsort(values)
    values, vectors = values[order], vectors[:, order]
    if max_hz is not None:
        keep = values <= (2 * np.pi * max_hz) ** 2
        values, vectors = values[keep], vectors[:, keep]
    return values, vectors


def rigid_ring_parameters(params: PlanetaryParameters, rigid_mass: np.ndarray,
                          rigid_stiffness: np.ndarray, base_radius: float, k_rest: float,
                          engaged: Engagement) -> PlanetaryParameters:
    """The 9 + 3N model of the same system with the ring rigid: its mass and mounting from
    the ring body's rigid motions (3 x 3, x, y, rotation), ``c_rp = k_rest``, the planets
    at the engaged angles."""
    return replace(params.replace(
        m_r=float(0.5 * (rigid_mass[0, 0] + rigid_mass[1, 1])),
        mu_r=float(rigid_mass[2, 2] / base_radius ** 2),
        c_r=float(0.5 * (rigid_stiffness[0, 0] + rigid_stiffness[1, 1])),
        c_ru=float(rigid_stiffness[2, 2] / base_radius ** 2),
        c_rp=float(k_rest), theta=engaged.theta))
