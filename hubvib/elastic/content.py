"""What a coupled mode is made of: the ring's nodal diameters, the harmonic index under
the planets' cyclic symmetry, its class and multiplicity.

For N equally spaced planets the system is invariant under turning by 2 pi / N, so every
mode belongs to one harmonic index p (0 <= p <= N/2, p and N - p together; Wu & Parker,
J. Vib. Acoust. 2008): the planets move as ``exp(i p 2 pi j / N)``, the central members
only rotate for p = 0 and only translate for p = 1, and the ring's nodal diameters are
``n = +-p mod N``.

Class, one rule (:func:`mode_content`): the kinetic energy is split over the bodies (the
ring, the sun, the carrier, the planets together); a mode whose largest share is the
ring's is a *ring* mode.  Any other mode is classed by its symmetry type (Lin & Parker,
J. Sound Vib. 1999): *rotational* (p = 0), *translational* (p = 1), *planet* (other p),
or *mixed* when no index holds ``CLASS_SHARE`` of the kinetic energy (a tooth count that
is no multiple of N, support pads off the planets' symmetry, or unequal spacing).

Multiplicity, one rule (:func:`symmetry_pairs`): a pair by symmetry is a pair, found by
shape, not by a frequency gap.  Each mode's shape (the lumped bodies mass-weighted, the
ring's mid-rim displacement weighted to its kinetic energy) is turned by k 2 pi / N,
k = 1 .. N - 1.  A mode whose turned shapes stay on its own line (mean share
``SINGLE_SHARE``) is single (p = 0 or N/2); a degenerate pair's member keeps only
(N - 2) / (2 (N - 1)) < 1/2 there.  Two modes whose turned shapes lie in their common span
(mean share ``PAIR_SHARE`` for both) are one pair; they count 2 each, printed with their
split [Hz] (the mesh's tooth count and the support pads break the symmetry a little).  A
mode whose partner lies above the band's top counts 1.  For the rigid-ring (9 + 3N) model
this reproduces Lin & Parker's multiplicities (rotational 1, translational 2, planet modes
N - 3) for N = 3, 4, 5; from N = 6 on the rigid model's planet frequency holds several
harmonic indices at once (a degeneracy beyond the symmetry's pairs), which this rule
does not count.  The elastic ring separates those indices anyway
(its nodal diameters differ), so there a planet mode is a pair or, for p = N/2, single.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

#: share of the kinetic energy one harmonic index must hold for the mode to be classed by it
CLASS_SHARE = 0.95
#: relative gap below which two frequencies are one repeated frequency (the exactly
#: symmetric rigid-ring spectrum, and tracking across crack depths)
PAIR_RTOL = 1e-3
#: mean share of a mode's turned shapes on its own line from which it is single [-]
SINGLE_SHARE = 0.75
#: mean share of two modes' turned shapes in their span from which they are a pair [-]
PAIR_SHARE = 0.75
#: the bodies a mode's kinetic energy is split over, in ``ModeContent.body_shares`` order
BODIES = ("ring", "sun", "carrier", "planets")


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
        'ring', 'rotational', 'translational', 'planet' or 'mixed' (the module's rule).
    body_shares : tuple of float
        Share of the kinetic energy in each of ``BODIES`` [-].
    """

    nodal_diameter: int
    diameter_shares: tuple
    ring_share: float
    harmonic_index: int | None
    harmonic_share: float
    kind: str
    body_shares: tuple = ()


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


def body_shares(modes, j: int) -> tuple:
    """Kinetic-energy share of coupled mode ``j`` in each of ``BODIES`` [-] (sums to 1)."""
    x, m = modes.lumped[:, j], modes.lumped_mass
    energy = dict.fromkeys(BODIES, 0.0)
    energy["ring"] = float(modes.ring_kinetic[j])
    for name, value, mass in zip(modes.lumped_names, x, m):
        body = {"s": "sun", "c": "carrier"}.get(name.rsplit("_", 1)[1], "planets")
        energy[body] += float(mass * value ** 2)
    total = sum(energy.values())
    return tuple(energy[b] / total if total > 0 else 0.0 for b in BODIES)


def mode_content(modes, j: int, planets: int, equally_spaced: bool = True) -> ModeContent:
    """The content of coupled mode ``j`` (``lumped.elastic_ring.CoupledModes``), classed by
    the module's rule: the ring when it holds the largest kinetic-energy share of the
    bodies, else the symmetry type (rotational, translational, planet; mixed)."""
    diameters = diameter_content(modes.probe[:, j])
    ring = float(modes.ring_kinetic[j])
    n = int(np.argmax(diameters))
    shown = tuple(float(s) for s in diameters[:13])
    shares = body_shares(modes, j)
    if not equally_spaced:
        return ModeContent(n, shown, ring, None, float("nan"),
                           mode_class(shares, None, float("nan")), shares)
    energy = harmonic_energy(modes, j, planets, diameters)
    p = int(np.argmax(energy))
    share = float(energy[p])
    return ModeContent(n, shown, ring, p, share, mode_class(shares, p, share), shares)


def mode_class(shares, p: int | None, harmonic_share: float) -> str:
    """The module's class rule: 'ring' when the ring holds the largest of the body
    ``shares`` (``BODIES`` order), else the symmetry type of harmonic index ``p`` holding
    ``harmonic_share`` of the kinetic energy ('mixed' below ``CLASS_SHARE`` or without
    symmetry, ``p`` None)."""
    if len(shares) and BODIES[int(np.argmax(shares))] == "ring":
        return "ring"
    if p is None or not harmonic_share >= CLASS_SHARE:
        return "mixed"
    return "rotational" if p == 0 else "translational" if p == 1 else "planet"


