"""Coupled modes about the loaded crack over one planet pitch, and the spectrum a record
of them shows (SI units).

At each carrier position the working load leaves the crack's faces apart or pressed
(``crack_state``).  Small vibrations about that state see the faces apart as free and
the pressed pairs tied in the normal direction; tangentially a pressed contact sticks
(friction holds a small vibration: the answer, ``stick``) or, as a bound, slides freely
(``slip``).  On the reduced ring (its basis holds the static responses of every pair
load, so the ties are represented with their residual flexibility) the ties are imposed
exactly: the ring coordinates are restricted to the null space of the tied rows of
``G V``.  The planets are placed at the position (``engagement``) and coupled as usual.

Each position's spectrum is tracked to the intact ring's at the same position, and the
intact ring's to its own at the reference position (half a planet pitch from the cracked
tooth, the ``away`` of ``ElasticCase``): every frequency is reported in the order of
that intact spectrum, NaN where a mode is not tracked.  A record over many carrier
revolutions sees every position for the same time; ``record_track`` turns the
positions' spectra into what its identification returns.
"""
from __future__ import annotations

import math
import weakref
from dataclasses import dataclass

import numpy as np

from .crack_state import CrackState, crack_state, pitch_teeth  # noqa: F401  (CrackState: the
# states a LoadedSpectra holds, importable from here)

#: torque fractions x closure gaps [m] of the loaded states a case carries
TORQUE_FRACTIONS = (1.0, 0.5, 0.25)
CLOSURE_GAPS = (0.0, 1e-6, 2e-6)
#: every PROBE_STRIDE-th mid-rim point in the stored mode descriptors (64 of 256)
PROBE_STRIDE = 4
#: modal damping ratio and carrier speed of a record [-, rad/s]: the detection's defaults
#: (``hubvib.detection.options.DetectionOptions``, a layer above)
DAMPING_RATIO = 0.02
CARRIER_SPEED = 150.0 * 2 * math.pi / 60
NULL_RCOND = 1e-10


@dataclass(frozen=True, eq=False)
class StoredSpectrum:
    """A coupled spectrum kept light: its frequencies [Hz] and mode descriptors
    (``tracking.descriptors``, float32, every ``PROBE_STRIDE``-th probe point)."""

    frequency_hz: np.ndarray
    descriptors: np.ndarray


@dataclass(frozen=True, eq=False)
class LoadedSpectra:
    """One load variant over the pitch.

    Attributes
    ----------
    torque_N_m : float
        Sun torque [N m] (with no closure gap the state holds at every torque of its sign).
    closure_gap_m : float
        [m]
    carrier_teeth : tuple of int
        Planet 1's tooth at each position.
    states : tuple of CrackState
    stick_hz, slip_hz : ndarray (positions, modes)
        Each position's coupled frequencies, ascending, NaN-padded [Hz], with the pressed
        pairs stuck / sliding tangentially (``record_track`` orders them as the intact
        ring's).
    stick_index, slip_index : tuple of int
        Each position's spectrum in ``PitchSpectra.spectra``.
    torque_fraction : float
        Of the design's sun torque.
    """

    torque_N_m: float
    closure_gap_m: float
    carrier_teeth: tuple
    states: tuple
    stick_hz: np.ndarray
    slip_hz: np.ndarray
    stick_index: tuple
    slip_index: tuple
    torque_fraction: float = 1.0

    @property
    def open_share(self) -> float:
        """Share of positions with some face apart (open length > 0) [-]."""
        return float(np.mean([s.open_length_m > 0 for s in self.states]))


