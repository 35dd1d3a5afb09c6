"""The elastic ring's coupled modes from two accelerometer records, intact and now (SI).

The elastic-ring model predicts modes that a single sensor on the ring cannot all tell
apart: near-degenerate pairs (a nodal-diameter pair split by the mounting pads or the
planets) and close neighbours.  What one sensor sees of a mode is its radial amplitude at
the sensor (mass-normalised shape); a mode is *seen* when that is at least ``SEEN`` of the
largest in the band.  Among seen modes closer than ``CLOSE`` half-power bandwidths, the one
at least ``DOMINANT`` times stronger at the sensor than each of its close neighbours stands
for the group (the others are skipped, with the reason); a group without such a mode is
left to :func:`.modes.identify_modes`, which skips close modes.  Each represented mode is
then identified on its own (:mod:`.bfft`, spectral lines of the running reducer notched
out: mesh orders and the planet-pass sidebands, deterministic lines at multiples of the
carrier frequency, not modes), in a band free of the other seen modes.

:func:`identify_elastic_records` returns, for every model mode identified in both records,
the frequency now, the baseline frequency and the identification scatter (root mean square
of the two records' Cramer-Rao bounds), in the elastic model's mode order, as
``hubvib.detection.from_records.measured_from_records`` does for the rigid ring.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .modes import ModeIdentification, identify_modes
from .records import Record

#: radial amplitude at the sensor, over the largest in the band, for a mode to be seen
SEEN = 0.1
#: half-power bandwidths (2 zeta f) within which two seen modes are one group
CLOSE = 3.0
#: how much stronger at the sensor a mode must be than each close neighbour to stand for
#: its group
DOMINANT = 2.5


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
    """

    modes: np.ndarray
    frequency_hz: np.ndarray
    baseline_hz: np.ndarray
    sigma_hz: np.ndarray
    now: ModeIdentification
    intact: ModeIdentification
    skipped_modes: dict

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


def represented(predicted_hz, visibility, damping_ratio: float) -> tuple[list, dict]:
    """The model modes a single sensor identifies (0-based) and why each other is not."""
    f = np.asarray(predicted_hz, dtype=float)
    vis = np.asarray(visibility, dtype=float)
    skipped = {}
    seen = [i for i in range(f.size) if vis[i] >= SEEN]
    for i in range(f.size):
        if vis[i] < SEEN:
            skipped[i] = (f"not seen at the sensor (radial amplitude {vis[i]:.2g} of the "
                          f"largest, below {SEEN:g})")
    keep = []
    for i in seen:
        close = [j for j in seen if j != i
                 and abs(f[j] - f[i]) < CLOSE * 2 * damping_ratio * max(f[i], f[j])]
        stronger = [j for j in close if vis[j] >= DOMINANT * vis[i]]
        if stronger:
            skipped[i] = (f"hidden at the sensor by mode {stronger[0] + 1} "
                          f"({abs(f[stronger[0]] - f[i]):.3g} Hz away, "
                          f"{vis[stronger[0]] / max(vis[i], 1e-300):.2g} x stronger there)")
        else:  # a group without a dominant mode: identify_modes skips its close modes
            keep.append(i)
    return keep, skipped


def identify_represented(record: Record, predicted_hz, visibility,
                         damping_ratio: float) -> ModeIdentification:
    """Identify the modes a single sensor can tell apart (:func:`represented`), each
    against the other kept modes only; indices into ``predicted_hz``."""
    keep, skipped = represented(predicted_hz, visibility, damping_ratio)
    f = np.asarray(predicted_hz, dtype=float)
    found = identify_modes(record, f[keep], damping_ratio, lines=True)
    index = tuple(keep[i] for i in found.index)
    skipped = dict(skipped)
    helps = {}
    for i, why in found.skipped.items():
        skipped[keep[i]] = why
        helps[keep[i]] = found.helps.get(i, "")
    return ModeIdentification(index, found.modes, dict(sorted(skipped.items())), helps)


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
                             sensor_angle: float, damping_ratio: float = 0.02
                             ) -> ElasticRecordInput:
    """The elastic model's modes identified in a record now and in the intact baseline.

    Parameters
    ----------
    record, baseline_record : Record
        Acceleration at the sensor now and of the intact reducer (any unit).
    elastic_cases_or_model
        The intact elastic model (see :func:`model_spectrum`): its coupled frequencies
        [Hz] are the guesses, its probe gives each mode's visibility at the sensor.
    sensor_angle : float
        The sensor's polar angle on the ring in the model's frame [rad] (for a scene:
        the cracked tooth's angle plus ``[elastic] sensor_angle_deg``).
    damping_ratio : float
        Modal damping assumed for the bands [-].
    """
    predicted, probe = model_spectrum(elastic_cases_or_model)
    visibility = radial_visibility(probe, sensor_angle)
    now = identify_represented(record, predicted, visibility, damping_ratio)
    intact = identify_represented(baseline_record, predicted, visibility, damping_ratio)
    pick_now = dict(zip(now.index, now.modes))
    pick_intact = dict(zip(intact.index, intact.modes))
    common = [i for i in now.index if i in pick_intact]
    skipped = {i: f"in the baseline record: {why}" for i, why in intact.skipped.items()}
    skipped.update(now.skipped)
    frequency = np.array([pick_now[i].frequency_hz for i in common])
    base = np.array([pick_intact[i].frequency_hz for i in common])
    sigma = np.sqrt(0.5 * np.array([pick_now[i].sigma_hz ** 2 + pick_intact[i].sigma_hz ** 2
                                    for i in common]))
    return ElasticRecordInput(np.array(common, dtype=int), frequency, base, sigma, now, intact,
                              dict(sorted(skipped.items())))