def turned_shapes(modes, theta, turns) -> np.ndarray:
    """(turns, descriptor, modes): every mode's shape turned by ``turns[k]`` [rad] about
    the centre, as the descriptor :func:`shape_descriptors` gives; ``theta``: the planets'
    angles [rad] (planet i goes to the planet nearest ``theta_i + turn``)."""
    names = list(modes.lumped_names)
    X = np.asarray(modes.lumped)
    theta = np.asarray(theta, dtype=float)
    half = modes.probe.shape[0] // 2
    spectrum = [np.fft.rfft(modes.probe[:half], axis=0), np.fft.rfft(modes.probe[half:], axis=0)]
    n = np.arange(spectrum[0].shape[0])[:, None]
    out = []
    for turn in turns:
        c, s = np.cos(turn), np.sin(turn)
        lumped = np.zeros_like(X)
        for body in ("s", "c"):
            ix, iy, iu = (names.index(f"{d}_{body}") for d in ("x", "y", "u"))
            lumped[ix], lumped[iy] = c * X[ix] - s * X[iy], s * X[ix] + c * X[iy]
            lumped[iu] = X[iu]
        for i in range(theta.size):
            j = int(np.argmin(np.abs(np.angle(np.exp(1j * (theta - theta[i] - turn))))))
            for d in ("tau", "eta", "u"):
                lumped[names.index(f"{d}_{j + 1}")] = X[names.index(f"{d}_{i + 1}")]
        # the field at angle phi is the old one at phi - turn: radial and tangential
        # components keep their meaning, each Fourier term n turns by exp(-i n turn)
        probe = np.vstack([np.fft.irfft(a * np.exp(-1j * n * turn), half, axis=0)
                           for a in spectrum])
        out.append(shape_descriptors(modes, lumped, probe))
    return np.array(out)


def shape_descriptors(modes, lumped=None, probe=None) -> np.ndarray:
    """(descriptor, modes): the lumped DOFs times sqrt(mass) over the ring's mid-rim
    displacement, the latter scaled by one factor so that its squared norm over all modes
    equals the ring's kinetic energy over all modes (a proxy of the ring's mass weight)."""
    lumped = modes.lumped if lumped is None else lumped
    probe = modes.probe if probe is None else probe
    total = float(np.sum(np.asarray(modes.probe) ** 2))
    weight = np.sqrt(float(np.sum(modes.ring_kinetic)) / total) if total > 0 else 0.0
    return np.vstack([np.sqrt(modes.lumped_mass)[:, None] * lumped, weight * probe])


def symmetry_pairs(modes, theta, equally_spaced: bool = True) -> tuple:
    """Per coupled mode the index of its pair partner by the planets' cyclic symmetry, or
    None (single, or its partner beyond the band): the module's rule, by shape.  ``theta``:
    the planets' angles [rad]; no pairs unless they are ``equally_spaced`` and N >= 3."""
    count = modes.omega.size
    planets = len(theta)
    partner: list = [None] * count
    if not equally_spaced or planets < 3 or count < 2:
        return tuple(partner)
    D = shape_descriptors(modes)
    turned = turned_shapes(modes, theta, 2 * np.pi * np.arange(1, planets) / planets)
    norms = np.maximum(np.einsum("kdm,kdm->km", turned, turned), np.finfo(float).tiny)

    def kept(columns, j) -> float:
        q, _ = np.linalg.qr(D[:, columns])
        inside = np.einsum("dc,kd->kc", q, turned[:, :, j])
        return float(np.mean(np.sum(inside ** 2, axis=1) / norms[:, j]))

    candidates = [j for j in range(count) if kept([j], j) < SINGLE_SHARE]
    scores = sorted(((min(kept([a, b], a), kept([a, b], b)), a, b)
                     for i, a in enumerate(candidates) for b in candidates[i + 1:]),
                    reverse=True)
    for score, a, b in scores:
        if score < PAIR_SHARE:
            break
        if partner[a] is None and partner[b] is None:
            partner[a], partner[b] = b, a
    return tuple(partner)


def pair_classes(content, partner) -> tuple:
    """``content`` with both members of each pair (same harmonic index) classed as one:
    the module's rule on the pair's mean body and harmonic shares."""
    out = list(content)
    for a, b in enumerate(partner):
        if b is None or b < a or content[a].harmonic_index != content[b].harmonic_index:
            continue
        bodies = tuple(0.5 * (x + y) for x, y in zip(content[a].body_shares,
                                                     content[b].body_shares))
        share = 0.5 * (content[a].harmonic_share + content[b].harmonic_share)
        kind = mode_class(bodies, content[a].harmonic_index, share)
        out[a], out[b] = replace(content[a], kind=kind), replace(content[b], kind=kind)
    return tuple(out)


def pair_multiplicities(partner) -> tuple:
    """2 for a mode with a pair partner, else 1."""
    return tuple(1 if p is None else 2 for p in partner)


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
    """How many modes share each mode's frequency (gaps below ``rtol`` relative): for
    spectra whose shapes are not at hand; :func:`symmetry_pairs` is the rule by shape."""
    out = [0] * len(frequency_hz)
    for group in frequency_groups(frequency_hz, rtol):
        for i in group:
            out[i] = int(group.size)
    return tuple(out)


def elastic_label(content, frequency_hz: float) -> str:
    """``elastic n=4 (translational, 4715.6 Hz)``: a coupled mode of the elastic ring by its
    dominant nodal diameters, class and intact frequency [Hz] (the name every report,
    table and picture gives it)."""
    return f"elastic n={content.nodal_diameter} ({content.kind}, {frequency_hz:.1f} Hz)"