@dataclass(frozen=True, eq=False)
class PitchSpectra:
    """A case's spectra over one planet pitch.

    ``base_index``: per position, the ring as built (intact, or faces free) in
    ``spectra``; ``reference``: the position whose intact spectrum orders the modes;
    ``loaded``: the load variants (empty when intact); ``mesh_force_N``: each planet's
    mesh force at the design's torque [N]; ``seconds``: per step.
    """

    carrier_teeth: tuple
    reference: int
    spectra: tuple
    base_index: tuple
    loaded: tuple
    sun_torque_N_m: float
    mesh_force_N: float
    n_planets: int
    seconds: dict

    def variant(self, torque_fraction: float = 1.0, closure_gap_m: float = 0.0
                ) -> LoadedSpectra | None:
        """The load variant asked (None for an intact ring)."""
        if not self.loaded:
            return None
        for v in self.loaded:
            same = (math.copysign(1.0, v.torque_fraction) == math.copysign(1.0, torque_fraction)
                    if closure_gap_m == 0 else math.isclose(v.torque_fraction, torque_fraction))
            if v.closure_gap_m == closure_gap_m and same:
                return v
        have = sorted({(v.torque_fraction, v.closure_gap_m) for v in self.loaded})
        raise ValueError(f"torque_fraction = {torque_fraction!r}, closure_gap_m = "
                         f"{closure_gap_m!r}: not among the case's variants {have}")


class _Modes:
    def __init__(self, modes):
        self.modes = modes
        self.frequency_hz = modes.frequency_hz


def _store(modes, ring_mass: float) -> StoredSpectrum:
    from .tracking import descriptors

    return StoredSpectrum(np.asarray(modes.frequency_hz, dtype=float),
                          descriptors(_Modes(modes), ring_mass, PROBE_STRIDE).astype(np.float32))


@dataclass(frozen=True, eq=False)
class _LightModes:
    """What a stored spectrum needs of ``CoupledModes`` (no ring coordinates)."""

    omega: np.ndarray
    lumped: np.ndarray
    lumped_mass: np.ndarray
    probe: np.ndarray

    @property
    def frequency_hz(self) -> np.ndarray:
        return self.omega / (2 * np.pi)


def _light_modes(mats, probe: np.ndarray, Z: np.ndarray | None, band_hz: float
                 ) -> _LightModes:
    """``coupled_modes`` below ``band_hz`` of the dense coupled model ``mats``
    (``coupled_matrices``, ring M = I) with its ring coordinates restricted to the columns
    of ``Z`` (orthonormal; None: all).  The restriction of the assembled model is the model
    of the restricted ring (the couplings are linear in the ring's contact rows).  The mass
    is diagonal, so the problem is made standard by scaling; the whole spectrum is solved
    (tens of coordinates) and the part below the band kept."""
    n = mats.n_ring
    K = np.asarray(mats.K)
    if Z is not None:
        rr, rl = Z.T @ K[:n, :n] @ Z, Z.T @ K[:n, n:]
        K = np.block([[rr, rl], [rl.T, K[n:, n:]]])
        probe = probe @ Z
        n = Z.shape[1]
    mass = np.concatenate([np.ones(n), mats.lumped_mass])
    scale = 1 / np.sqrt(mass)
    A = scale[:, None] * K * scale[None, :]
    top = (2 * np.pi * band_hz) ** 2
    values, vectors = np.linalg.eigh(0.5 * (A + A.T))
    below = values <= top
    values, vectors = values[below], vectors[:, below] * scale[:, None]
    return _LightModes(np.sqrt(np.clip(values, 0.0, None)), vectors[n:], mats.lumped_mass,
                       np.asarray(probe @ vectors[:n]))


def position_operators(er, carrier_tooth: int):
    """The reduced ring at one carrier position (``fem.ring_positions``: the modes, the
    engaged teeth's contact responses and, when the crack is paired, every pair's) as
    ``RingOperators``, and the pair rows (2 pairs, m): normal, then tangential."""
    from hubvib.fem.ring_positions import position_basis
    from hubvib.lumped.elastic_ring import RingOperators, engagement

    if er.positions is None:
        raise ValueError("the ring was built without more_positions: it has no reduced "
                         "ring per carrier position")
    teeth = engagement(er.params, er.operators, int(carrier_tooth)).teeth
    pb = position_basis(er.positions, teeth, functionals=er.contact is not None)
    ops = er.operators
    return RingOperators(pb.K, np.eye(pb.K.shape[0]), pb.contact, ops.moment_sign,
                         ops.patch_angles, ops.directions, pb.probe), pb.rows


