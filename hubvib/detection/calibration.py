"""How ``hubvib diagnose`` performs on a scene: false alarms, coverage, impossible patterns.

``calibrate`` (on a scene: ``python -m hubvib.studies.diagnosis_check``) draws reducers
from the uncertainty model of a spectrum model (the rigid-ring lumped model or the elastic
ring, :mod:`.spectrum_model`), identifies their
frequencies with errors from a noise model the diagnosis was not tuned on (Student t
with 8 degrees of freedom, unit variance, times each mode's identification scatter),
diagnoses each against its own intact measurement and writes a markdown table:
the verdicts on intact reducers, the coverage of the intervals over depths drawn
uniformly from the sweep, and the verdicts on patterns no ring crack produces
(docs/diagnosis.md quotes it).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .diagnosis import (CRACK, NO_CRACK, NOT_EXPLAINED, NOT_IDENTIFIABLE, Posterior,
                        synthetic_measurements)


def student_errors(rng, shape, dof: int = 8) -> np.ndarray:
    """Standardised identification errors with heavier tails than normal (unit variance)."""
    return rng.standard_t(dof, size=shape) / math.sqrt(dof / (dof - 2))


@dataclass(frozen=True)
class Calibration:
    """Measured behaviour of the diagnosis.

    Attributes
    ----------
    modes : tuple of int
        Modes used (1-based).
    trials : int
    intact : dict
        Verdict -> fraction of intact reducers [-].
    coverage : float
        Fraction of cracked reducers (depth uniform on the sweep) whose interval holds the
        true depth [-].
    median_width : float
        Median interval width [m].
    patterns : dict
        Pattern name -> (verdict, fit p-value).
    intervals : int or None
        Cracked reducers that got an interval (the others: no crack identifiable).
    """

    modes: tuple
    trials: int
    intact: dict
    coverage: float
    median_width: float
    patterns: dict
    intervals: int | None = None

    def table(self) -> list[str]:
        rows = ["| check | result |", "|---|---:|"]
        for verdict in (NO_CRACK, CRACK, NOT_EXPLAINED):
            rows.append(f"| intact reducers called `{verdict}` | "
                        f"{100 * self.intact.get(verdict, 0.0):.1f} % |")
        if self.intact.get(NOT_IDENTIFIABLE, 0.0) > 0:
            rows.append(f"| intact reducers called `{NOT_IDENTIFIABLE}` | "
                        f"{100 * self.intact[NOT_IDENTIFIABLE]:.1f} % |")
        given = "" if self.intervals is None else (
            f" ({self.intervals} of {self.trials} cracked reducers got an interval)")
        rows.append(f"| 90 % intervals holding the true depth | {100 * self.coverage:.1f} %"
                    f"{given} |")
        rows.append("| median interval width | " + (
            "no interval (no crack identifiable)" if math.isnan(self.median_width)
            else f"{1e3 * self.median_width:.3g} mm") + " |")
        for name, (verdict, p) in self.patterns.items():
            rows.append(f"| {name} | `{verdict}` (fit p = {p:.2g}) |")
        return rows


def patterns(f0: np.ndarray) -> dict:
    """Shift patterns [Hz] of four modes that no ring crack produces."""
    return {"every mode +1 %": 0.01 * f0, "every mode -1 %": -0.01 * f0,
            "last mode +8.6 Hz above its own baseline": np.array([0, 0, 0, 8.6]),
            "first mode -141 Hz, the others unchanged": np.array([-141.0, 0, 0, 0]),
            "last mode -6.9 Hz alone": np.array([0, 0, 0, -6.9])}


def calibrate(model, options, timing, ref, modes, trials: int = 400,
              seed: int = 5) -> Calibration:
    """Diagnose ``trials`` intact and ``trials`` cracked reducers of ``model`` (a
    ``SpectrumModel`` or a ``CrackModel``) and the patterns."""
    index = np.asarray(modes) - 1
    posterior = Posterior(ref, index, True)
    f, own = synthetic_measurements(model, options, timing, np.zeros(trials), seed,
                                    errors=student_errors)
    verdicts = [posterior.diagnose(f[j, index] - own[j, index], "measured").verdict
                for j in range(trials)]
    intact = {v: verdicts.count(v) / trials for v in set(verdicts)}
    truth = np.random.default_rng(seed + 1).uniform(0, model.depths[-1], trials)
    f, own = synthetic_measurements(model, options, timing, truth, seed + 2,
                                    errors=student_errors)
    covered, widths = 0, []
    for j in range(trials):
        r = posterior.diagnose(f[j, index] - own[j, index], "measured")
        if r.depth_low is not None:
            covered += r.depth_low <= truth[j] <= r.depth_high
            widths.append(r.depth_high - r.depth_low)
    f0 = ref.nominal_hz[0, index]
    found = {}
    if index.size == 4:
        for name, y in patterns(f0).items():
            r = posterior.diagnose(y, "measured", f0)
            found[name] = (r.verdict, r.fit_p_value)
    return Calibration(tuple(int(m) for m in modes), trials, intact, covered / trials,
                       float(np.median(widths)) if widths else math.nan, found, len(widths))
