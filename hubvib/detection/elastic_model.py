"""The elastic ring as a spectrum model (``spectrum_model.SpectrumModel``): per-depth
frequencies a record sees, and their Monte Carlo over parameter scatter and FE error (SI).

Per crack depth the design's FE ring is meshed with the crack, coupled to the lumped
bodies (``hubvib.elastic``), and every coupled mode is tracked to the intact mode it
continues (:func:`record_frequencies`: the one place a depth's frequencies come from).

Each sample is one reducer as built, scattered like the rigid-ring model's
(:mod:`.uncertainty`): every lumped mass and the ring's mass by ``scatter_masses``, every
lumped spring and the ring-planet spring without the ring body ``k_rest`` by
``scatter_stiffnesses``, the ring's foundation (its mounting) by ``scatter_mounting``,
log-normal, independent.  The ring body's stiffness is the FE ring's; its discretisation
error enters as ``z e_i(d)`` on mode i's frequency at depth d, one standard-normal ``z``
per sample common to every depth and mode, with ``e_i(d) = FE_CHANGE_ERROR |f_i(d) -
f_i(0)|`` (nominal): the crack's change of a mode is known to ``FE_CHANGE_ERROR`` of
itself.  The error of the intact frequencies themselves is not modelled: it cancels
against the reducer's own intact record, not against the model's intact spectrum.

Per depth the coupled model (planet 1 half a planet pitch from the cracked tooth) is
``K = K_0 + sum_j (s_j - 1) K_j`` with ``K_j`` the parts of the scattered springs and of
the foundation, and ``M = diag(s_ring I, m_lumped)`` (the reduced ring's mass is the
identity); every sample's ``M^-1/2 K M^-1/2`` is solved at once (batched ``eigvalsh``).
A sample's modes are named after the nominal ones in sorted order: mode i at depth d is
the sample's ``slot_i(d)``-th frequency, where the nominal mode of the cracked ring that
tracks intact mode i lies (:mod:`hubvib.elastic.tracking`; a split pair's lower member
is the lower frequency, as the nominal's); :func:`sorted_order_kept` measures how often
a sample's mode in that place is the nominal's by subspace match.
"""
from __future__ import annotations

import hashlib
import math
import weakref
from dataclasses import dataclass, field, replace

import numpy as np

from hubvib.elastic.cases import cached_case
from hubvib.elastic.content import elastic_label
from hubvib.elastic.tracking import track_modes
from hubvib.foundation.output import explained, finite_or_none
from hubvib.lumped.elastic_ring import RING_DOFS, coupled_matrices
from hubvib.lumped.network import mass_diagonal, spring_network
from hubvib.lumped.parameters import MASS_FIELDS

from .drift import Drift
from .pod import RECORD_LENGTHS, family_pod, monte_carlo_shifts, watched_by_drop
from .options import DetectionOptions
from .result import DetectionResult
from .uncertainty import lognormal

__all__ = ["ElasticDetail", "elastic_result", "bilinear_hz", "elastic_mode_rows",
           "FE_CHANGE_ERROR", "MIN_MATCH", "VISIBLE", "ElasticSpectrum", "ElasticSamples",
           "RecordFrequencies", "elastic_spectrum_model", "record_frequencies",
           "draw_elastic", "batched_hz", "depth_operators", "sorted_order_kept",
           "sensor_visibility", "case_arguments", "cached_case"]

#: relative error of a crack's change of a coupled mode from the ring's discretisation:
#: the crack study's ring mesh gives changes within 1 Hz of the modal mesh's at 9 mm on
#: the Raba ring, where the watched modes move 100-370 Hz, and the modal mesh's changes
#: converge to 0.3 Hz over two finer levels (docs/elastic_ring.md)
FE_CHANGE_ERROR = 0.01
#: a cracked mode continues an intact one when its subspace match is at least this
MIN_MATCH = 0.5
#: relative step of the mesh stiffnesses for the load drift's sensitivity
LOAD_STEP = 1e-4
#: radial amplitude at the sensor, relative to the largest of the band's modes there, for
#: a mode to count as seen (mass-normalised shapes)
VISIBLE = 0.1


@dataclass(frozen=True, eq=False)
class DepthOperators:
    """One depth's coupled model, split into the parts the samples scatter.

    ``K`` (n, n) [N/m] nominal; ``pieces`` (p, n, n): the part of each name in ``names``
    (``K`` is linear in each); ``slot`` (modes,): index in the sorted spectrum of the mode
    that continues each intact mode; ``tracked`` (modes,): whether that continuation
    matches at least ``MIN_MATCH``.
    """

    K: np.ndarray
    pieces: np.ndarray
    names: tuple
    n_ring: int
    mass: np.ndarray
    slot: np.ndarray
    tracked: np.ndarray


