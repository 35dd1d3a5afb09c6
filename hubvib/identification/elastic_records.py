"""The elastic ring's coupled modes from two accelerometer records, intact and now (SI).

The elastic-ring model predicts modes that a single sensor on the ring cannot all tell
apart: near-degenerate pairs (a nodal-diameter pair split by the mounting pads or the
planets) and neighbours within a few half-power bandwidths.  What one sensor sees of a mode
is its radial amplitude there (mass-normalised shape, :func:`radial_visibility`); a mode is
*seen* when that is at least ``SEEN`` of the largest in the band.  Seen modes closer than
``CLOSE`` half-power bandwidths form a group, which the record shows as one peak: the group
is identified as one mode (:mod:`.bfft`, the spectral lines of the running reducer notched
out: mesh orders, planet-pass sidebands and shaft orders are deterministic lines at
multiples of the carrier frequency, not modes), named by its member strongest at the sensor,
and its model frequency is where the model's sensor spectrum peaks (:func:`group_peak`,
every mode under the same white modal force, ASSUMED).  A running reducer's record shows
its modes where the mesh cycle puts them (the Floquet modes, ``hubvib.signal.elastic_floquet``:
up to hundreds of hertz from the mean-stiffness model on the Raba ring's 4.7-9 kHz modes);
given those (``record_hz``), the bands, the fits' starting points and the model
frequencies reported use them.  The record now is fitted from the baseline record's fit of
each band, so that both land in the same optimum of a likelihood with several.

:func:`identify_elastic_records` returns, for every group identified in both records, the
frequency now, the baseline frequency and the identification scatter (root mean square of
the two records' Cramer-Rao bounds), in the elastic model's mode order, as
``hubvib.detection.from_records.measured_from_records`` does for the rigid ring.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .modes import CLOSE_MODE_METHOD, MORE_FORCING, ModeIdentification
from .records import Record

#: radial amplitude at the sensor, over the largest in the band, for a mode to be seen
SEEN = 0.1
#: radial amplitude at the sensor above which a mode is fitted with its band (not reported
#: unless seen): its response is in the record and would bias its neighbours
FAINT = 0.02
#: half-power bandwidths (2 zeta f) within which seen modes share a band (fitted together)
CLOSE = 3.0
#: half-power bandwidths within which seen modes are one peak (a single sensor cannot tell
#: them apart: a near-degenerate pair)
MERGE = 0.25
#: the band reaches this many zeta f beyond its outer peaks
BAND = 3.0
#: a fitted frequency whose Cramer-Rao bound exceeds this many zeta f is not reported
POORLY = 0.25


@dataclass(frozen=True)
class ElasticRecordInput:
    """What two records gave for the elastic ring's modes.

    Attributes
    ----------
    modes : ndarray of int
        Model modes (0-based, the elastic model's order) identified in both records.
    frequency_hz, baseline_hz, sigma_hz : ndarray
        Now, in the baseline record, and the identification scatter of each [Hz].
    now, intact : ModeIdentification
        Per record, indexed by model mode.
    skipped_modes : dict
        Model mode (0-based) -> why it is not among the rows.
    model_hz : ndarray
        The intact model's peak of each row's group at the sensor [Hz].
    """

    modes: np.ndarray
    frequency_hz: np.ndarray
    baseline_hz: np.ndarray
    sigma_hz: np.ndarray
    now: ModeIdentification
    intact: ModeIdentification
    skipped_modes: dict
    model_hz: np.ndarray

    @property
    def shift_hz(self) -> np.ndarray:
        return self.frequency_hz - self.baseline_hz

    def rows(self) -> list[dict]:
        return [{"mode": int(i) + 1, "frequency_hz": float(f), "baseline_hz": float(b),
                 "shift_hz": float(f - b), "sigma_hz": float(s)}
                for i, f, b, s in zip(self.modes, self.frequency_hz, self.baseline_hz,
                                      self.sigma_hz)]


def radial_visibility(probe: np.ndarray, sensor_angle: float) -> np.ndarray:
    """Radial mid-rim amplitude of each mode at ``sensor_angle`` [rad] (linear between the
    probe points), over the largest [-]; ``probe`` (2 P, modes): radial, then tangential."""
    points = probe.shape[0] // 2
    position = (sensor_angle % (2 * math.pi)) / (2 * math.pi) * points
    low = int(math.floor(position)) % points
    w = position - math.floor(position)
    radial = np.abs((1 - w) * probe[low] + w * probe[(low + 1) % points])
    top = radial.max()
    return radial / top if top > 0 else radial


@dataclass(frozen=True)
class ModeGroup:
    """Seen modes within ``MERGE`` half-power bandwidths of each other: one peak for one
    sensor (a near-degenerate pair), fitted as one mode.

    Attributes
    ----------
    members : tuple of int
        Model modes (0-based), the first the one strongest at the sensor (it names the
        peak).
    peak_hz : float
        Where the model's sensor spectrum peaks over the members [Hz] (:func:`group_peak`).
    """

    members: tuple
    peak_hz: float

    @property
    def mode(self) -> int:
        return self.members[0]


def group_peak(frequency_hz, visibility, damping_ratio: float) -> float:
    """Frequency [Hz] of the largest acceleration PSD of modes ``frequency_hz`` seen with
    amplitudes ``visibility`` at the sensor, each under the same white modal force:
    ``sum_j v_j^2 f^4 / ((f_j^2 - f^2)^2 + (2 zeta f_j f)^2)``."""
    f = np.asarray(frequency_hz, dtype=float)
    v = np.asarray(visibility, dtype=float)
    if f.size == 1:
        return float(f[0])
    span = np.linspace(f.min() * (1 - 2 * damping_ratio), f.max() * (1 + 2 * damping_ratio),
                       4001)
    psd = (v[:, None] ** 2 * span[None] ** 4
           / ((f[:, None] ** 2 - span[None] ** 2) ** 2
              + (2 * damping_ratio * f[:, None] * span[None]) ** 2)).sum(axis=0)
    return float(span[np.argmax(psd)])


def _chains(order, f, width):
    """Consecutive members of ``order`` (ascending in f) closer than ``width(f)``."""
    out, current = [], []
    for i in order:
        if current and f[i] - f[current[-1]] >= width(f[i]):
            out.append(current)
            current = []
        current.append(i)
    if current:
        out.append(current)
    return out


def mode_bands(predicted_hz, visibility, damping_ratio: float) -> tuple[list, dict]:
    """The bands a single sensor identifies, each a list of peaks (:class:`ModeGroup`), and
    why each unseen mode is not in one.

    A mode is seen when its visibility is at least ``SEEN``; seen modes closer than
    ``CLOSE`` half-power bandwidths ``2 zeta f`` (chained) share a band; within a band,
    modes closer than ``MERGE`` half-power bandwidths are one peak."""
    f = np.asarray(predicted_hz, dtype=float)
    vis = np.asarray(visibility, dtype=float)
    skipped = {i: (f"not seen at the sensor (radial amplitude {vis[i]:.2g} of the largest, "
                   f"below {SEEN:g})") for i in range(f.size) if vis[i] < SEEN}
    # the faint ones are fitted with their band (their response is in the record) but not
    # reported
    seen = sorted((i for i in range(f.size) if vis[i] >= FAINT), key=lambda i: f[i])
    bands = []
    for band in _chains(seen, f, lambda x: CLOSE * 2 * damping_ratio * x):
        peaks = []
        for unit in _chains(band, f, lambda x: MERGE * 2 * damping_ratio * x):
            unit = sorted(unit, key=lambda i: -vis[i])
            peaks.append(ModeGroup(tuple(unit), group_peak(f[unit], vis[unit], damping_ratio)))
        bands.append(peaks)
    return bands, skipped


def rotating_pairs(frequency_hz, damping_ratio: float) -> set:
    """Modes (0-based) with another mode closer than ``MERGE`` half-power bandwidths
    ``2 zeta f``: the near-degenerate pairs of the ring, whose shapes turn with the
    planets."""
    f = np.asarray(frequency_hz, dtype=float)
    close = np.abs(f[:, None] - f[None, :]) < MERGE * 2 * damping_ratio * f[:, None]
    np.fill_diagonal(close, False)
    return set(int(i) for i in np.flatnonzero(close.any(axis=1)))


def identify_bands(record: Record, bands: list, skipped: dict,
                   damping_ratio: float, starts: dict | None = None,
                   fits: dict | None = None) -> ModeIdentification:
    """Fit every band's peaks together (:func:`.multimode.identify_band`, lines notched);
    indexed by each peak's naming mode, the other members skipped with the reason.
    ``starts``: band number -> another record's fit of it, the start of this one's (the
    baseline's, so that a record that differs a little lands in the same optimum);
    ``fits``: if given, filled with band number -> this record's fit."""
    from .bfft import IdentificationError, IdentifiedMode
    from .multimode import identify_band

    skipped, helps = dict(skipped), {}
    found = {}
    nyquist = 0.5 * record.sample_rate
    for number, peaks in enumerate(bands):
        for g in peaks:
            for other in g.members[1:]:
                skipped[other] = (f"one peak with elastic mode {g.mode + 1} at the sensor (closer "
                                  f"than {MERGE:g} half-power bandwidth)")
        guesses = np.array([g.peak_hz for g in peaks])
        low = guesses.min() * (1 - BAND * damping_ratio)
        high = guesses.max() * (1 + BAND * damping_ratio)
        if high >= nyquist:
            for g in peaks:
                skipped[g.mode] = f"above the Nyquist frequency {nyquist:g} Hz of the record"
                helps[g.mode] = f"a sample rate above {2 * high:.4g} Hz"
            continue
        try:
            fit = identify_band(record.values, record.sample_rate, guesses, damping_ratio,
                                low, high, start=(starts or {}).get(number))
        except IdentificationError as exc:
            for g in peaks:
                skipped[g.mode] = str(exc)
                helps[g.mode] = MORE_FORCING
            continue
        if fits is not None:
            fits[number] = fit
        order = np.argsort(guesses)
        for g, j in zip((peaks[i] for i in order), range(len(peaks))):
            if g.mode in skipped:  # fitted, not seen
                continue
            if not 0 < fit.sigma_hz[j] < POORLY * damping_ratio * fit.frequency_hz[j]:
                skipped[g.mode] = (f"poorly determined in its band {low:.5g}..{high:.5g} Hz "
                                   f"(Cramer-Rao bound {fit.sigma_hz[j]:.3g} Hz, more than "
                                   f"{POORLY:g} zeta f): its neighbours take its response")
                helps[g.mode] = CLOSE_MODE_METHOD
                continue
            found[g.mode] = IdentifiedMode(float(fit.frequency_hz[j]),
                                           float(fit.damping_ratio[j]), float(fit.snr[j]),
                                           float(fit.sigma_hz[j]))
    index = tuple(sorted(found))
    return ModeIdentification(index, tuple(found[i] for i in index),
                              dict(sorted(skipped.items())), helps)


def model_spectrum(elastic_cases_or_model):
    """(frequencies [Hz], probe (2P, modes)) of the intact elastic model: an
    ``ElasticCase`` list (the first intact; planet 1 away from the crack), one
    ``ElasticCase``, an ``ElasticSpectrum`` or a ``CoupledModes``."""
    x = elastic_cases_or_model
    if isinstance(x, (list, tuple)):
        x = x[0]
    x = getattr(x, "away", x)
    x = getattr(x, "modes", x)
    return np.asarray(x.frequency_hz), np.asarray(x.probe)


def identify_elastic_records(record: Record, baseline_record: Record, elastic_cases_or_model,
                             sensor_angle: float, damping_ratio: float = 0.02,
                             record_hz=None, turning: bool = False) -> ElasticRecordInput:
    """The elastic model's modes identified in a record now and in the intact baseline.

    Parameters
    ----------
    record, baseline_record : Record
        Acceleration at the sensor now and of the intact reducer (any unit).
    elastic_cases_or_model
        The intact elastic model (see :func:`model_spectrum`): its coupled frequencies
        [Hz] and its probe (each mode's visibility at the sensor) give the groups and the
        guesses.
    sensor_angle : float
        The sensor's polar angle on the ring in the model's frame [rad] (for a scene: the
        cracked tooth's centre line ``2 pi k / z`` plus ``[elastic] sensor_angle_deg``).
    damping_ratio : float
        Modal damping assumed for the bands [-].
    record_hz : array_like or None
        The frequency each model mode shows in a record of the running reducer [Hz], in
        the model's order (the Floquet modes over the mesh cycle,
        ``hubvib.signal.elastic_floquet``; NaN or missing entries: the model's): the
        bands, the fit's starting point and ``model_hz`` use it.  None: the model's
        frequencies (mesh stiffnesses at their means).
    turning : bool
        The records are of a running reducer (the carrier turning): a mode with another
        model mode within ``MERGE`` half-power bandwidths (a near-degenerate pair, split by
        the planets, whatever either's visibility) is fitted with its band but not
        reported: the carrier turns the pair's shapes past the fixed sensor, which sees
        its peak modulated at the planet-pass frequency.

    Returns
    -------
    ElasticRecordInput
        Rows in the model's mode order, each named by its group's strongest mode.
    """
    predicted, probe = model_spectrum(elastic_cases_or_model)
    paired = rotating_pairs(predicted, damping_ratio) if turning else set()
    if record_hz is not None:
        predicted = predicted.copy()
        shown = np.asarray(record_hz, dtype=float)[:predicted.size]
        known = np.isfinite(shown)
        predicted[:shown.size][known] = shown[known]
    visibility = radial_visibility(probe, sensor_angle)
    bands, unseen = mode_bands(predicted, visibility, damping_ratio)
    for i in paired:
        unseen.setdefault(i, "one of a near-degenerate pair: the turning carrier turns its "
                             "shapes past the sensor, which sees the peak modulated at the "
                             "planet-pass frequency")
    groups = [g for peaks in bands for g in peaks]
    fits = {}
    intact = identify_bands(baseline_record, bands, unseen, damping_ratio, fits=fits)
    now = identify_bands(record, bands, unseen, damping_ratio, starts=fits)
    pick_now = dict(zip(now.index, now.modes))
    pick_intact = dict(zip(intact.index, intact.modes))
    common = sorted(i for i in now.index if i in pick_intact)
    skipped = {i: f"in the baseline record: {why}" for i, why in intact.skipped.items()}
    skipped.update(now.skipped)
    frequency = np.array([pick_now[i].frequency_hz for i in common])
    base = np.array([pick_intact[i].frequency_hz for i in common])
    sigma = np.sqrt(0.5 * np.array([pick_now[i].sigma_hz ** 2 + pick_intact[i].sigma_hz ** 2
                                    for i in common]))
    peak = {g.mode: g.peak_hz for g in groups}
    return ElasticRecordInput(np.array(common, dtype=int), frequency, base, sigma, now, intact,
                              dict(sorted(skipped.items())),
                              np.array([peak[i] for i in common]))


def model_peaks(elastic_spectrum_or_case, sensor_angle: float, damping_ratio: float,
                reference=None) -> dict:
    """Model mode (0-based, the group's naming mode) -> the group's peak [Hz] in this
    spectrum; ``reference``: the intact spectrum whose groups (members by index) are used
    (a crack keeps the mode order of small changes)."""
    f, probe = model_spectrum(elastic_spectrum_or_case)
    vis = radial_visibility(probe, sensor_angle)
    ref_f, ref_probe = model_spectrum(reference if reference is not None
                                      else elastic_spectrum_or_case)
    bands, _ = mode_bands(ref_f, radial_visibility(ref_probe, sensor_angle), damping_ratio)
    groups = [g for peaks in bands for g in peaks]
    n = min(f.size, ref_f.size)
    out = {}
    for g in groups:
        members = [i for i in g.members if i < n]
        if members:
            out[g.mode] = group_peak(f[members], vis[members], damping_ratio)
    return out


def scene_identification(scene, record: Record, baseline: Record,
                         damping_ratio: float | None = None,
                         record_shift_hz=None) -> ElasticRecordInput:
    """:func:`identify_elastic_records` for a crack scene's elastic ring: the intact model
    the scene's cached elastic case (planet 1 half a planet pitch from the cracked tooth),
    the sensor at ``[elastic] sensor_angle_deg`` from the cracked tooth's centre line, the
    damping the scene's ``[signal] damping_ratio`` unless given; ``record_shift_hz``: per
    model mode, how far the running reducer's mesh cycle moves the frequency a record shows
    [Hz] (``hubvib.signal.elastic_record.scene_floquet_shift``), or a function of no
    argument returning it (called once the model is at hand); None: not at all."""
    from hubvib.cases.sweep import crack_of
    from hubvib.elastic.cases import cached_case
    from hubvib.elastic.rest import rest_stiffness
    from hubvib.reducer.stages import ring_gear

    elastic = scene.elastic
    tooth = scene.crack.tooth if scene.crack is not None else 0
    # the diagnosis's own intact case (the sweep's tooth at depth 0): the same ring, mode
    # order and cache entry
    intact = crack_of(scene.crack, 0.0) if scene.crack is not None else None
    case = cached_case(scene.design, intact, elastic, rest_stiffness(scene.design,
                                                                     elastic.options.rest))
    angle = 2 * math.pi * tooth / ring_gear(scene.design).teeth + elastic.sensor_angle
    zeta = scene.signal.damping_ratio if damping_ratio is None else float(damping_ratio)
    record_hz = None
    if record_shift_hz is not None:
        predicted, _ = model_spectrum(case)
        if callable(record_shift_hz):
            record_shift_hz = record_shift_hz()
        shift = np.asarray(record_shift_hz, dtype=float)[:predicted.size]
        record_hz = predicted.copy()
        record_hz[:shift.size] += np.where(np.isfinite(shift), shift, 0.0)
    return identify_elastic_records(record, baseline, case, angle, zeta, record_hz,
                                    turning=scene.signal.sun_speed_rpm > 0)
