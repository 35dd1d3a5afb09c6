"""What a coupled mode is made of: the ring's nodal diameters, the harmonic index under
the planets' cyclic symmetry, its class and multiplicity.

For N equally spaced planets the system is invariant under turning by 2 pi / N, so every
mode belongs to one harmonic index p (0 <= p <= N/2, p and N - p together; Wu & Parker,
J. Vib. Acoust. 2008): the planets move as ``exp(i p 2 pi j / N)``, the central members
only rotate for p = 0 and only translate for p = 1, and the ring's nodal diameters are
``n = +-p mod N``.  Classes: *rotational* (p = 0), *translational* (p = 1), *planet*
(other p; the central members at rest), *ring* (the lumped bodies at rest), *mixed* (no
index holds ``CLASS_SHARE`` of the kinetic energy: unequal spacing, a tooth count that is
no multiple of N, or a crack).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: share of the kinetic energy one harmonic index must hold for the mode to be classed by it
CLASS_SHARE = 0.95
#: kinetic share of the lumped bodies below which a mode is a ring mode
RING_ONLY = 1e-3
#: relative gap below which two frequencies are one repeated frequency
PAIR_RTOL = 1e-3


@dataclass(frozen=True)
class ModeContent:
    """One coupled mode's make-up.

    Attributes
    ----------
    nodal_diameter : int
        The ring's dominant nodal-diameter count n on its mid-rim circle.
    diameter_shares : tuple of float
        Share of the ring's mid-rim displacement (u_r^2 + u_t^2) in n = 0, 1, 2, ...
        (up to ``len``) [-].
    ring_share : float
        Share of the kinetic energy in the ring [-].
    harmonic_index : int or None
        The dominant p (None when the planets are not equally spaced).
    harmonic_share : float
        Its share of the kinetic energy [-].
    kind : str
        'rotational', 'translational', 'planet', 'ring' or 'mixed'.
    """

    nodal_diameter: int
    diameter_shares: tuple
    ring_share: float
    harmonic_index: int | None
    harmonic_share: float
    kind: str


def diameter_content(probe_column: np.ndarray) -> np.ndarray:
    """Share of the mid-rim displacement in each nodal-diameter count n = 0 .. P/2."""
    half = probe_column.size // 2
    radial, tangential = probe_column[:half], probe_column[half:]
    power = np.abs(np.fft.rfft(radial)) ** 2 + np.abs(np.fft.rfft(tangential)) ** 2
    power[1:-1] *= 2  # +n and -n
    total = power.sum()
    return power / total if total > 0 else power


def is_elastic_ring_shape(probe_column: np.ndarray) -> bool:
    """Whether a ring displacement on the mid-rim circle is an elastic ring mode: dominant
    nodal diameters n >= 2, or n = 0 with radial motion (breathing; n = 0 tangential is a
    rigid rotation, n = 1 a rigid translation)."""
    content = diameter_content(probe_column)
    n = int(np.argmax(content))
    if n >= 2:
        return True
    if n == 1:
        return False
    half = probe_column.size // 2
    return abs(np.mean(probe_column[:half])) > abs(np.mean(probe_column[half:]))


def fold(n: int, planets: int) -> int:
    """Harmonic index p of nodal-diameter count n under N planets: n mod N folded to <= N/2."""
    p = n % planets
    return min(p, planets - p)


def harmonic_energy(modes, j: int, planets: int, diameters: np.ndarray) -> np.ndarray:
    """Kinetic energy of mode j per harmonic index p = 0 .. N // 2 (sums to 1)."""
    energy = np.zeros(planets // 2 + 1)
    names = modes.lumped_names
    x = modes.lumped[:, j]
    m = modes.lumped_mass
    for name, value, mass in zip(names, x, m):
        if name in ("u_s", "u_c"):
            energy[0] += mass * value ** 2
        elif name in ("x_s", "y_s", "x_c", "y_c"):
            energy[fold(1, planets)] += mass * value ** 2
    for dof in ("tau", "eta", "u"):
        rows = [names.index(f"{dof}_{i + 1}") for i in range(planets)]
        amplitude = x[rows] * np.sqrt(m[rows])
        spectrum = np.abs(np.fft.fft(amplitude)) ** 2 / planets
        for p, value in enumerate(spectrum):
            energy[fold(p, planets)] += value
    ring = modes.ring_kinetic[j]
    for n, share in enumerate(diameters):
        energy[fold(n, planets)] += ring * share
    return energy / energy.sum()


def mode_content(modes, j: int, planets: int, equally_spaced: bool = True) -> ModeContent:
    """The content of coupled mode ``j`` (``lumped.elastic_ring.CoupledModes``)."""
    diameters = diameter_content(modes.probe[:, j])
    ring = float(modes.ring_kinetic[j])
    n = int(np.argmax(diameters))
    shown = tuple(float(s) for s in diameters[:13])
    if not equally_spaced:
        return ModeContent(n, shown, ring, None, float("nan"),
                           "ring" if 1 - ring < RING_ONLY else "mixed")
    energy = harmonic_energy(modes, j, planets, diameters)
    p = int(np.argmax(energy))
    share = float(energy[p])
    if 1 - ring < RING_ONLY:
        kind = "ring"
    elif share < CLASS_SHARE:
        kind = "mixed"
    else:
        kind = "rotational" if p == 0 else "translational" if p == 1 else "planet"
    return ModeContent(n, shown, ring, p, share, kind)


def frequency_groups(frequency_hz: np.ndarray, rtol: float = PAIR_RTOL) -> list[np.ndarray]:
    """Index groups of ascending frequencies whose neighbours differ by at most ``rtol``
    relative: one group per repeated frequency."""
    f = np.asarray(frequency_hz)
    groups, start = [], 0
    for i in range(1, f.size + 1):
        if i == f.size or f[i] - f[i - 1] > rtol * f[i]:
            groups.append(np.arange(start, i))
            start = i
    return groups


def multiplicities(frequency_hz: np.ndarray, rtol: float = PAIR_RTOL) -> tuple:
    """How many modes share each mode's frequency (gaps below ``rtol`` relative)."""
    out = [0] * len(frequency_hz)
    for group in frequency_groups(frequency_hz, rtol):
        for i in group:
            out[i] = int(group.size)
    return tuple(out)