def _lumped_spring_parts(params, ring, tooth: int, k_rest: float):
    """(names, parts): the coupled stiffness's part of every lumped spring field kept in
    the coupled model and of ``k_rest`` [N/m]."""
    mats = coupled_matrices(params, ring, tooth, k_rest)
    network = spring_network(params.replace(theta=mats.engagement.theta))
    keep = np.array([i for i in range(params.n_dof) if i not in RING_DOFS])
    n_ring = ring.size
    names, parts = [], []
    for name in dict.fromkeys(network.parameter):
        if name in ("c_r", "c_ru", "c_rp"):
            continue
        rows = [j for j, p in enumerate(network.parameter) if p == name]
        if not np.any(network.k[rows]):
            continue
        G = network.G[np.ix_(rows, keep)]
        part = np.zeros_like(mats.K)
        part[n_ring:, n_ring:] = G.T @ (network.k[rows][:, None] * G)
        names.append(name)
        parts.append(part)
    doubled = coupled_matrices(params, ring, tooth, 2.0 * k_rest).K
    names.append("k_rest")
    parts.append(doubled - mats.K)
    return mats, names, parts


#: per case, per intact case: its ``DepthOperators`` and their sampled spectra (kept while
#: the cases live): a sweep refined depth by depth asks again for the depths it holds
_OPERATORS = weakref.WeakKeyDictionary()


def depth_operators(case, intact, ring_mass: float) -> DepthOperators:
    """The coupled model of ``case`` (an ``ElasticCase`` with its operators) at planet 1
    away from the crack, its parts, and the slots of the intact modes of ``intact`` (the
    same object again for the same cases and ``ring_mass``)."""
    try:
        known = _OPERATORS.setdefault(case, weakref.WeakKeyDictionary()).setdefault(intact, {})
    except TypeError:  # not weakly referable: computed every time
        known = {}
    key = float(ring_mass)
    if key not in known:
        known[key] = _depth_operators(case, intact, ring_mass)
    return known[key]


def _depth_operators(case, intact, ring_mass: float) -> DepthOperators:
    if case.operators is None:
        raise ValueError("the elastic case holds no ring operators: recompute it "
                         "(hubvib.elastic.cases.cached_case)")
    tooth = case.away.carrier_tooth
    mats, names, parts = _lumped_spring_parts(case.params, case.operators, tooth,
                                              case.k_rest)
    n_ring = case.operators.size
    if case.foundation_K is not None and np.any(case.foundation_K):
        part = np.zeros_like(mats.K)
        part[:n_ring, :n_ring] = case.foundation_K
        names.append("foundation")
        parts.append(part)
    n = intact.away.frequency_hz.size
    tracked = track_modes(intact.away, case.away, ring_mass)
    slot, ok = np.full(n, -1), np.zeros(n, dtype=bool)
    for j, (ref, match) in enumerate(zip(tracked.reference, tracked.match)):
        if 0 <= ref < n:
            slot[ref], ok[ref] = j, match >= MIN_MATCH
    free = [j for j in range(mats.K.shape[0]) if j not in set(slot)]
    for i in np.flatnonzero(slot < 0):
        slot[i] = free.pop(0)
    return DepthOperators(np.asarray(mats.K), np.array(parts), tuple(names), n_ring,
                          np.asarray(mats.lumped_mass, dtype=float), slot, ok)


@dataclass(frozen=True)
class ElasticSamples:
    """``n`` draws of the uncertain reducer on the elastic ring: relative factors [-] of
    the lumped masses (by field), of the ring's mass, of every scattered stiffness part
    (by name, as ``DepthOperators.names``), and the FE error's standard normal ``z``."""

    masses: dict
    ring_mass: np.ndarray
    stiffness: dict
    z: np.ndarray

    @property
    def n(self) -> int:
        return self.z.size


def draw_elastic(model: "ElasticSpectrum", options, n: int, rng) -> ElasticSamples:
    """``n`` samples under ``options`` (DetectionOptions: ``scatter_masses``,
    ``scatter_stiffnesses``, ``scatter_mounting``)."""
    masses = {name: lognormal(1.0, options.scatter_masses, rng, n)
              for name in model.mass_fields}
    ring = lognormal(1.0, options.scatter_masses, rng, n)
    stiffness = {name: lognormal(1.0, options.scatter_mounting if name == "foundation"
                                 else options.scatter_stiffnesses, rng, n)
                 for name in model.stiffness_names}
    return ElasticSamples(masses, ring, stiffness, rng.standard_normal(n))


def unscattered(model: "ElasticSpectrum", n: int = 1) -> ElasticSamples:
    """``n`` copies of the nominal reducer (every factor 1, no FE error)."""
    ones = np.ones(n)
    return ElasticSamples({k: ones for k in model.mass_fields}, ones,
                          {k: ones for k in model.stiffness_names}, np.zeros(n))


#: per depth's operators: sampled spectra by the samples' and masks' fingerprint
_SAMPLED = weakref.WeakKeyDictionary()


def _fingerprint(samples: ElasticSamples, masks: dict) -> bytes:
    """A digest of every factor of ``samples`` and of ``masks``: equal draws, equal key."""
    digest = hashlib.blake2b(digest_size=16)
    for group in (samples.masses, samples.stiffness, masks):
        for name in sorted(group):
            digest.update(name.encode())
            digest.update(np.ascontiguousarray(group[name]).tobytes())
    digest.update(np.ascontiguousarray(samples.ring_mass).tobytes())
    digest.update(np.ascontiguousarray(samples.z).tobytes())
    return digest.digest()


