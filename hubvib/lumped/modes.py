"""Grouping of repeated frequencies, canonical mode shapes and mode types.

Mode types for equally spaced planets follow Lin & Parker (J. Sound Vib. 1999):
*rotational* (central members only rotate; single), *translational* (central
members only translate; double), *planet* (central members at rest;
multiplicity N - 3).  Unequal spacing mixes them: ``"mixed"``.
"""
from __future__ import annotations

import numpy as np

from .network import CENTRAL_ROTATIONS, CENTRAL_TRANSLATIONS

FREQUENCY_RTOL = 1e-7  # relative gap below which two frequencies are one repeated frequency
ENERGY_TOL = 1e-8  # kinetic-energy fraction below which a member counts as at rest


def clusters(omega: np.ndarray, n_rigid: int) -> list[np.ndarray]:
    """Index groups of (numerically) equal frequencies; rigid modes form one group."""
    groups = [np.arange(n_rigid)] if n_rigid else []
    start = n_rigid
    for i in range(n_rigid + 1, omega.size + 1):
        if i == omega.size or omega[i] - omega[i - 1] > FREQUENCY_RTOL * omega[i]:
            groups.append(np.arange(start, i))
            start = i
    return groups


def canonical_basis(W: np.ndarray) -> np.ndarray:
    """Basis-independent orthonormal basis of span(W), W with orthonormal columns.

    Built from the projector ``P = W W^T``, which does not depend on the basis
    an eigensolver happened to return: pick the coordinate with the largest
    ``P_jj`` (lowest index among near-ties), take ``P e_j`` normalised, deflate,
    repeat.  Each vector has a positive component at its chosen coordinate, so
    the sign is fixed as well.
    """
    P = W @ W.T
    basis = []
    for _ in range(W.shape[1]):
        d = np.diag(P)
        j = int(np.flatnonzero(d >= d.max() * (1 - 1e-9))[0])
        v = P[:, j] / np.sqrt(d[j])
        basis.append(v)
        P = P - np.outer(v, v)
    return np.array(basis).T


def mode_type(W: np.ndarray) -> str:
    """Type of the mode group whose mass-scaled shapes are the columns of W."""
    energy = (W**2).sum(axis=1) / W.shape[1]
    translation = energy[list(CENTRAL_TRANSLATIONS)].sum()
    rotation = energy[list(CENTRAL_ROTATIONS)].sum()
    if translation < ENERGY_TOL and rotation < ENERGY_TOL:
        return "planet"
    if translation < ENERGY_TOL:
        return "rotational"
    if rotation < ENERGY_TOL:
        return "translational"
    return "mixed"


def mac(phi_a: np.ndarray, phi_b: np.ndarray, mass: np.ndarray) -> np.ndarray:
    """Mass-weighted modal assurance criterion between all column pairs."""
    cross = phi_a.T @ (mass[:, None] * phi_b)
    norm_a = np.einsum("ij,ij->j", phi_a, mass[:, None] * phi_a)
    norm_b = np.einsum("ij,ij->j", phi_b, mass[:, None] * phi_b)
    return cross**2 / np.outer(norm_a, norm_b)