def tied_operators(operators, rows: np.ndarray):
    """The reduced ring with ``rows @ q = 0`` imposed (coordinates on their null space;
    ``operators`` M = I, so the restricted ring keeps M = I)."""
    from hubvib.lumped.elastic_ring import RingOperators

    if rows.shape[0] == 0:
        return operators
    Z = tie_space(rows)
    K = Z.T @ (operators.K @ Z)
    return RingOperators(0.5 * (K + K.T), np.eye(Z.shape[1]), Z.T @ operators.contact,
                         operators.moment_sign, operators.patch_angles, operators.directions,
                         operators.probe @ Z)


def tie_space(rows: np.ndarray) -> np.ndarray:
    """Orthonormal basis of the coordinates with ``rows @ q = 0``."""
    import scipy.linalg as sla

    norm = np.linalg.norm(rows, axis=1)
    rows = rows[norm > 0] / norm[norm > 0, None]  # each tie weighted alike: a rank that
    # does not depend on which other ties are imposed
    return sla.null_space(rows, rcond=NULL_RCOND)


def tie_rows(rows: np.ndarray, pressed: np.ndarray, stick: bool) -> np.ndarray:
    """The ties of the ``pressed`` pairs from a position's pair rows (normal, then
    tangential): normal, and tangential too when ``stick``."""
    p = pressed.size
    tied = [rows[:p][pressed]]
    if stick:
        tied.append(rows[p:][pressed])
    return np.vstack(tied)


def loaded_operators(er, carrier_tooth: int, pressed, stick: bool = True, base=None):
    """The reduced ring at ``carrier_tooth`` with the ``pressed`` pairs tied (``stick``:
    tangentially too); ``base``: ``position_operators(er, carrier_tooth)`` when at hand."""
    ops, rows = position_operators(er, carrier_tooth) if base is None else base
    pressed = np.zeros(0, bool) if pressed is None else np.asarray(pressed, bool)
    if er.contact is not None and pressed.any():
        ops = tied_operators(ops, tie_rows(rows, pressed, stick))
    return ops


def loaded_modes(er, carrier_tooth: int, pressed, stick: bool = True):
    """Coupled modes (``CoupledModes``) below the band with planet 1 on ``carrier_tooth``
    and the ``pressed`` pairs tied (``stick``: tangentially too)."""
    from hubvib.lumped.elastic_ring import coupled_modes

    return coupled_modes(er.params, loaded_operators(er, carrier_tooth, pressed, stick),
                         int(carrier_tooth), er.k_rest, max_hz=er.options.band_hz)


def loaded_spectrum(er, carrier_tooth: int, pressed, stick: bool = True):
    """``loaded_modes`` with each mode's content and multiplicity (``ElasticSpectrum``)."""
    from .content import mode_content, multiplicities
    from .model import ElasticSpectrum

    modes = loaded_modes(er, carrier_tooth, pressed, stick)
    spaced = er.params.equally_spaced(1e-9)
    content = tuple(mode_content(modes, j, er.params.n_planets, spaced)
                    for j in range(modes.omega.size))
    return ElasticSpectrum(modes, content, multiplicities(modes.frequency_hz),
                           int(carrier_tooth), None)


def pitch_spectra(er, tooth: int, reference_tooth: int, sun_torque: float,
                  mesh_force: float, torque_fractions=TORQUE_FRACTIONS,
                  closure_gaps=CLOSURE_GAPS) -> PitchSpectra:
    """The spectra of ``er`` (built with ``more_positions`` over the pitch and, when
    cracked, ``crack_faces``) at every position of the pitch from ``tooth``: the ring as
    built and, when its crack's contact is condensed, every load variant (a mesh force of
    ``mesh_force`` [N] at the design's ``sun_torque`` [N m])."""
    from hubvib.foundation.blas import blas_threads

    with blas_threads(1):  # many small dense problems: one thread each is fastest
        return _pitch_spectra(er, tooth, reference_tooth, sun_torque, mesh_force,
                              torque_fractions, closure_gaps)


