"""Measured frequencies from two accelerometer records, intact and now (SI).

Both records are identified mode by mode (:func:`hubvib.identification.modes.identify_modes`)
around the crack model's intact spectrum with the scene's damping, the spectral
lines of the running reducer (mesh and shaft orders) notched out of each band
(:func:`hubvib.identification.bfft.line_mask`); the modes
identified in both become the rows of a :class:`.measured.Measured` with the
intact record as baseline and the identification scatter of each row (the root
mean square of the two records' Cramer-Rao bounds) as ``sigma_hz``.

Valid records in which no mode of the model can be identified in both are not an
error: the answer is the verdict ``not identifiable from these records``
(:class:`NotIdentified`), with the reason per mode and what would make the records
usable (record length, damping, sample rate, forcing).
"""
from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from hubvib.identification.modes import DEGENERATE, ModeIdentification, identify_modes
from hubvib.identification.readers import read_record

from .diagnosis import diagnose, scene_reference
from .measured import Measured


#: verdict when no mode of the model is identified in both records
NOT_IDENTIFIED = "not identifiable from these records"


@dataclass(frozen=True)
class RecordInput:
    """What the two records gave.

    Attributes
    ----------
    measured : Measured or None
        Rows of the modes identified in both records; None when there is none.
    now, intact : ModeIdentification
        Identification of the current and the intact record.
    """

    measured: Measured | None
    now: ModeIdentification
    intact: ModeIdentification

    def skipped(self) -> dict[int, str]:
        """Model mode (1-based) -> why it is not among the rows: the reason in the record
        now, else the one in the intact record (the record named)."""
        out = {}
        for i, why in self.now.skipped.items():
            out[i + 1] = why
        for i, why in self.intact.skipped.items():
            if i + 1 not in out:
                out[i + 1] = f"in the baseline record: {why}"
        return dict(sorted(out.items()))

    def helps(self) -> dict[int, str]:
        """Model mode (1-based) -> what would make it identifiable."""
        out = {i + 1: h for i, h in self.intact.helps.items()}
        out.update({i + 1: h for i, h in self.now.helps.items()})
        return {m: out.get(m, "") for m in self.skipped()}


_PAIR = re.compile("^" + re.escape(DEGENERATE).replace(r"\{other\}", r"(\d+)") + "$")


def skipped_lines(skipped: dict[int, str], model: str = "rigid") -> list[str]:
    """The skipped modes (1-based -> why) of the ``model`` ring's spectrum as short lines,
    each naming the model: the degenerate pairs on one line, every other mode on its own."""
    pairs, lines = set(), []
    for mode, why in skipped.items():
        match = _PAIR.match(why)
        if match:
            pairs.add(tuple(sorted((mode, int(match.group(1))))))
        else:
            lines.append(f"{model} mode {mode}: {why}")
    if pairs:
        listed = ", ".join(f"{a}/{b}" for a, b in sorted(pairs))
        lines.insert(0, f"{model} modes {listed}: degenerate pairs (close modes), which a "
                     "single-mode fit cannot separate")
    return lines


_VALUE = re.compile(r"^(.*?)(\d[\d.e+-]*)( %| s| Hz)$")


def what_would_help(helps: dict[int, str], model: str = "rigid") -> list[str]:
    """The distinct remedies of ``helps`` (mode of the ``model`` ring -> remedy), each with
    the modes it serves, named with their model;
    a remedy with a number per mode (damping below, records of at least, a sample rate
    above) is one line with the number of each mode."""
    grouped: dict[str, list] = {}
    for mode, text in helps.items():
        if not text:
            continue
        match = _VALUE.match(text)
        if match:
            head, value, unit = match.groups()
            grouped.setdefault(head.rstrip(), []).append(f"{value}{unit} ({model} mode {mode})")
        else:
            grouped.setdefault(text, []).append(mode)
    lines = []
    for head, items in grouped.items():
        if items and isinstance(items[0], str):
            lines.append(f"{head} {', '.join(items)}")
        else:
            label = f"{model} mode" if len(items) == 1 else f"{model} modes"
            lines.append(f"{head} ({label} {', '.join(str(m) for m in items)})")
    return lines