def batched_hz(op: DepthOperators, samples: ElasticSamples, masks: dict) -> np.ndarray:
    """Every sample's coupled frequencies at one depth [Hz], ascending, (n, dofs).

    ``masks``: lumped mass field -> which lumped DOFs it is the mass of.  The same draws at
    the same operators are solved once (a read-only array is returned again)."""
    known = _SAMPLED.setdefault(op, {})
    key = (samples.n, _fingerprint(samples, masks))
    if key not in known:
        values = _batched_hz(op, samples, masks)
        values.flags.writeable = False
        known[key] = values
    return known[key]


def _batched_hz(op: DepthOperators, samples: ElasticSamples, masks: dict) -> np.ndarray:
    n = samples.n
    factors = np.column_stack([samples.stiffness.get(name, np.ones(n)) - 1.0
                               for name in op.names]) if op.names else np.zeros((n, 0))
    size = op.K.shape[0]
    K = (factors @ op.pieces.reshape(len(op.names), -1)).reshape(n, size, size)
    K += op.K
    lumped = np.ones((n, op.mass.size))
    for name, mask in masks.items():
        lumped[:, mask] = samples.masses[name][:, None]
    mass = np.hstack([np.repeat(samples.ring_mass[:, None], op.n_ring, axis=1),
                      lumped * op.mass])
    w = 1.0 / np.sqrt(mass)
    K *= w[:, :, None]
    K *= w[:, None, :]
    values = np.linalg.eigvalsh(K)
    return np.sqrt(np.clip(values, 0.0, None)) / (2 * math.pi)


def sorted_order_kept(model: "ElasticSpectrum", cases, samples: ElasticSamples, k: int,
                      modes) -> np.ndarray:
    """Per intact mode of ``modes`` (0-based), the share of ``samples`` at grid depth ``k``
    whose mode in the nominal's sorted place is the nominal's mode there by subspace match
    (:func:`hubvib.elastic.tracking.track_modes` of the sample's modes against
    ``cases[k].away``) [-]: the check that naming a sample's modes by sorted order keeps
    the nominal's identities."""
    from types import SimpleNamespace

    op, case = model.operators[k], cases[k]
    size = op.K.shape[0]
    factors = np.column_stack([samples.stiffness.get(name, np.ones(samples.n)) - 1.0
                               for name in op.names])
    K = (factors @ op.pieces.reshape(len(op.names), -1)).reshape(samples.n, size, size)
    K += op.K
    lumped = np.ones((samples.n, op.mass.size))
    for name, mask in model.masks.items():
        lumped[:, mask] = samples.masses[name][:, None]
    w = 1.0 / np.sqrt(np.hstack([np.repeat(samples.ring_mass[:, None], op.n_ring, axis=1),
                                 lumped * op.mass]))
    values, vectors = np.linalg.eigh(K * w[:, :, None] * w[:, None, :])
    shapes = vectors * w[:, :, None]  # mass-normalised
    count = min(size, case.away.frequency_hz.size + 6)
    kept = np.zeros(len(modes))
    for j in range(samples.n):
        ring = shapes[j, :op.n_ring, :count]
        other = SimpleNamespace(
            modes=SimpleNamespace(lumped_mass=op.mass, lumped=shapes[j, op.n_ring:, :count],
                                  probe=np.asarray(case.operators.probe @ ring)),
            frequency_hz=np.sqrt(np.clip(values[j, :count], 0.0, None)) / (2 * math.pi))
        reference = track_modes(case.away, other, cases[0].ring_mass).reference
        for a, i in enumerate(modes):
            kept[a] += reference[op.slot[i]] == op.slot[i]
    return kept / samples.n


def _mass_masks(params, lumped_mass: np.ndarray) -> dict:
    """Lumped mass field -> mask of the coupled model's lumped DOFs whose mass it is."""
    keep = np.array([i for i in range(params.n_dof) if i not in RING_DOFS])
    base = mass_diagonal(params)[keep]
    masks = {}
    for name in MASS_FIELDS:
        value = getattr(params, name)
        if name in ("m_r", "mu_r"):
            continue  # the ring's mass is the FE body's
        changed = mass_diagonal(params.replace(**{name: 2.0 * value}))[keep] != base
        if changed.any():
            masks[name] = changed
    return masks