def _pitch_spectra(er, tooth, reference_tooth, sun_torque, mesh_force, torque_fractions,
                   closure_gaps) -> PitchSpectra:
    import time

    from hubvib.lumped.elastic_ring import coupled_matrices, engagement

    seconds = {"states": 0.0, "modes": 0.0}
    params = er.params
    positions = pitch_teeth(er.operators.teeth, params.n_planets, tooth)
    if reference_tooth not in positions:
        raise ValueError(f"reference_tooth = {reference_tooth} is not in the pitch {positions}")
    ring_mass = float(er.body.rigid_mass()[0, 0])
    spectra: list = []
    index: dict = {}
    bases: dict = {}

    def spectrum(position, pressed, stick):
        key = (position, np.asarray(pressed, bool).tobytes(), bool(stick) and np.any(pressed))
        if not np.any(pressed):
            key = (position, b"", False)
        if key not in index:
            t = time.perf_counter()
            index[key] = len(spectra)
            if position not in bases:
                ops, rows = position_operators(er, position)
                bases[position] = (coupled_matrices(params, ops, position, er.k_rest),
                                   ops.probe, rows)
            mats, probe, rows = bases[position]
            pressed = np.asarray(pressed, bool)
            Z = tie_space(tie_rows(rows, pressed, stick)) if pressed.any() else None
            spectra.append(_store(_light_modes(mats, probe, Z, er.options.band_hz),
                                  ring_mass))
            seconds["modes"] += time.perf_counter() - t
        return index[key]

    pairs = 0 if er.contact is None else er.contact.pairs.count
    base = tuple(spectrum(p, np.zeros(pairs, bool), True) for p in positions)
    engaged = {p: engagement(params, er.operators, p).teeth for p in positions}
    loaded = []
    if er.contact is not None:
        variants = load_variants(torque_fractions, closure_gaps)
        for fraction, gap in variants:
            states, stick, slip = [], [], []
            for p in positions:
                t = time.perf_counter()
                state, solution = crack_state(er.contact, p, engaged[p], fraction * mesh_force,
                                              gap)
                seconds["states"] += time.perf_counter() - t
                states.append(state)
                stick.append(spectrum(p, solution.pressed, True))
                slip.append(spectrum(p, solution.pressed, False))
            loaded.append(LoadedSpectra(
                fraction * sun_torque, float(gap), positions, tuple(states),
                _table([spectra[i].frequency_hz for i in stick]),
                _table([spectra[i].frequency_hz for i in slip]), tuple(stick), tuple(slip),
                float(fraction)))
    return PitchSpectra(positions, positions.index(reference_tooth), tuple(spectra), base,
                        tuple(loaded), float(sun_torque), float(mesh_force), params.n_planets,
                        seconds)


def load_variants(torque_fractions, closure_gaps) -> list:
    """(torque fraction, closure gap [m]) pairs to compute: every pair, but with no
    closure gap one per sign of the torque (the state does not depend on its size)."""
    out = []
    for gap in closure_gaps:
        for fraction in torque_fractions:
            if not (math.isfinite(fraction) and fraction != 0):
                raise ValueError(f"torque fraction = {fraction!r}, allowed finite and != 0")
            if gap == 0:
                fraction = math.copysign(1.0, fraction)
            if (fraction, float(gap)) not in out:
                out.append((fraction, float(gap)))
    return out


def _table(rows) -> np.ndarray:
    width = max((r.size for r in rows), default=0)
    out = np.full((len(rows), width), np.nan)
    for i, r in enumerate(rows):
        out[i, :r.size] = r
    return out


