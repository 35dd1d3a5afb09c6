"""Coupled modes followed from one ring state to another (over crack depth).

The two rings have different meshes, so modes are compared on what both share: the
lumped DOFs (mass-weighted) and the ring's displacement on its mid-rim circle (weighted by
the ring's mass per probe point).  A repeated frequency of the reference is one subspace:
a mode of the other state matches it by the share of its descriptor inside that subspace
(near-degenerate pairs rotate freely within it, so a mode-to-mode MAC would not hold).
The assignment maximises the summed match (Hungarian algorithm).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from .content import PAIR_RTOL, frequency_groups


@dataclass(frozen=True)
class Tracked:
    """For each mode of the other state: the reference mode it continues (0-based index,
    -1 when unmatched), the match in [0, 1], and whether it is a member of a reference
    pair whose members now differ by more than ``PAIR_RTOL`` (a split pair)."""

    reference: tuple
    match: tuple
    split_pair: tuple


def descriptors(spectrum, ring_mass: float, stride: int = 1) -> np.ndarray:
    """(features, modes): sqrt(m) x for the lumped DOFs, then the mid-rim displacements
    scaled so that their squares sum to the ring's kinetic energy of a uniform motion;
    ``stride``: every stride-th probe point only (a lighter descriptor, for storing)."""
    modes = spectrum.modes
    lumped = np.sqrt(modes.lumped_mass)[:, None] * modes.lumped
    points = modes.probe.shape[0] // 2
    probe = np.vstack([modes.probe[:points:stride], modes.probe[points::stride]])
    probe = probe * np.sqrt(ring_mass / (probe.shape[0] / 2))
    return np.vstack([lumped, probe])


def track_modes(reference, other, ring_mass: float, rtol: float = PAIR_RTOL) -> Tracked:
    """Which reference mode each mode of ``other`` continues (``ElasticSpectrum`` both)."""
    return track_descriptors(descriptors(reference, ring_mass), reference.frequency_hz,
                             descriptors(other, ring_mass), other.frequency_hz, rtol)


def track_descriptors(a: np.ndarray, f_ref: np.ndarray, b: np.ndarray, f: np.ndarray,
                      rtol: float = PAIR_RTOL) -> Tracked:
    """``track_modes`` on stored descriptors: ``a`` (features, reference modes) at
    frequencies ``f_ref`` [Hz], ``b`` (features, modes) at ``f`` [Hz]."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    f_ref, f = np.asarray(f_ref, dtype=float), np.asarray(f, dtype=float)
    b_norm = np.linalg.norm(b, axis=0)
    score = np.zeros((a.shape[1], b.shape[1]))
    for group in frequency_groups(f_ref, rtol):
        q, _ = np.linalg.qr(a[:, group])
        share = np.linalg.norm(q.T @ b, axis=0) ** 2 / np.where(b_norm > 0, b_norm, 1) ** 2
        score[group] = share
    rows, cols = linear_sum_assignment(-score)
    ref = np.full(b.shape[1], -1)
    match = np.zeros(b.shape[1])
    ref[cols] = rows
    match[cols] = score[rows, cols]
    # a repeated frequency's members are interchangeable: its lower continuation is named
    # after its first member, the upper after the second
    for group in frequency_groups(f_ref, rtol):
        members = np.flatnonzero(np.isin(ref, group))
        if members.size >= 2:
            ordered = members[np.argsort(f[members], kind="stable")]
            ref[ordered] = np.sort(ref[members])  # the match is the group's: unchanged
    split = np.zeros(b.shape[1], dtype=bool)
    for group in frequency_groups(f_ref, rtol):
        if group.size < 2:
            continue
        members = np.flatnonzero(np.isin(ref, group))
        if members.size >= 2 and np.ptp(f[members]) > rtol * f[members].mean():
            split[members] = True
    return Tracked(tuple(int(r) for r in ref), tuple(float(m) for m in match),
                   tuple(bool(s) for s in split))
