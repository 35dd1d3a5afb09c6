"""Spectral analysis of rotating-machine signals in orders of a reference rotation.

Shared by the vibration signature (orders of the carrier) and the kinematic-error
harmonics of seed 000 (orders of the output shaft).  Conventions (seed 000,
eqs. 5-8 in the form that rebuilds the signal):

    F(phi) = c_0 / 2 + sum_k c_k cos(k phi + phi_k),   c_k = sqrt(a_k^2 + b_k^2),
    a_k = (1/pi) int F cos(k phi) dphi,  b_k = (1/pi) int F sin(k phi) dphi,
    phi_k = atan2(-b_k, a_k),

so on P equal angle steps ``c_k = 2 |FFT_k| / P`` and ``phi_k = arg FFT_k``.  Orders
need ``P > 2 k``; a signal is first resampled onto the angle of the reference
rotation (``angle_domain``) and cut to whole revolutions.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.signal import spectrogram as scipy_spectrogram


@dataclass(frozen=True)
class OrderSpectrum:
    """Fourier amplitude and phase per integer order of one revolution.

    Attributes
    ----------
    orders : ndarray of int
        0, 1, ..., P // 2 (the Nyquist order excluded when P is even).
    amplitude : ndarray
        c_k [unit of the signal]; c_0 is twice the mean.
    phase : ndarray
        phi_k [rad].
    """

    orders: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray

    @property
    def nyquist_order(self) -> int:
        """Highest order the revolution resolves (< P / 2)."""
        return int(self.orders[-1])

    def amplitude_of(self, order: int) -> float:
        return float(self.amplitude[order])

    def rebuild(self, points: int) -> np.ndarray:
        """F at ``points`` equal angles of one revolution from c_k, phi_k (seed 000 eq. 5)."""
        phi = 2 * math.pi * np.arange(points) / points
        k = self.orders[1:, None]
        return self.amplitude[0] / 2 + (self.amplitude[1:, None]
                                        * np.cos(k * phi[None] + self.phase[1:, None])).sum(0)


def order_spectrum(one_revolution: np.ndarray) -> OrderSpectrum:
    """c_k and phi_k of a signal on P equal angle steps of one revolution."""
    P = one_revolution.size
    X = np.fft.rfft(one_revolution)
    top = (P - 1) // 2  # orders strictly below P / 2
    X = X[:top + 1]
    amplitude = 2 * np.abs(X) / P
    phase = np.angle(X)
    amplitude[0], phase[0] = 2 * X[0].real / P, 0.0
    return OrderSpectrum(np.arange(top + 1), amplitude, phase)


@dataclass(frozen=True)
class AngleRecord:
    """A signal on a uniform grid of the reference angle, whole revolutions only.

    Attributes
    ----------
    values : ndarray (R, P)
        R revolutions of P points each, starting at ``start_angle``.
    start_angle : float
        [rad]
    leftover : float
        Fraction of a revolution at the end of the record that was dropped [-].
    """

    values: np.ndarray
    start_angle: float
    leftover: float

    @property
    def revolutions(self) -> int:
        return self.values.shape[0]

    def synchronous_average(self) -> np.ndarray:
        """Time-synchronous average: the mean revolution (P,)."""
        return self.values.mean(axis=0)


def angle_domain(angle: np.ndarray, values: np.ndarray, points_per_rev: int) -> AngleRecord:
    """Resample ``values`` given at increasing ``angle`` [rad] onto ``points_per_rev`` equal
    steps per revolution (cubic spline; exact at the given points), whole revolutions only.

    Raises
    ------
    ValueError
        Fewer than one whole revolution, or ``angle`` not increasing.
    """
    angle = np.asarray(angle, dtype=float)
    values = np.asarray(values, dtype=float)
    if angle.size < 4 or np.any(np.diff(angle) <= 0):
        raise ValueError("angle: allowed a strictly increasing sequence of >= 4 points")
    span = (angle[-1] - angle[0]) / (2 * math.pi)
    whole = int(math.floor(span + 1e-9))
    if whole < 1:
        raise ValueError(f"the record covers {span:.3g} revolutions; allowed: >= 1")
    grid = angle[0] + 2 * math.pi * np.arange(whole * points_per_rev) / points_per_rev
    on_grid = CubicSpline(angle, values)(grid)
    return AngleRecord(on_grid.reshape(whole, points_per_rev), float(angle[0]),
                       float(span - whole))


@dataclass(frozen=True)
class RecordSpectrum:
    """Amplitude spectrum of a whole record in (fractional) orders, resolution 1 / R."""

    orders: np.ndarray
    amplitude: np.ndarray

    def frequency_hz(self, rotation_hz: float) -> np.ndarray:
        """The orders as frequencies [Hz] at this rotation frequency."""
        return self.orders * rotation_hz


def record_spectrum(record: AngleRecord) -> RecordSpectrum:
    """Amplitude spectrum of all revolutions together (one-sided, c_k convention)."""
    flat = record.values.reshape(-1)
    X = np.fft.rfft(flat)
    amplitude = 2 * np.abs(X) / flat.size
    amplitude[0] /= 2
    return RecordSpectrum(np.arange(X.size) / record.revolutions, amplitude)


@dataclass(frozen=True)
class Spectrogram:
    """Short-time amplitude spectrum: ``amplitude[f, t]`` [unit of the signal]."""

    time_s: np.ndarray
    frequency_hz: np.ndarray
    amplitude: np.ndarray


def spectrogram(values: np.ndarray, sample_rate: float, segment: int) -> Spectrogram:
    """Hann-windowed short-time spectrum, ``segment`` samples per window, 75 % overlap."""
    f, t, S = scipy_spectrogram(values, fs=sample_rate, window="hann", nperseg=segment,
                                noverlap=3 * segment // 4, scaling="spectrum",
                                mode="magnitude")
    return Spectrogram(t, f, 2 * S)


# --- harmonic labelling --------------------------------------------------------
@dataclass(frozen=True)
class HarmonicRule:
    """Orders ``m * base + n * spacing`` with m in 1..max_multiple, |n| <= max_sideband.

    ``label`` names the base (``"z_r"``), ``spacing_label`` the spacing (``"N"``).
    """

    label: str
    base: float
    max_multiple: int = 10 ** 6
    spacing: float = 0.0
    spacing_label: str = ""
    max_sideband: int = 0
    meaning: str = ""

    def match(self, order: float, tolerance: float = 1e-6) -> str | None:
        """The label of ``order`` under this rule, or None."""
        for n in sorted(range(-self.max_sideband, self.max_sideband + 1), key=abs):
            rest = order - n * self.spacing
            m = round(rest / self.base)
            if 1 <= m <= self.max_multiple and abs(rest - m * self.base) <= tolerance * max(
                    1.0, abs(order)):
                text = self.label if m == 1 else f"{m}x{self.label}"
                if n:
                    text += f" {'+' if n > 0 else '-'} {abs(n)}x{self.spacing_label}" \
                        if abs(n) != 1 else f" {'+' if n > 0 else '-'} {self.spacing_label}"
                return text
        return None


@dataclass(frozen=True)
class SidebandRule:
    """Multiples of ``spacing`` within half a ``base`` of a multiple ``m * base``
    (sidebands of harmonic m, m >= 1), labelled ``"21xN (z_r - 1)"``."""

    label: str
    base: float
    spacing: float
    spacing_label: str
    meaning: str = ""

    def match(self, order: float, tolerance: float = 1e-6) -> str | None:
        n = round(order / self.spacing)
        m = round(order / self.base)
        if m < 1 or abs(order - n * self.spacing) > tolerance * max(1.0, abs(order)):
            return None
        offset = order - m * self.base
        if abs(offset) <= tolerance * max(1.0, abs(order)) or abs(offset) > self.base / 2:
            return None
        centre = self.label if m == 1 else f"{m}x{self.label}"
        return f"{n}x{self.spacing_label} ({centre} {'+' if offset > 0 else '-'} {abs(offset):g})"


UNEXPLAINED = "unexplained"


@dataclass(frozen=True)
class LabelledHarmonic:
    """One spectral line with what explains it (``UNEXPLAINED`` when no rule fits)."""

    order: float
    amplitude: float
    phase: float
    label: str
    meaning: str = ""
    also: tuple[str, ...] = field(default=())

    def to_dict(self) -> dict:
        return {"order": float(self.order), "amplitude": float(self.amplitude),
                "phase_deg": float(math.degrees(self.phase)), "label": self.label,
                "meaning": self.meaning, "also": list(self.also)}


def label_order(order: float, rules) -> tuple[str, str, tuple[str, ...]]:
    """(label, meaning, other matching labels) of ``order``; the first matching rule wins."""
    hits = [(text, rule.meaning) for rule in rules if (text := rule.match(order)) is not None]
    if not hits:
        return UNEXPLAINED, "", ()
    return hits[0][0], hits[0][1], tuple(text for text, _ in hits[1:])


def top_harmonics(spectrum: OrderSpectrum, rules, count: int, max_order: int | None = None,
                  relative_floor: float = 1e-9) -> list[LabelledHarmonic]:
    """The ``count`` largest orders >= 1 (and <= ``max_order``), largest first, labelled.

    Lines below ``relative_floor`` times the largest are left out (round-off)."""
    top = spectrum.nyquist_order if max_order is None else min(max_order,
                                                               spectrum.nyquist_order)
    orders = spectrum.orders[1:top + 1]
    amplitude = spectrum.amplitude[1:top + 1]
    if amplitude.size == 0:
        return []
    order = np.argsort(-amplitude, kind="stable")[:count]
    floor = relative_floor * amplitude.max()
    out = []
    for i in order:
        if amplitude[i] <= floor:
            break
        label, meaning, also = label_order(float(orders[i]), rules)
        out.append(LabelledHarmonic(float(orders[i]), float(amplitude[i]),
                                    float(spectrum.phase[orders[i]]), label, meaning, also))
    return out