@dataclass(frozen=True)
class RecordTrack:
    """A crack's coupled modes as a record over many carrier revolutions shows them, per
    mode of the intact ring at the reference position (its order), all [Hz] but
    ``open_share``.

    ``record_hz``: what a record's identification returns (faces stuck where pressed);
    ``intact_record_hz``: the intact ring treated the same way; ``instantaneous_min_hz``,
    ``instantaneous_max_hz``: the extremes over the positions (stuck); ``slip_hz``: the
    record frequency with the pressed faces sliding (the bound); ``split_hz``: per mode
    the separate peaks when the record shows them split (empty otherwise);
    ``open_share``: share of positions with faces apart; ``regime``: per mode
    ``averaged`` / ``mixture`` / ``split``.
    """

    reference_hz: np.ndarray
    record_hz: np.ndarray
    intact_record_hz: np.ndarray
    instantaneous_min_hz: np.ndarray
    instantaneous_max_hz: np.ndarray
    slip_hz: np.ndarray
    split_hz: tuple
    open_share: float
    regime: tuple
    states: tuple
    torque_N_m: float
    closure_gap_m: float

    @property
    def change_hz(self) -> np.ndarray:
        """``record_hz - intact_record_hz`` [Hz]."""
        return self.record_hz - self.intact_record_hz


def ordered_frequencies(intact: PitchSpectra, case: PitchSpectra, index) -> np.ndarray:
    """(positions, modes): the spectra ``index`` (one per position, in ``case.spectra``)
    in the order of the intact ring's reference spectrum, NaN where untracked: each
    tracked to the intact spectrum at its position (``track_descriptors``), that to the
    reference by order.  The intact ring's modes keep their order over the pitch (a pair
    that veers as the planets turn, Raba's 2.6 / 2.8 kHz pair, exchanges shapes, not
    order), and a record's identification follows a branch, not a shape."""
    if intact.carrier_teeth != case.carrier_teeth:
        raise ValueError(f"the intact case's positions {intact.carrier_teeth} are not the "
                         f"case's {case.carrier_teeth}")
    ref = intact.spectra[intact.base_index[intact.reference]]
    rows = _ordered_rows(intact, case)
    out = np.full((len(index), ref.frequency_hz.size), np.nan)
    for p, i in enumerate(index):
        key = (p, int(i))
        if key not in rows:
            rows[key] = _ordered_row(intact, case, p, int(i), ref.frequency_hz.size)
        out[p] = rows[key]
    return out


#: per case's and intact case's pitch spectra: each (position, spectrum) ordered as the
#: intact reference (kept while both live): load variants share most of their spectra
_ROWS = weakref.WeakKeyDictionary()


def _ordered_rows(intact: PitchSpectra, case: PitchSpectra) -> dict:
    try:
        return _ROWS.setdefault(case, weakref.WeakKeyDictionary()).setdefault(intact, {})
    except TypeError:  # not weakly referable: computed every time
        return {}


def _ordered_row(intact: PitchSpectra, case: PitchSpectra, p: int, i: int, n: int
                 ) -> np.ndarray:
    """Spectrum ``i`` of ``case`` at position ``p`` in the intact reference's order (n,)."""
    from .tracking import track_descriptors

    ref = intact.spectra[intact.base_index[intact.reference]]
    here = intact.spectra[intact.base_index[p]]
    to_ref = np.full(here.frequency_hz.size, -1)
    common = min(here.frequency_hz.size, ref.frequency_hz.size)
    to_ref[:common] = np.arange(common)
    s = case.spectra[i]
    to_here = np.asarray(track_descriptors(here.descriptors, here.frequency_hz,
                                           s.descriptors, s.frequency_hz).reference)
    out = np.full(n, np.nan)
    for j, r in enumerate(to_here):
        if r >= 0 and to_ref[r] >= 0:
            out[to_ref[r]] = s.frequency_hz[j]
    return out


#: record tracks already computed, per case's pitch spectra (kept while those live): a
#: sweep refined depth by depth asks for the same tracks again
_TRACKS = weakref.WeakKeyDictionary()


