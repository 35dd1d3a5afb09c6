"""Seed 000: harmonic analysis of the kinematic error of ball/roller planetary gears (SI).

Kapitonov & Drozdov, "Method for improving the accuracy of planetary transmissions
based on spectral analysis ... of kinematic errors" (``shared/seeds/000_*.txt``),
equations as they must be read (``shared/reference/seeds_000_002.md``):

- eq. (2): ratio of one stage ``i = (z1 + z2) / z1``; S equal stages give ``i^S``;
- eqs. (3)/(4): from the pulse periods ``T_j`` of an encoder on the output
  (``N`` pulses per output revolution), ``F_i = omega_m (sum_{j<=i} T_j - i T_m)``
  with ``T_m`` the *mean period* over whole output revolutions and
  ``omega_m = 2 pi n_m``, ``n_m = 1 / (N T_m)`` in rev/s; F in rad;
- eqs. (5)-(8): ``F(phi) = c0/2 + sum c_k cos(k phi + phi_k)`` over the output angle
  phi (:mod:`hubvib.signal.spectral`, the module the vibration signature uses).

The error is resampled onto the output angle (pulse i sits at ``2 pi i / N``) and
cut to whole revolutions before the transform; orders at or above ``N / 2`` are
never reported (they would be aliases).  Each large harmonic is labelled by the
part that explains it, as the paper does by hand, or reported as unexplained.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hubvib.foundation.files import MAX_TABLE_BYTES, read_text
from hubvib.signal.spectral import (HarmonicRule, LabelledHarmonic, OrderSpectrum, angle_domain,
                                    order_spectrum, top_harmonics)

UNITS = {"deg": 180 / math.pi, "arcmin": 60 * 180 / math.pi, "rad": 1.0}


#: physical bounds, checked before computing (1e308 s or 1000 stages overflowed)
MAX_PERIODS = 10_000      # periods of a track (z1, z2)
MAX_STAGES = 20
MAX_RATIO = 1e12          # total ratio [-]
MIN_PERIOD_S = 1e-9       # [s] a 1 GHz pulse rate
MAX_PERIOD_S = 86_400.0   # [s] one pulse a day


@dataclass(frozen=True)
class GearTrain:
    """S equal stages of an intermediate-rolling-body planetary gear.

    Attributes
    ----------
    z1 : int
        Periods of the driving (eccentric) track, >= 1.
    z2 : int
        Periods of the fixed multi-period track, >= 1.
    stages : int
        Number of equal stages, >= 1.
    """

    z1: int
    z2: int
    stages: int = 1

    def __post_init__(self):
        for name, high in (("z1", MAX_PERIODS), ("z2", MAX_PERIODS), ("stages", MAX_STAGES)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= high:
                raise ValueError(f"--{name} = {value!r}; allowed: an integer 1..{high}")
        if self.stage_ratio ** self.stages > MAX_RATIO:  # checked before any order is formed
            raise ValueError(f"--stages {self.stages} of ({self.z1} + {self.z2}) / {self.z1} "
                             f"give a ratio of {self.stage_ratio ** self.stages:.3g}; allowed: "
                             f"a total ratio <= {MAX_RATIO:.0e} (lower --stages or --z2)")

    @property
    def stage_ratio(self) -> float:
        """Eq. (2): i = (z1 + z2) / z1 [-]."""
        return (self.z1 + self.z2) / self.z1

    @property
    def ratio(self) -> float:
        """Total ratio (stage ratio to the power S) [-]."""
        return self.stage_ratio ** self.stages

    def engagement_order(self, stage: int) -> float:
        """Satellite engagements per output revolution of stage ``stage`` (1 = output
        stage): z2 (z1 + z2) i_stage^(stage - 1) (the paper's 294 = 6 x 7 x 7)."""
        return self.z2 * (self.z1 + self.z2) * self.stage_ratio ** (stage - 1)

    def rules(self) -> list[HarmonicRule]:
        """Labelling rules, most specific first."""
        rules = [HarmonicRule("output", 1.0, 2, meaning="once/twice per output revolution: "
                                                         "radial run-out, misalignment")]
        for s in range(self.stages, 0, -1):
            rules.append(HarmonicRule(f"E{s}", self.engagement_order(s), 3,
                                      meaning=f"satellite engagement of stage {s}"))
        for s in range(1, self.stages + 1):
            rules.append(HarmonicRule("z2" if s == 1 else f"z2*i^{s - 1}",
                                      self.z2 * self.stage_ratio ** (s - 1),
                                      meaning=f"periods of the fixed track, stage {s}"))
        rules.append(HarmonicRule("i", self.ratio, meaning="input shaft (the ratio)"))
        for s in range(1, self.stages):
            rules.append(HarmonicRule(f"i_stage^{s}", self.stage_ratio ** s,
                                      meaning=f"shaft between stages {s} and {s + 1}"))
        return rules


@dataclass(frozen=True)
class KinematicError:
    """Kinematic error against the output angle, whole revolutions only.

    Attributes
    ----------
    angle : ndarray
        Output angle of each pulse [rad], 2 pi i / N, i = 0..R N.
    error : ndarray
        F_i [rad] (eq. 3).
    error_eq4 : ndarray
        F_i by eq. (4) [rad] (the same numbers: a check of the reading).
    mean_period : float
        T_m [s].
    pulses_per_rev : int
    revolutions : int
        Whole output revolutions used, R.
    leftover_periods : int
        Periods after the last whole revolution, left out.
    """

    angle: np.ndarray
    error: np.ndarray
    error_eq4: np.ndarray
    mean_period: float
    pulses_per_rev: int
    revolutions: int
    leftover_periods: int

    @property
    def mean_speed_rpm(self) -> float:
        """n_m [min^-1]."""
        return 60.0 / (self.pulses_per_rev * self.mean_period)

    @property
    def peak_to_peak(self) -> float:
        """Largest kinematic error (the paper's measure of accuracy) [rad]."""
        return float(self.error.max() - self.error.min())


def kinematic_error(periods, pulses_per_rev: int) -> KinematicError:
    """Eqs. (3)/(4) from pulse periods [s] and N pulses per output revolution.

    Raises
    ------
    ValueError
        A period that is not a finite number > 0, N < 4, fewer than two revolutions.
    """
    if isinstance(pulses_per_rev, bool) or not isinstance(pulses_per_rev, int) or \
            pulses_per_rev < 4:
        raise ValueError(f"--pulses-per-rev = {pulses_per_rev!r}; allowed: an integer >= 4")
    T = np.asarray(periods, dtype=float)
    bad = np.flatnonzero(~((T >= MIN_PERIOD_S) & (T <= MAX_PERIOD_S)))  # NaN fails both
    if bad.size:
        raise ValueError(f"--periods: period {bad[0] + 1} = {float(T[bad[0]])!r} s; allowed: "
                         f"{MIN_PERIOD_S:g}..{MAX_PERIOD_S:g} s (a pulse period of a turning "
                         "output)")
    R = T.size // pulses_per_rev
    if R < 2:
        raise ValueError(f"--periods: {T.size} periods = {T.size / pulses_per_rev:.3g} output "
                         f"revolutions at {pulses_per_rev} pulses per revolution; allowed: >= 2 "
                         f"revolutions ({2 * pulses_per_rev} periods)")
    used = T[:R * pulses_per_rev]
    mean_period = float(used.mean())
    elapsed = np.concatenate([[0.0], np.cumsum(used)])
    i = np.arange(used.size + 1)
    omega_m = 2 * math.pi * R / elapsed[-1]                # mean output speed [rad/s], eq. (3)
    n_m = 1.0 / (pulses_per_rev * mean_period)             # [rev/s], eq. (4)
    return KinematicError(2 * math.pi * i / pulses_per_rev, omega_m * (elapsed - i * mean_period),
                          2 * math.pi * n_m * (elapsed - i * mean_period), mean_period,
                          pulses_per_rev, R, int(T.size - used.size))


@dataclass(frozen=True)
class HarmonicAnalysis:
    """The kinematic error, its spectrum per output order and the labelled top harmonics."""

    train: GearTrain
    error: KinematicError
    spectrum: OrderSpectrum
    lines: list[LabelledHarmonic]
    warnings: list[str] = field(default_factory=list)


def analyse(periods, pulses_per_rev: int, train: GearTrain, count: int = 10,
            max_order: int | None = None) -> HarmonicAnalysis:
    """Kinematic error, c_k and phi_k per output order (time-synchronous average over the
    whole revolutions), the ``count`` largest harmonics labelled."""
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise ValueError(f"--top = {count!r}; allowed: an integer >= 1")
    error = kinematic_error(periods, pulses_per_rev)
    warnings = []
    if error.leftover_periods:
        warnings.append(f"the record is not a whole number of output revolutions: the last "
                        f"{error.leftover_periods} period(s) after revolution "
                        f"{error.revolutions} were left out")
    record = angle_domain(error.angle, error.error, pulses_per_rev)
    spectrum = order_spectrum(record.synchronous_average())
    if max_order is not None:
        if isinstance(max_order, bool) or not isinstance(max_order, int) or max_order < 1:
            raise ValueError(f"--max-order = {max_order!r}; allowed: an integer >= 1")
        if max_order > spectrum.nyquist_order:
            warnings.append(f"--max-order {max_order} is above the Nyquist order "
                            f"{spectrum.nyquist_order} of {pulses_per_rev} pulses per "
                            f"revolution: orders above it are not reported (they would be "
                            f"aliases)")
    lines = top_harmonics(spectrum, train.rules(), count, max_order)
    return HarmonicAnalysis(train, error, spectrum, lines, warnings)


def position_locked_periods(harmonics: dict, pulses_per_rev: int, revolutions: int,
                            output_rpm: float) -> np.ndarray:
    """Pulse periods [s] of an output whose angle lags the ideal one by
    ``F(phi) = sum_k A_k cos(k phi)`` (``harmonics``: order -> A_k [rad]); the error is
    locked to the output position (a synthetic record for checks and examples)."""
    phi = 2 * math.pi * np.arange(pulses_per_rev * revolutions + 1) / pulses_per_rev
    F = sum(a * np.cos(k * phi) for k, a in harmonics.items())
    omega = output_rpm * 2 * math.pi / 60
    return np.diff(phi / omega + F / omega)


def read_periods(path: Path) -> np.ndarray:
    """Pulse periods [s] from a CSV: one number per line (first column), optionally under a
    header naming the column: ``period``/``period_s`` (default) or ``timestamp``/``time_s``
    (then the periods are the differences).  Blank lines and ``#`` comments are skipped."""
    text = read_text(path, "--periods", ValueError, kind="CSV", max_bytes=MAX_TABLE_BYTES)
    kind, values = "periods", []
    for number, line in enumerate(text.splitlines(), 1):
        field_ = line.split("#", 1)[0].split(",")[0].strip()
        if not field_:
            continue
        try:
            values.append(float(field_))
        except ValueError:
            header = field_.lower()
            if values or not any(w in header for w in ("period", "time", "stamp")):
                raise ValueError(f"--periods {str(path)!r}: line {number}: {field_!r} is not a "
                                 "number (allowed: numbers, under an optional header "
                                 "'period_s' or 'timestamp_s')") from None
            kind = "periods" if "period" in header else "timestamps"
    values = np.array(values, dtype=float)
    if kind == "timestamps":
        if np.any(~np.isfinite(values)):
            raise ValueError(f"--periods {str(path)!r}: a timestamp is not a finite number")
        values = np.diff(values)
    return values


def error_rows(analysis: HarmonicAnalysis, unit: str) -> list[dict]:
    scale = UNITS[unit]
    e = analysis.error
    return [{"output_angle_deg": float(math.degrees(a)), f"error_{unit}": float(scale * f)}
            for a, f in zip(e.angle, e.error)]


def spectrum_rows(analysis: HarmonicAnalysis, unit: str) -> list[dict]:
    scale = UNITS[unit]
    s = analysis.spectrum
    return [{"order": int(k), f"amplitude_{unit}": float(scale * a),
             "phase_deg": float(math.degrees(p))}
            for k, a, p in zip(s.orders[1:], s.amplitude[1:], s.phase[1:])]


def to_dict(analysis: HarmonicAnalysis, unit: str) -> dict:
    scale, e, t = UNITS[unit], analysis.error, analysis.train
    return {
        "source": "seed 000 (Kapitonov & Drozdov), eqs. (2)-(8) as read in "
                  "shared/reference/seeds_000_002.md",
        "z1": t.z1, "z2": t.z2, "stages": t.stages, "stage_ratio": t.stage_ratio,
        "ratio": t.ratio, "pulses_per_rev": e.pulses_per_rev, "revolutions": e.revolutions,
        "leftover_periods": e.leftover_periods, "mean_period_s": e.mean_period,
        "mean_output_speed_rpm": e.mean_speed_rpm, "unit": unit,
        "peak_to_peak": scale * e.peak_to_peak,
        "nyquist_order": analysis.spectrum.nyquist_order,
        "engagement_orders": [t.engagement_order(s) for s in range(1, t.stages + 1)],
        "harmonics": [dict(line.to_dict(), amplitude=scale * line.amplitude)
                      for line in analysis.lines],
        "warnings": analysis.warnings,
    }


def figure(analysis: HarmonicAnalysis, unit: str):
    """F against the output angle (first revolution) and the amplitude spectrum."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scale, e = UNITS[unit], analysis.error
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6))
    one = slice(0, e.pulses_per_rev + 1)
    top.plot(np.degrees(e.angle[one]), scale * e.error[one], lw=0.8)
    top.set_xlabel("output angle [deg]")
    top.set_ylabel(f"kinematic error F [{unit}]")
    s = analysis.spectrum
    bottom.vlines(s.orders[1:], 0, scale * s.amplitude[1:], lw=0.8)
    for line in analysis.lines:
        bottom.annotate(f"{line.order:g}: {line.label}", (line.order, scale * line.amplitude),
                        fontsize=7, rotation=30)
    bottom.set_xlabel("output order k")
    bottom.set_ylabel(f"c_k [{unit}]")
    for ax in (top, bottom):
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    return fig