@dataclass(frozen=True, eq=False)
class ElasticSpectrum:
    """The elastic ring as a spectrum model (``spectrum_model.SpectrumModel``): the
    spectrum with planet 1 half a planet pitch from the cracked tooth (the crack is in the
    ring body: it acts at every carrier position) at the sweep's depths ``grid``, linearly
    interpolated in depth to ``depths``.

    ``labels``: one name per intact mode; ``k_rest`` [N/m]; ``fe_change_error`` [-];
    ``nominal_grid_hz`` (grid, modes): what a record of the nominal reducer sees
    (:func:`record_frequencies`); ``record_ratio`` (grid, modes) or None: per depth and
    mode, the nominal record change over the change at the reference position (planet 1
    half a pitch away, faces open; ``reference_grid_hz``), by which every sampled reducer's
    change, solved at the reference position, is scaled, its intact frequency moved by the
    nominal record's offset from the reference (None: the record is the reference).  Where
    the reference change is below ``RATIO_FLOOR`` of the record's (NaN ratio: the load
    cycle moves a mode that the open crack half a pitch away hardly moves) the nominal
    difference of the two changes is added instead (and where the two changes differ in
    sign), so that a ratio never exceeds ``1 / RATIO_FLOOR`` nor flips a sample's scatter.
    A shortcut: the Monte Carlo reducers share the nominal reducer's account of what the
    load cycle does to the crack's change (zero scatter gives the nominal record exactly).
    """

    grid: tuple
    operators: tuple
    masks: dict
    nominal_grid_hz: np.ndarray
    labels: tuple
    k_rest: float
    foundation: tuple | None
    fe_change_error: float = FE_CHANGE_ERROR
    depths: tuple = ()
    ring: str = "elastic"
    mesh: dict = field(default_factory=dict)
    record_ratio: np.ndarray | None = None
    reference_grid_hz: np.ndarray | None = None

    def __post_init__(self):
        if not self.depths:
            object.__setattr__(self, "depths", tuple(self.grid))

    @property
    def mass_fields(self) -> tuple:
        return tuple(self.masks)

    @property
    def stiffness_names(self) -> tuple:
        return tuple(dict.fromkeys(n for op in self.operators for n in op.names))

    @property
    def tracked(self) -> np.ndarray:
        """(grid depths, modes): whether the nominal continuation matches ``MIN_MATCH``."""
        return np.array([op.tracked for op in self.operators])

    def fe_error_hz(self) -> np.ndarray:
        """Standard deviation of the FE error of each mode at each grid depth [Hz]."""
        change = np.abs(self.nominal_grid_hz - self.nominal_grid_hz[0])
        return self.fe_change_error * change

    def grid_hz(self, samples: ElasticSamples) -> np.ndarray:
        """Frequencies of the samples at the grid depths [Hz], (n, grid, modes), FE error
        included."""
        out = np.empty((samples.n, len(self.grid), self.nominal_grid_hz.shape[1]))
        for k, op in enumerate(self.operators):
            out[:, k] = batched_hz(op, samples, self.masks)[:, op.slot]
        if self.record_ratio is not None:  # the record, not the reference position
            offset = self.nominal_grid_hz[0] - self.reference_grid_hz[0]
            change = out - out[:, :1]
            nominal_change = self.reference_grid_hz - self.reference_grid_hz[0]
            added = (self.nominal_grid_hz - self.nominal_grid_hz[0]) - nominal_change
            scaled = np.isfinite(self.record_ratio)
            out = out[:, :1] + offset + np.where(
                scaled[None], np.nan_to_num(self.record_ratio)[None] * change,
                change + np.nan_to_num(added)[None])
        return out + samples.z[:, None, None] * self.fe_error_hz()[None]

    def _interpolated(self, values: np.ndarray, depths) -> np.ndarray:
        """``values`` (n, grid, modes) at ``depths`` (one set for all, or (n, m) per
        sample), linearly in depth."""
        grid = np.asarray(self.grid)
        depths = np.asarray(depths, dtype=float)
        per_sample = depths.ndim == 2
        d = depths if per_sample else np.broadcast_to(depths, (values.shape[0], depths.size))
        index = np.clip(np.searchsorted(grid, d, side="right") - 1, 0, grid.size - 2)
        t = (d - grid[index]) / (grid[index + 1] - grid[index])
        rows = np.arange(values.shape[0])[:, None]
        low, high = values[rows, index], values[rows, index + 1]
        exact = t == 0
        out = (1 - t)[..., None] * low + t[..., None] * high
        out[exact] = low[exact]
        return out

    def nominal_hz(self, options=None, timing=None, long_record=None) -> np.ndarray:
        values = self.nominal_grid_hz[None]
        return self._interpolated(values, self.depths)[0]

    def sampled_hz(self, options, timing=None, samples: int = 0, rng=None, workers: int = 1,
                   depth_index=None, long_record=None) -> np.ndarray:
        drawn = draw_elastic(self, options, samples, rng)
        return self.frequencies_of(drawn, depth_index)

    def frequencies_of(self, drawn: ElasticSamples, depth_index=None) -> np.ndarray:
        """Frequencies [Hz] of the drawn samples at ``depths`` (samples, depths, modes), or
        with ``depth_index`` at depth 0 and that depth (samples, 2, modes)."""
        values = self.grid_hz(drawn)
        if depth_index is None:
            return self._interpolated(values, self.depths)
        depths = np.asarray(self.depths)[np.asarray(depth_index)]
        pairs = np.column_stack([np.zeros(drawn.n), depths])
        return self._interpolated(values, pairs)

    def mode_labels(self) -> tuple:
        return self.labels

    def drift(self, intact_hz, options) -> Drift:
        """Temperature: every spring (and the ring body) by ``(e_E + alpha) dT``, every
        frequency by half that; load: the mesh springs (``c_sp``, ``k_rest``) by ``dL``,
        the sensitivity by a finite difference of the intact model."""
        f = np.asarray(intact_hz, dtype=float)
        per_kelvin = 0.5 * (options.modulus_per_K + options.expansion_per_K) * f
        op = self.operators[0]
        stepped = unscattered(self)
        stepped = replace(stepped, stiffness={
            name: (np.full(1, 1.0 + LOAD_STEP) if name in ("c_sp", "k_rest") else v)
            for name, v in stepped.stiffness.items()})
        moved = batched_hz(op, stepped, self.masks)[0, op.slot]
        per_load = (moved - self.nominal_grid_hz[0]) / LOAD_STEP
        return Drift(per_kelvin, per_load, options.temperature_std, options.mesh_load_std)

    def mesh_stiffness(self) -> dict:
        return {"ring_model": "elastic", "k_rest_N_m": float(self.k_rest),
                "foundation_N_m2": None if self.foundation is None else {
                    "normal": self.foundation[0], "tangential": self.foundation[1]},
                "fe_change_error_relative": self.fe_change_error, **self.mesh}

    def at_depths(self, depths) -> "ElasticSpectrum":
        depths = np.asarray(depths, dtype=float)
        if depths[0] != 0 or depths.min() < 0 or depths.max() > self.grid[-1] * (1 + 1e-12):
            raise ValueError(f"depths {depths[0]:.4g}..{depths.max():.4g} m: they must start "
                             f"at 0 and stay within the sweep 0..{self.grid[-1]:.4g} m")
        return replace(self, depths=tuple(float(d) for d in depths))