def record_track(intact_case, case, torque_fraction: float = 1.0,
                 closure_gap_m: float = 0.0, damping_ratio: float = DAMPING_RATIO,
                 carrier_speed: float = CARRIER_SPEED) -> RecordTrack:
    """The record's spectrum of ``case`` (an ``ElasticCase`` with its pitch spectra)
    against ``intact_case`` at one load variant; ``carrier_speed`` [rad/s] sets the
    planet-pass frequency ``N carrier_speed / 2 pi`` [Hz]."""
    pitch, intact = getattr(case, "pitch", None), getattr(intact_case, "pitch", None)
    key = (float(torque_fraction), float(closure_gap_m), float(damping_ratio),
           float(carrier_speed))
    try:
        known = _TRACKS.setdefault(pitch, weakref.WeakKeyDictionary()).setdefault(intact, {})
    except TypeError:  # not weakly referable (None, a stand-in): computed every time
        known = {}
    if key not in known:
        known[key] = _record_track(intact_case, case, torque_fraction, closure_gap_m,
                                   damping_ratio, carrier_speed)
    return known[key]


def _record_track(intact_case, case, torque_fraction, closure_gap_m, damping_ratio,
                  carrier_speed) -> RecordTrack:
    intact, pitch = intact_case.pitch, case.pitch
    if intact is None or pitch is None:
        raise ValueError("record_track: both cases need their pitch spectra (a mounted "
                         "ring; the free ring has no loaded state)")
    variant = pitch.variant(torque_fraction, closure_gap_m)
    dwell = np.full(len(pitch.carrier_teeth), 1.0 / len(pitch.carrier_teeth))
    pass_hz = pitch.n_planets * carrier_speed / (2 * math.pi)
    intact_hz = ordered_frequencies(intact, intact, intact.base_index)
    if variant is None:
        stick = slip = intact_hz if case is intact_case else ordered_frequencies(
            intact, pitch, pitch.base_index)
        states, share = (), 0.0
        torque, gap = pitch.sun_torque_N_m * torque_fraction, closure_gap_m
    else:
        stick = ordered_frequencies(intact, pitch, variant.stick_index)
        slip = ordered_frequencies(intact, pitch, variant.slip_index)
        states, share = variant.states, variant.open_share
        # with no gap one state serves every torque of a sign: report the one asked
        torque, gap = pitch.sun_torque_N_m * torque_fraction, variant.closure_gap_m
    record = _record(stick, dwell, damping_ratio, pass_hz)
    intact_record = _intact_record(intact, intact_hz, dwell, damping_ratio, pass_hz)
    reference = intact.spectra[intact.base_index[intact.reference]].frequency_hz
    split = tuple(tuple(float(f) for f in peaks) if regime == "split" else ()
                  for peaks, regime in zip(record.peaks_hz, record.regime))
    return RecordTrack(
        np.asarray(reference), np.asarray(record.frequency_hz),
        np.asarray(intact_record.frequency_hz),
        np.asarray(record.instantaneous_min_hz), np.asarray(record.instantaneous_max_hz),
        np.asarray((record if np.array_equal(slip, stick, equal_nan=True) else
                    _record(slip, dwell, damping_ratio, pass_hz)).frequency_hz), split,
        float(share), tuple(record.regime), tuple(states), float(torque), float(gap))


#: the intact ring's record per pitch spectra, damping ratio and pass frequency
_INTACT_RECORDS = weakref.WeakKeyDictionary()


def _intact_record(intact: PitchSpectra, intact_hz, dwell, damping_ratio, pass_hz):
    try:
        known = _INTACT_RECORDS.setdefault(intact, {})
    except TypeError:
        known = {}
    key = (float(damping_ratio), float(pass_hz), np.asarray(dwell).tobytes())
    if key not in known:
        known[key] = _record(intact_hz, dwell, damping_ratio, pass_hz)
    return known[key]


def _record(instantaneous_hz, dwell, damping_ratio, pass_hz):
    from .record_spectrum import record_spectrum

    return record_spectrum(instantaneous_hz, dwell, damping_ratio, pass_hz)