@dataclass(frozen=True)
class NotIdentified:
    """The answer to two valid records in which no mode of the model is identified in both.

    Attributes
    ----------
    skipped : dict
        Model mode (1-based) -> why it was not identified.
    helps : list of str
        What would make the records usable, each with the modes it serves.
    record_s, baseline_s : float
        Lengths of the two records [s].
    damping_ratio : float
        Modal damping the identification assumed (the scene's) [-].
    """

    skipped: dict
    helps: list
    record_s: float
    baseline_s: float
    damping_ratio: float
    verdict: str = NOT_IDENTIFIED

    def to_dict(self) -> dict:
        return {"verdict": self.verdict, "depth_m": None, "depth_low_m": None,
                "depth_high_m": None, "modes": [], "record_s": self.record_s,
                "baseline_record_s": self.baseline_s,
                "assumed_damping_ratio": self.damping_ratio,
                "skipped_modes": {str(m): why for m, why in self.skipped.items()},
                "what_would_help": list(self.helps)}


def measured_from_records(record, baseline, predicted_hz, damping_ratio: float,
                          source: str = "record") -> RecordInput:
    """Identify the predicted modes [Hz] in both records (Record objects)."""
    now = identify_modes(record, predicted_hz, damping_ratio, lines=True)
    intact = identify_modes(baseline, predicted_hz, damping_ratio, lines=True)
    common = [i for i in now.index if i in intact.index]
    if not common:
        return RecordInput(None, now, intact)
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
    reducer (file paths): (Diagnosis or NotIdentified, Reference, RecordInput)."""
    record = read_record(record_path, "--record")
    baseline = read_record(baseline_path, "--baseline-record")
    ref, options = scene_reference(scene, progress, workers)
    found = measured_from_records(record, baseline, ref.nominal_hz[0], options.damping_ratio,
                                  "--record")
    if found.measured is None:
        return NotIdentified(found.skipped(), what_would_help(found.helps()), record.duration,
                             baseline.duration, options.damping_ratio), ref, found
    return diagnose(found.measured, ref, options), ref, found


#: share of a mode's half-power half-width ``zeta f`` within which its intact peak must lie
#: of the model's running frequency to count as that mode (the choice: docs/signal.md,
#: "The coupled modes from the records")
NEAR_SHARE = 0.25


def elastic_measured(scene, record, baseline, record_shift_hz=None):
    """``(measured, left_out)``: the scene's elastic-ring modes identified in ``record`` and
    its intact ``baseline`` (``identification.Record``;
    ``identification.elastic_records.scene_identification`` with the scene's intact case,
    sensor and damping; ``record_shift_hz`` as there) as measured
    frequencies with their scatter (``detection.measured.Measured``), the modes whose
    intact peak lies further from the model's mode than ``NEAR_SHARE`` of its half-power
    half-width left out (the model does not hold them there, or the peak is another
    mode's: one line each in ``left_out``); ``measured``
    is None when no mode is left, and ``left_out`` then ends with why each was skipped."""
    from hubvib.identification.elastic_records import scene_identification

    found = scene_identification(scene, record, baseline, None, record_shift_hz)
    zeta = scene.signal.damping_ratio
    model = np.asarray(found.model_hz, dtype=float)
    base = np.asarray(found.baseline_hz, dtype=float)
    near = np.abs(base - model) <= NEAR_SHARE * zeta * model
    left_out = [f"elastic mode {m + 1}: identified at {f:.1f} Hz in the intact record, "
                f"further than {NEAR_SHARE:g} of its half-power half-width "
                f"({NEAR_SHARE * zeta * g:.1f} Hz) from the model's {g:.1f} Hz: left out"
                for m, f, g in zip(found.modes[~near], base[~near], model[~near])]
    if not near.any():
        why = "; ".join(f"elastic mode {m + 1}: {reason}" for m, reason in
                        sorted(found.skipped_modes.items())[:6])
        return None, left_out + [why]
    return Measured(np.asarray(found.frequency_hz, dtype=float)[near],
                    np.asarray(found.modes, dtype=int)[near] + 1, base[near],
                    tuple(range(1, int(near.sum()) + 1)), "--record",
                    sigma_hz=np.asarray(found.sigma_hz, dtype=float)[near]), left_out
