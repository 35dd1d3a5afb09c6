"""Measured frequencies from two accelerometer records, intact and now (SI).

Both records are identified mode by mode (:func:`hubvib.identification.modes.identify_modes`)
around the crack model's intact spectrum with the scene's damping, the spectral
lines of the running reducer (mesh and shaft orders) notched out of each band
(:func:`hubvib.identification.bfft.line_mask`); the modes
identified in both become the rows of a :class:`.measured.Measured` with the
intact record as baseline and the identification scatter of each row (the root
mean square of the two records' Cramer-Rao bounds) as ``sigma_hz``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubvib.identification.modes import ModeIdentification, identify_modes
from hubvib.identification.readers import RecordError, read_record

from .diagnosis import diagnose, scene_reference
from .measured import Measured


@dataclass(frozen=True)
class RecordInput:
    """What the two records gave.

    Attributes
    ----------
    measured : Measured
        Rows of the modes identified in both records.
    now, intact : ModeIdentification
        Identification of the current and the intact record.
    """

    measured: Measured
    now: ModeIdentification
    intact: ModeIdentification


def measured_from_records(record, baseline, predicted_hz, damping_ratio: float,
                          source: str = "record") -> RecordInput:
    """Identify the predicted modes [Hz] in both records (Record objects)."""
    now = identify_modes(record, predicted_hz, damping_ratio, lines=True)
    intact = identify_modes(baseline, predicted_hz, damping_ratio, lines=True)
    common = [i for i in now.index if i in intact.index]
    if not common:
        reasons = "; ".join(f"mode {i + 1}: {why}" for i, why in sorted(now.skipped.items()))
        raise RecordError(f"{source}: no mode of the model can be identified in both records "
                          f"({reasons or 'none predicted'})")
    pick_now = {i: m for i, m in zip(now.index, now.modes)}
    pick_intact = {i: m for i, m in zip(intact.index, intact.modes)}
    frequency = np.array([pick_now[i].frequency_hz for i in common])
    base = np.array([pick_intact[i].frequency_hz for i in common])
    sigma = np.sqrt(0.5 * np.array([pick_now[i].sigma_hz ** 2 + pick_intact[i].sigma_hz ** 2
                                    for i in common]))
    measured = Measured(frequency, np.array(common) + 1, base,
                        tuple(range(1, len(common) + 1)), source, sigma_hz=sigma)
    return RecordInput(measured, now, intact)


def diagnose_records(scene, record_path, baseline_path, progress: bool = True,
                     workers: int = 2):
    """Diagnosis of ``scene`` from an acceleration record now and one of the intact
    reducer (file paths): (Diagnosis, Reference, RecordInput)."""
    record = read_record(record_path, "--record")
    baseline = read_record(baseline_path, "--baseline-record")
    ref, options = scene_reference(scene, progress, workers)
    found = measured_from_records(record, baseline, ref.nominal_hz[0], options.damping_ratio,
                                  "--record")
    return diagnose(found.measured, ref, options), ref, found