def elastic_spectrum_model(depths, cases, fe_change_error: float = FE_CHANGE_ERROR,
                           load: "RecordLoad | None | str" = "working", options=None
                           ) -> ElasticSpectrum:
    """The elastic spectrum model of ``cases`` (``ElasticCase`` per depth of ``depths``
    [m], the first intact, each holding its ring operators); ``load`` and ``options`` as
    :func:`record_frequencies`."""
    intact = cases[0]
    operators = tuple(depth_operators(case, intact, intact.ring_mass) for case in cases)
    masks = _mass_masks(intact.params, operators[0].mass)
    nominal = np.array([case.away.frequency_hz[op.slot] if op.slot.max() <
                        case.away.frequency_hz.size else np.full(op.slot.size, np.nan)
                        for case, op in zip(cases, operators)])
    model = ElasticSpectrum(tuple(float(d) for d in depths), operators, masks, nominal,
                            tuple(elastic_label(c, f) for c, f in
                                  zip(intact.away.content, intact.away.frequency_hz)),
                            float(intact.k_rest), intact.foundation, fe_change_error)
    # the nominal reducer as the batched solve gives it: every mode, also those the band
    # of a cracked spectrum no longer holds
    solved = np.array([batched_hz(op, unscattered(model), masks)[0, op.slot]
                       for op in operators])
    reference = np.where(np.isfinite(nominal), nominal, solved)
    records = [record_frequencies(intact, case, load, options) for case in cases]
    if all(r.record_hz is r.reference_hz for r in records):  # today: the reference itself
        return replace(model, nominal_grid_hz=reference)
    record = np.array([padded(r.record_hz, reference.shape[1]) for r in records])
    record = np.where(np.isfinite(record), record, reference)
    change, moved = reference - reference[0], record - record[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where((np.abs(change) > 0) & (np.abs(change) >= RATIO_FLOOR * np.abs(moved))
                         & (moved * change >= 0), moved / change, np.nan)
    ratio[0] = 1.0
    return replace(model, nominal_grid_hz=record, record_ratio=ratio,
                   reference_grid_hz=reference)


@dataclass(frozen=True)
class RecordFrequencies:
    """What a record sees of one crack depth, per intact mode (the intact case's "away"
    order) [Hz]: ``record_hz`` (NaN: no mode continues it), ``reference_hz`` (planet 1
    half a planet pitch from the cracked tooth, faces open: where the Monte Carlo reducers
    are solved), ``split_pair`` (bool) and ``track``."""

    record_hz: np.ndarray
    reference_hz: np.ndarray
    split_pair: np.ndarray
    track: object = None  # the loaded crack's ``RecordTrack`` (None: faces open)


#: reference change, as a share of the record's, below which a sampled reducer's record
#: change is its reference change plus the nominal difference (not scaled by their ratio)
RATIO_FLOOR = 0.25


@dataclass(frozen=True)
class RecordLoad:
    """The load a record's crack is under: ``torque_fraction`` of the design's sun torque
    [-] and the closure ``gap`` [m] (``hubvib.elastic.loaded``)."""

    torque_fraction: float = 1.0
    gap: float = 0.0


#: the working load; None would leave the faces open (the record sees the reference)
RECORD_LOAD = RecordLoad()


def record_frequencies(intact, case, load: RecordLoad | None | str = "working",
                       options=None) -> RecordFrequencies:
    """The one place the elastic ring's per-depth nominal frequencies come from: ``case``
    (an ``ElasticCase``) as a record sees it, its modes tracked to ``intact``'s (subspace
    match at least ``MIN_MATCH``).

    With a load (default ``RECORD_LOAD``, the working load) and cases holding their pitch
    spectra (a mounted ring), the record track of :func:`hubvib.elastic.loaded.record_track`
    (the faces opening and closing as the planets pass; ``options``: the detection's
    damping ratio and carrier speed, default theirs); otherwise the "away" spectrum
    (planet 1 half a pitch from the crack, faces open), the record's and the reference's
    the same array."""
    reference, split = tracked_to(intact.away, case.away, intact.ring_mass)
    if isinstance(load, str):
        load = RECORD_LOAD
    if load is None or getattr(case, "pitch", None) is None or intact.pitch is None:
        return RecordFrequencies(reference, reference, split)
    track = record_load_track(intact, case, load, options)
    record = padded(np.asarray(track.record_hz, dtype=float), reference.size)
    return RecordFrequencies(record, reference, split, track)


def record_load_track(intact, case, load: RecordLoad, options=None):
    """``hubvib.elastic.loaded.record_track`` of ``case`` under ``load`` with the
    detection's damping ratio and carrier speed (``options``, default theirs)."""
    from hubvib.elastic.loaded import record_track

    options = DetectionOptions() if options is None else options
    return record_track(intact, case, torque_fraction=load.torque_fraction,
                        closure_gap_m=load.gap, damping_ratio=options.damping_ratio,
                        carrier_speed=options.carrier_speed)


def sensor_visibility(spectrum, sensor_angle: float) -> np.ndarray:
    """Radial ring displacement at the sensor angle of each mode, over the largest [-]."""
    probe = spectrum.modes.probe
    points = probe.shape[0] // 2
    index = int(round(sensor_angle % (2 * math.pi) / (2 * math.pi) * points)) % points
    radial = np.abs(probe[index])
    top = radial.max()
    return radial / top if top > 0 else radial


def tracked_to(intact, cracked, mass, index=None) -> tuple[np.ndarray, np.ndarray]:
    """Each intact mode's frequency in ``cracked`` (NaN where no mode continues it with a
    match of at least ``MIN_MATCH``) and whether it is a member of a split pair;
    ``index``: the intact modes' positions in the reported order (default the same)."""
    tracked = track_modes(intact, cracked, mass)
    n = intact.frequency_hz.size if index is None else int(np.max(index)) + 1
    f = np.full(n, np.nan)
    split = np.zeros(n, dtype=bool)
    for j, (ref, match) in enumerate(zip(tracked.reference, tracked.match)):
        if ref >= 0 and match >= MIN_MATCH:
            at = ref if index is None else index[ref]
            if at >= 0:
                f[at] = cracked.frequency_hz[j]
                split[at] = tracked.split_pair[j]
    return f, split


def assignment(reference, other, mass):
    tracked = track_modes(reference, other, mass)
    return tracked.reference, tracked.match


def padded(values: np.ndarray, n: int) -> np.ndarray:
    out = np.full(n, np.nan)
    out[:min(n, values.size)] = values[:n]
    return out


def case_arguments(design, depths, crack_of, scene: ElasticScene) -> list[tuple]:
    """The arguments of ``cached_case`` for every depth (the first 0: intact)."""
    from hubvib.elastic.rest import rest_stiffness

    k_rest = rest_stiffness(design, scene.options.rest)
    return [(design, crack_of(d), scene, k_rest) for d in depths]


# ------------------------------------------------------------------ the detection answer

@dataclass(frozen=True)
class ElasticDetail:
    """What only the elastic ring's answer has (``DetectionResult.detail``).

    Attributes
    ----------
    kind, nodal_diameter, harmonic_index, ring_share : tuple
        Each intact mode's content.
    in_contact_hz : ndarray (depths, modes)
        The tracked frequency with planet 1 on the cracked tooth [Hz] (NaN: not tracked).
    open_hz : ndarray (depths, modes)
        Faces open, planet 1 half a pitch from the crack [Hz] (the reference position).
    tracks : tuple
        Per depth the loaded crack's ``RecordTrack`` (None: faces open).
    load : RecordLoad or None
    split_pair : ndarray (depths, modes) of bool
    visibility : ndarray (modes,)
        Radial amplitude at the sensor relative to the largest among the modes [-].
    k_rest, foundation, ring_dofs, sensor_angle, lowest_ring_mode
        [N/m], (k_n, k_t) [N/m^2] or None, [-], [rad], (Hz, n) or None.
    scatter : tuple
        Relative scatter (masses, stiffnesses, mounting) [-] and the FE error of a
        crack's change [-].
    """

    kind: tuple
    nodal_diameter: tuple
    harmonic_index: tuple
    ring_share: tuple
    in_contact_hz: np.ndarray
    split_pair: np.ndarray
    visibility: np.ndarray
    k_rest: float
    foundation: tuple | None
    ring_dofs: int
    sensor_angle: float
    lowest_ring_mode: tuple | None = None
    scatter: tuple = ()
    open_hz: np.ndarray | None = None
    tracks: tuple = ()
    load: object = None

    @property
    def crack_states(self) -> tuple:
        """Per depth ``(carrier_tooth, open_length_m)`` arrays over the pitch (None where
        the depth has no loaded state: intact, faces open, or through the rim)."""
        out = []
        for track in self.tracks:
            states = getattr(track, "states", ()) if track is not None else ()
            out.append((np.array([s.carrier_tooth for s in states]),
                        np.array([s.open_length_m for s in states])) if states else None)
        return tuple(out)

    @property
    def open_share(self) -> np.ndarray:
        """Per depth: share of carrier positions with the faces apart [-] (NaN: none)."""
        return np.array([np.nan if t is None or not getattr(t, "states", ())
                         else t.open_share for t in self.tracks])

    @property
    def in_contact_shift_hz(self) -> np.ndarray:
        """Change with planet 1 on the cracked tooth, against the intact ring there [Hz]."""
        return self.in_contact_hz - self.in_contact_hz[0]


def bilinear_hz(result: DetectionResult) -> np.ndarray:
    """The textbook breathing crack beside the loaded one: open half a cycle, closed
    (= intact) the other [Hz], (depths, modes): ``2 f_open f_intact / (f_open +
    f_intact)`` with the open crack half a pitch away."""
    f = result.detail.open_hz if result.detail.open_hz is not None else result.frequency_hz
    f0 = f[0]
    return 2 * f * f0 / (f + f0)


def _open_shift(result: DetectionResult) -> np.ndarray:
    """Change with the faces open, planet 1 half a pitch away [Hz] (depths, modes)."""
    f = result.detail.open_hz
    return result.shift_hz if f is None else f - f[0]


def elastic_mode_rows(result: DetectionResult) -> list[dict]:
    """One dict per intact mode of the elastic ring's answer (JSON-ready; NaN as None)."""
    detail = result.detail
    out = []
    for i, f in enumerate(result.intact_hz):
        out.append(explained({
            "mode": i + 1, "label": result.labels[i], "frequency_hz": float(f),
            "class": detail.kind[i], "nodal_diameter": detail.nodal_diameter[i],
            "harmonic_index": detail.harmonic_index[i], "ring_share": detail.ring_share[i],
            "visibility": float(detail.visibility[i]), "watched": i in result.watched,
            "sigma_hz": {f"{t:g}": float(s[i]) for t, s in result.sigma_hz.items()},
            "shift_record_hz": [finite_or_none(x) for x in result.shift_hz[:, i]],
            "shift_open_hz": [finite_or_none(x) for x in _open_shift(result)[:, i]],
            "record": [None if t is None or i >= len(t.record_hz) else _record_row(t, i)
                       for t in detail.tracks],
            "shift_in_contact_hz": [finite_or_none(x)
                                    for x in detail.in_contact_shift_hz[:, i]],
            "shift_bilinear_hz": [finite_or_none(x) for x in
                                  bilinear_hz(result)[:, i] - bilinear_hz(result)[0, i]],
            "split_pair": [bool(x) for x in detail.split_pair[:, i]]}, **MODE_ROW_NULLS))
    return out


#: why a per-depth entry of an elastic mode's row is null
MODE_ROW_NULLS = {
    "shift_record_hz": "null at a depth where the mode is not tracked (no mode of the "
                       "cracked ring's spectrum matches it by shape)",
    "shift_open_hz": "null at a depth where the mode is not tracked with the faces open, "
                     "planet 1 half a pitch away (no mode matches it by shape)",
    "shift_bilinear_hz": "null where shift_open_hz is (the bilinear estimate is built from it)",
    "shift_in_contact_hz": "null where the mode is not tracked with planet 1 on the cracked "
                           "tooth (no mode of that spectrum matches it by shape, intact "
                           "included)",
    "record": "null at a depth without a loaded state (intact, faces open or through the "
              "rim: the open-crack answer holds there) or whose pitch spectra lack the mode",
}


def _record_row(track, i: int) -> dict:
    """Mode ``i`` of a depth's record over the pitch (JSON-ready)."""
    why = "the mode is not tracked over the pitch at this depth"
    return explained({
        "frequency_hz": finite_or_none(track.record_hz[i]),
        "intact_hz": finite_or_none(track.intact_record_hz[i]),
        "instantaneous_min_hz": finite_or_none(track.instantaneous_min_hz[i]),
        "instantaneous_max_hz": finite_or_none(track.instantaneous_max_hz[i]),
        "frequency_slip_hz": finite_or_none(track.slip_hz[i]),
        "regime": track.regime[i] if i < len(track.regime) else None,
        "split_hz": list(track.split_hz[i]) if i < len(track.split_hz) else []},
        frequency_hz=why, intact_hz=why, instantaneous_min_hz=why, instantaneous_max_hz=why,
        frequency_slip_hz=why, regime=why)


def elastic_result(design, depths, crack_of, scene, options, cases: list | None = None,
                   added: tuple = (), refinement: str = "",
                   left_out: tuple = (), load: RecordLoad | None | str = "working"
                   ) -> DetectionResult:
    """The elastic ring's detection answer over ``depths`` [m] (the first 0).

    ``crack_of(depth)`` gives the ``Crack`` of a depth; ``cases``: the ``ElasticCase`` of
    every depth when computed elsewhere (a worker pool), else computed here; ``added``,
    ``refinement``, ``left_out``: as :class:`.result.DetectionResult`; ``load``: the
    record's crack load (:class:`RecordLoad`; default the working load, None: faces open).

    Per depth the frequencies a record sees (:func:`record_frequencies`), each coupled
    mode tracked to the intact mode it continues; the change with planet 1 on the cracked
    tooth beside it (``detail.in_contact_hz``).  The rule is the rigid-ring study's with
    the reducer's own intact record as baseline (:func:`.pod.family_pod`), over the Monte
    Carlo reducers of :class:`ElasticSpectrum` (parameter scatter and FE error); the
    nominal reducer's POD beside it.  Watched: the modes the sensor sees (radial ring motion
    at the sensor at least ``VISIBLE`` of the largest), ranked by their largest drop over
    the sweep against the scatter (:func:`.pod.watched_by_drop`).  Closed faces give the
    intact ring within the mesh's discretisation error, so the bilinear (breathing)
    estimate is :func:`bilinear_hz`; ``detail.open_hz`` keeps the open crack half a pitch
    away beside the record."""
    if cases is None:
        cases = [cached_case(*a) for a in case_arguments(design, depths, crack_of, scene)]
    if getattr(scene, "crack_load", "working") == "open":
        load = None
    intact = cases[0]
    intact_away = intact.away
    mass = intact.ring_mass
    n = intact_away.frequency_hz.size
    open_hz = np.full((len(depths), n), np.nan)
    on_hz = np.full((len(depths), n), np.nan)
    split = np.zeros((len(depths), n), dtype=bool)
    # the on-tooth spectra are tracked to the intact on-tooth spectrum, then reported in
    # the order of the intact modes away from the tooth
    away_of_on = np.full(intact.on.frequency_hz.size, -1)
    for j, (ref, match) in enumerate(zip(*assignment(intact_away, intact.on, mass))):
        if ref >= 0 and match >= MIN_MATCH:
            away_of_on[j] = ref
    record_hz = np.full((len(depths), n), np.nan)
    tracks = []
    for k, case in enumerate(cases):
        seen = record_frequencies(intact, case, load, options)
        record_hz[k], open_hz[k], split[k] = (padded(seen.record_hz, n),
                                              padded(seen.reference_hz, n), seen.split_pair)
        tracks.append(seen.track)
        if (away_of_on >= 0).any():
            on_hz[k] = padded(tracked_to(intact.on, case.on, mass, away_of_on)[0], n)
    # a mode the loaded record does not hold (the band's edge) is seen at the reference
    record_hz = np.where(np.isfinite(record_hz) | ~np.isfinite(open_hz), record_hz, open_hz)
    lengths = tuple(sorted({*RECORD_LENGTHS, options.record_length}))
    sigma = {t: options.sigma_hz(record_hz[0], t) for t in lengths}
    # the sensor from the cracked tooth's centre line, as the records place it
    teeth = len(getattr(intact.operators, "patch_angles", ()))
    tooth = getattr(crack_of(depths[-1]), "tooth", 0) if len(depths) > 1 else 0
    visibility = sensor_visibility(intact_away, (2 * math.pi * tooth / teeth if teeth else 0.0)
                                   + scene.sensor_angle)
    shift = record_hz - record_hz[0]
    watched = watched_by_drop(shift, sigma[options.record_length],
                              np.flatnonzero(visibility >= VISIBLE), options.watched_modes)
    rate = options.per_mode_rate(len(watched)) if watched else options.false_alarm_rate
    pod_nominal = {t: family_pod(shift, sigma[t], watched, rate) for t in lengths}
    pod, samples = pod_nominal, 0
    if intact.operators is not None and options.samples > 0:
        sampled = monte_carlo_shifts(elastic_spectrum_model(depths, cases, load=load,
                                                            options=options), options)
        pod = {t: family_pod(sampled, sigma[t], watched, rate) for t in lengths}
        samples = options.samples
    c = intact_away.content
    detail = ElasticDetail(
        tuple(x.kind for x in c), tuple(x.nodal_diameter for x in c),
        tuple(x.harmonic_index for x in c), tuple(x.ring_share for x in c), on_hz, split,
        visibility, intact.k_rest, intact.foundation, intact.ring_dofs, scene.sensor_angle,
        intact.lowest_ring_mode, (options.scatter_masses, options.scatter_stiffnesses,
                                  options.scatter_mounting, FE_CHANGE_ERROR),
        open_hz, tuple(tracks), load)
    labels = tuple(elastic_label(x, f) for x, f in zip(c, intact_away.frequency_hz))
    return DetectionResult(
        "elastic", tuple(float(d) for d in depths), record_hz, labels, sigma, watched, pod,
        pod_nominal, options.detection_probability, options.false_alarm_rate,
        options.record_length, samples, tuple(added), refinement, tuple(left_out), detail)
