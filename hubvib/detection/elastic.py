"""Detection on the elastic-ring model: which coupled modes a root crack moves beyond the
identification scatter, seen by the sensor, and the probability of detecting it (SI).

Per crack depth the design's FE ring is meshed with the crack (faces open), coupled to
the lumped bodies (``hubvib.elastic``), and every coupled mode is tracked to the intact
mode it continues.  The crack is in the ring body, so it acts at every carrier position;
the statistic is the change with planet 1 half a planet pitch from the cracked tooth (the
change at every moment of a record), the change with planet 1 on the tooth is reported
beside it.  Closed faces give the intact ring within the mesh's discretisation error
(``tests/elastic/test_elastic_ring.py``), so the bilinear (breathing) estimate is
``2 f_open f_intact / (f_open + f_intact)``; the detection uses the open crack, the
upper bound of the change.

The rule is the rigid-ring study's with the reducer's own intact record as baseline: a
mode alarms when its change plus the difference of two identification errors,
``N(0, 2 sigma^2)``, falls below ``-z(1 - alpha_m) sqrt(2) sigma``; the family alarms on
any watched mode (Sidak ``alpha_m``).  The POD is the mean of that probability over the
Monte Carlo reducers of :mod:`.elastic_model` (parameter scatter and FE error, as
the rigid-ring POD), the identification noise integrated exactly; the nominal reducer's
POD (identification noise only) is kept beside it.  Watched: the modes the sensor sees
(radial ring motion at the sensor at least ``VISIBLE`` of the largest among the band's
modes), ranked by their largest drop over the sweep against the scatter.  A mode of the
cracked ring continues an intact one when its subspace match is at least ``MIN_MATCH``;
a crack through the rim opens the ring, and modes that no longer match are not tracked.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.elastic.options import ElasticScene
from hubvib.foundation.output import finite_or_none

from .elastic_model import (FE_CHANGE_ERROR, MIN_MATCH, VISIBLE, assignment, padded,
                            tracked_to, cached_case, case_arguments, elastic_spectrum_model,
                            record_frequencies,
                            sensor_visibility)
from .options import DetectionOptions
from .pod import family_pod

RECORD_LENGTHS = (10.0, 60.0, 600.0)
#: MIN_MATCH (from .elastic_model): subspace match below which a cracked mode is not
#: taken to continue an intact one (a crack through the rim opens the ring: its modes are
#: no longer the intact ring's)


@dataclass(frozen=True)
class ElasticDetection:
    """The elastic ring's answer for one crack sweep.

    Attributes
    ----------
    depths : tuple of float
        [m], the first 0.
    intact_hz : ndarray (modes,)
        Coupled modes of the intact reducer, planet 1 half a planet pitch from the crack.
    kind, nodal_diameter, harmonic_index, ring_share : tuple
        Each intact mode's content.
    open_hz, in_contact_hz : ndarray (depths, modes)
        The tracked frequency, faces open, planet 1 away from / on the cracked tooth [Hz]
        (NaN where no mode of the cracked ring tracks it).
    split_pair : ndarray (depths, modes) of bool
    sigma_hz : dict
        Record length [s] -> identification scatter of each mode [Hz].
    visibility : ndarray (modes,)
        Radial amplitude at the sensor relative to the largest among the modes [-].
    watched : tuple of int
        Watched modes (0-based), best first.
    pod : dict
        Record length [s] -> family POD per depth [-], over the Monte Carlo reducers
        (parameter scatter and FE error).
    k_rest, foundation, ring_dofs : float, tuple or None, int
    pod_nominal : dict or None
        Record length [s] -> family POD per depth of the nominal reducer [-]
        (identification noise only).
    samples : int
        Monte Carlo reducers behind ``pod`` (0: ``pod`` is the nominal reducer's).
    scatter : tuple
        Relative scatter (masses, stiffnesses, mounting) [-] and the FE error of a
        crack's change [-].
    """

    depths: tuple
    intact_hz: np.ndarray
    kind: tuple
    nodal_diameter: tuple
    harmonic_index: tuple
    ring_share: tuple
    open_hz: np.ndarray
    in_contact_hz: np.ndarray
    split_pair: np.ndarray
    sigma_hz: dict
    visibility: np.ndarray
    watched: tuple
    pod: dict
    detection_probability: float
    record_length: float
    k_rest: float
    foundation: tuple | None
    ring_dofs: int
    sensor_angle: float
    lowest_ring_mode: tuple | None = None
    pod_nominal: dict | None = None
    samples: int = 0
    scatter: tuple = ()

    @property
    def bilinear_hz(self) -> np.ndarray:
        """Breathing crack: open half a cycle, closed (= intact) the other [Hz]."""
        return 2 * self.open_hz * self.intact_hz / (self.open_hz + self.intact_hz)

    @property
    def shift_hz(self) -> np.ndarray:
        """Change of each mode, planet 1 away from the cracked tooth [Hz]."""
        return self.open_hz - self.intact_hz

    @property
    def in_contact_shift_hz(self) -> np.ndarray:
        """Change with planet 1 on the cracked tooth, against the intact ring there [Hz]."""
        return self.in_contact_hz - self.in_contact_hz[0]

    def first_detectable(self, record_length: float) -> float | None:
        """Smallest depth whose family POD reaches the detection probability [m]."""
        pod = self.pod[record_length]
        hits = [d for d, p in zip(self.depths, pod) if d > 0 and p >= self.detection_probability]
        return min(hits) if hits else None

    def rows(self) -> list[dict]:
        """One dict per intact mode (JSON-ready; NaN as None)."""
        out = []
        for i, f in enumerate(self.intact_hz):
            shifts = self.shift_hz[:, i]
            out.append({
                "mode": i + 1, "frequency_hz": float(f), "class": self.kind[i],
                "nodal_diameter": self.nodal_diameter[i],
                "harmonic_index": self.harmonic_index[i], "ring_share": self.ring_share[i],
                "visibility": float(self.visibility[i]), "watched": i in self.watched,
                "sigma_hz": {f"{t:g}": float(s[i]) for t, s in self.sigma_hz.items()},
                "shift_open_hz": [finite_or_none(x) for x in shifts],
                "shift_in_contact_hz": [finite_or_none(x) for x in self.in_contact_shift_hz[:, i]],
                "shift_bilinear_hz": [finite_or_none(x) for x in self.bilinear_hz[:, i] - f],
                "split_pair": [bool(x) for x in self.split_pair[:, i]],
            })
        return out


def sampled_shifts(model, options: DetectionOptions, seed: int | None = None) -> np.ndarray:
    """Changes of every mode of ``options.samples`` Monte Carlo reducers against their own
    intact spectrum [Hz], (samples, depths, modes); NaN where the nominal continuation is
    not tracked (``MIN_MATCH``)."""
    rng = np.random.default_rng(options.seed + 3 if seed is None else seed)
    f = model.sampled_hz(options, None, options.samples, rng)
    shift = f - f[:, :1]
    shift[:, ~model.tracked] = np.nan
    return shift


def elastic_detection(design, depths, crack_of, scene: ElasticScene,
                      options: DetectionOptions, cases: list | None = None) -> ElasticDetection:
    """The elastic ring's detection answer over ``depths`` [m] (the first 0);
    ``crack_of(depth)`` gives the ``Crack`` of a depth; ``cases``: the ``ElasticCase`` of
    every depth when computed elsewhere (a worker pool), else computed here."""
    if cases is None:
        cases = [cached_case(*a) for a in case_arguments(design, depths, crack_of, scene)]
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
    open_hz[0] = intact_away.frequency_hz
    if (away_of_on >= 0).any():
        on_hz[0] = padded(tracked_to(intact.on, intact.on, mass, away_of_on)[0], n)
    for k, case in enumerate(cases[1:], start=1):
        seen = record_frequencies(intact, case)
        open_hz[k], split[k] = seen.record_hz, seen.split_pair
        if (away_of_on >= 0).any():
            on_hz[k] = padded(tracked_to(intact.on, case.on, mass, away_of_on)[0], n)
    lengths = tuple(sorted({*RECORD_LENGTHS, options.record_length}))
    sigma = {t: options.sigma_hz(intact_away.frequency_hz, t) for t in lengths}
    visibility = sensor_visibility(intact_away, scene.sensor_angle)
    shift = open_hz - intact_away.frequency_hz
    drop = np.nan_to_num(np.clip(-shift, 0.0, None), nan=0.0).max(axis=0)
    seen = np.flatnonzero(visibility >= VISIBLE)
    order = seen[np.argsort(-drop[seen] / sigma[options.record_length][seen], kind="stable")]
    watched = tuple(int(i) for i in order[:options.watched_modes])
    rate = options.per_mode_rate(len(watched)) if watched else options.false_alarm_rate
    pod_nominal = {t: family_pod(shift, sigma[t], watched, rate) for t in lengths}
    pod, samples = pod_nominal, 0
    if intact.operators is not None and options.samples > 0:
        model = elastic_spectrum_model(depths, cases)
        sampled = sampled_shifts(model, options)
        pod = {t: family_pod(sampled, sigma[t], watched, rate) for t in lengths}
        samples = options.samples
    scatter = (options.scatter_masses, options.scatter_stiffnesses, options.scatter_mounting,
               FE_CHANGE_ERROR)
    c = intact_away.content
    return ElasticDetection(
        tuple(float(d) for d in depths), intact_away.frequency_hz,
        tuple(x.kind for x in c), tuple(x.nodal_diameter for x in c),
        tuple(x.harmonic_index for x in c), tuple(x.ring_share for x in c),
        open_hz, on_hz, split, sigma, visibility, watched, pod,
        options.detection_probability, options.record_length, intact.k_rest,
        intact.foundation, intact.ring_dofs, scene.sensor_angle, intact.lowest_ring_mode,
        pod_nominal, samples, scatter)
