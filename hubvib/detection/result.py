"""One detection answer for any ring model: per depth and mode the frequencies a record
sees, the watched family, its POD per record length and where it crosses the required
probability (SI).

Built from a spectrum model's study: :func:`rigid_result` reads the rigid-ring study
(:func:`.pod.pod_study`, its numbers unchanged), :func:`.elastic_model.elastic_result`
computes the elastic ring's through the same POD (:func:`.pod.family_pod`).  What only one
model has (the rigid ring's carriers and thresholds, the elastic ring's mode content and
in-contact spectrum) is its ``detail``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from hubvib.foundation.output import finite_or_none

from .mode_names import rigid_label
from .pod import RECORD_LENGTHS, family_pod
from .resolution import Bracket, bracket

__all__ = ["DetectionResult", "rigid_result"]


@dataclass(frozen=True)
class DetectionResult:
    """A ring model's detection answer over a crack sweep.

    Attributes
    ----------
    ring : str
        ``"rigid"`` or ``"elastic"``.
    depths : tuple of float
        [m], ascending, the first 0.
    frequency_hz : ndarray (depths, modes)
        What a record of the nominal reducer sees [Hz] (NaN: no mode continues it).
    labels : tuple of str
        Each mode's identity (:func:`.mode_names.rigid_label`,
        ``hubvib.elastic.content.elastic_label``).
    sigma_hz : dict
        Record length [s] -> identification scatter of each mode [Hz].
    watched : tuple of int
        The alarm family (0-based), best first.
    pod : dict
        Record length [s] -> family POD per depth over the Monte Carlo reducers [-] (the
        nominal reducer's when ``samples`` is 0).
    pod_nominal : dict
        Record length [s] -> family POD per depth of the nominal reducer [-].
    detection_probability, false_alarm_rate : float
        [-]
    record_length : float
        The scene's [s].
    samples : int
        Monte Carlo reducers behind ``pod``.
    added_depths : tuple of float
        Depths [m] the study added to resolve the crossing (:mod:`.resolution`).
    refinement : str
        How the crossing was resolved, in words (why no depths were added, if none).
    left_out : tuple of (float, str)
        Depths of the scene's sweep the model does not hold [m], each with the reason.
    detail : object
        The model's own part (rigid: ``pod.PodResult``; elastic:
        ``elastic_model.ElasticDetail``).
    """

    ring: str
    depths: tuple
    frequency_hz: np.ndarray
    labels: tuple
    sigma_hz: dict
    watched: tuple
    pod: dict
    pod_nominal: dict
    detection_probability: float
    false_alarm_rate: float
    record_length: float
    samples: int = 0
    added_depths: tuple = ()
    refinement: str = ""
    left_out: tuple = ()
    detail: object = field(default=None, compare=False)

    @property
    def intact_hz(self) -> np.ndarray:
        return self.frequency_hz[0]

    @property
    def shift_hz(self) -> np.ndarray:
        """Change of each mode a record sees [Hz], (depths, modes)."""
        return self.frequency_hz - self.frequency_hz[0]

    @property
    def lengths(self) -> tuple:
        return tuple(sorted(self.pod))

    def first_detectable(self, record_length: float) -> float | None:
        """Smallest depth whose family POD reaches the detection probability [m]."""
        return self.bracket(record_length).high

    def bracket(self, record_length: float) -> Bracket:
        """Where the family POD with records of ``record_length`` [s] crosses the detection
        probability (:func:`.resolution.bracket`)."""
        return bracket(self.depths, self.pod[record_length], self.detection_probability)

    def answer(self, record_length: float) -> str:
        """``between 1.5 and 2 mm`` and the like (:meth:`.resolution.Bracket.words`)."""
        return self.bracket(record_length).words()

    def watched_labels(self) -> list[str]:
        return [self.labels[i] for i in self.watched]

    def to_dict(self) -> dict:
        """JSON-ready (NaN as None)."""
        return {
            "ring": self.ring, "depths_mm": [1e3 * d for d in self.depths],
            "added_depths_mm": [1e3 * d for d in self.added_depths],
            "refinement": self.refinement,
            "left_out": [{"depth_mm": 1e3 * d, "reason": why} for d, why in self.left_out],
            "watched_modes": [int(i) + 1 for i in self.watched],
            "watched_labels": self.watched_labels(),
            "first_detectable_mm": {f"{t:g}": (None if self.first_detectable(t) is None
                                               else 1e3 * self.first_detectable(t))
                                    for t in self.lengths},
            "first_detectable_mm_reason": {f"{t:g}": self.answer(t) for t in self.lengths
                                           if self.first_detectable(t) is None},
            "pod_crossing": {f"{t:g}": self.bracket(t).to_dict() for t in self.lengths},
            "family_pod": {f"{t:g}": [float(p) for p in v] for t, v in self.pod.items()},
            "family_pod_nominal": {f"{t:g}": [float(p) for p in v]
                                   for t, v in self.pod_nominal.items()},
            "monte_carlo_samples": self.samples,
            "frequency_hz": [[finite_or_none(x) for x in row] for row in self.frequency_hz],
            "labels": list(self.labels)}

    def rows(self) -> list[dict]:
        """One row per depth and mode (``detection.csv``)."""
        rows = []
        for k, d in enumerate(self.depths):
            for i, label in enumerate(self.labels):
                rows.append({
                    "ring": self.ring, "depth_mm": 1e3 * d, "mode": label,
                    "frequency_hz": finite_or_none(self.frequency_hz[k, i]),
                    "shift_hz": finite_or_none(self.shift_hz[k, i]),
                    "sigma_hz": float(self.sigma_hz[self.record_length][i]),
                    "watched": i in self.watched,
                    "family_pod": float(self.pod[self.record_length][k]),
                    "added": any(math.isclose(d, a) for a in self.added_depths)})
        return rows


def rigid_result(pod, options, kind=None, refinement: str = "") -> DetectionResult:
    """The rigid-ring study's answer (``pod``: its ``pod.PodResult``, with family curves)
    as a :class:`DetectionResult`: the same numbers; the nominal reducer's family POD from
    its record shifts by :func:`.pod.family_pod`."""
    f = pod.nominal.frequency_hz
    kind = pod.kind if kind is None else kind
    lengths = sorted(pod.family_pod) or sorted({*RECORD_LENGTHS, options.record_length})
    sigma = {t: options.sigma_hz(f[0], t) for t in lengths}
    watched = tuple(int(i) for i in pod.watched)
    nominal = {t: family_pod(pod.nominal.shift_hz, sigma[t], watched, pod.per_mode_rate)
               for t in lengths}
    return DetectionResult(
        "rigid", tuple(float(d) for d in pod.depths), f,
        tuple(rigid_label(i, k, f[0, i]) for i, k in enumerate(kind)), sigma, watched,
        dict(pod.family_pod), nominal, pod.detection_probability, pod.false_alarm_rate,
        options.record_length, pod.samples, (), refinement, (), pod)
