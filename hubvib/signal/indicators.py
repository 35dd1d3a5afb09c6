"""Condition indicators of a time-synchronous average (TSA) over one carrier revolution.

Definitions of Lebold et al. 2000 ("Review of vibration analysis methods for gearbox
diagnostics and prognostics", 54th MFPT, pp. 623-634; after Stewart 1977 and
Zakrajsek et al. 1993), adapted to a planetary stage seen from a sensor on the ring.
For N equally spaced planets the line at the mesh order ``m z_r`` itself cancels and
the dominant line of mesh harmonic m is the multiple of N nearest to ``m z_r``
(McFadden & Smith 1985); that line and ``m z_r`` are the *mesh components*, the
multiples of N next to them on either side the *first-order sidebands*.

Signals (every mesh harmonic in the analysis band, not only the first few):

- *regular* signal ``y``: shaft orders (1, 2), the mesh components of every
  harmonic in the band and their first-order sidebands;
- *difference* signal ``d = TSA - y``;
- *residual* signal ``r``: TSA minus shaft orders and mesh components;
- *envelope* ``s``: modulus of the analytic signal of the TSA band-passed to
  ``+- z_r / 2`` orders about the dominant line of the first mesh harmonic.

Indicators (``x`` centred on its mean, ``<.>`` the mean over the P points):

- RMS, kurtosis ``<x^4> / <x^2>^2``, crest factor ``max|x| / RMS`` of the TSA;
- FM0 = peak-to-peak of the TSA / sum of the mesh-component amplitudes;
- FM4 = ``<d^4> / <d^2>^2``; M6A = ``<d^6> / <d^2>^3``; M8A = ``<d^8> / <d^2>^4``;
- NA4 = ``<r^4> / (mean variance of the residuals of the run so far)^2`` (the
  ensemble: the intact records and every depth up to this one);
- NB4 = the same with the envelope ``s`` instead of ``r``;
- ER (energy ratio) = RMS(d) / RMS(y);
- SER (sideband energy ratio) = sum of the 6 sidebands at ``+-n N`` around each
  dominant line / sum of the dominant lines, harmonics 1..H (``mesh_harmonics``).

With ``band`` > 0 the TSA is low-passed to orders <= ``band`` before any of them.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace

import numpy as np

INDICATORS = ("rms", "kurtosis", "crest_factor", "fm0", "fm4", "na4", "nb4", "m6a", "m8a",
              "er", "ser")
SHAFT_ORDERS = (1, 2)
SER_SIDEBANDS = 6


@dataclass(frozen=True)
class GearOrders:
    """What the indicators need to know of the stage.

    Attributes
    ----------
    ring_teeth, n_planets : int
        z_r, N.
    harmonics : int
        Mesh harmonics of SER (1..H).
    band : int
        Highest carrier order kept in the indicators (0: every order of the TSA).
    """

    ring_teeth: int
    n_planets: int
    harmonics: int
    band: int = 0

    def top(self, points: int) -> int:
        """Highest order analysed in a TSA of ``points`` samples."""
        nyquist = (points - 1) // 2
        return min(self.band, nyquist) if self.band else nyquist

    def in_band(self, points: int) -> "GearOrders":
        """The same stage with every mesh harmonic whose components reach the band."""
        return replace(self, harmonics=max(1, (self.top(points) + self.n_planets)
                                           // self.ring_teeth))

    def mesh_components(self) -> list[tuple[int, ...]]:
        """Per mesh harmonic m: (m z_r and the multiple of N nearest to it)."""
        out = []
        for m in range(1, self.harmonics + 1):
            mesh = m * self.ring_teeth
            nearest = self.n_planets * round(mesh / self.n_planets)
            if abs(nearest - mesh) * 2 == self.n_planets:  # a tie: take the lower one
                nearest = mesh - self.n_planets // 2
            out.append(tuple(sorted({mesh, nearest})))
        return out

    def dominant(self) -> list[int]:
        """The dominant (planet-pass) line of each mesh harmonic."""
        return [c[-1] if c[-1] % self.n_planets == 0 else c[0] for c in self.mesh_components()]

    def sidebands(self, count: int) -> list[int]:
        """Orders ``dominant +- n N``, n = 1..count, of every harmonic."""
        out = []
        for centre in self.dominant():
            for n in range(1, count + 1):
                out += [centre - n * self.n_planets, centre + n * self.n_planets]
        return [k for k in out if k > 0]


@dataclass(frozen=True)
class Indicators:
    """Values of one record [unit of the signal for RMS, else -]."""

    rms: float
    kurtosis: float
    crest_factor: float
    fm0: float
    fm4: float
    na4: float
    nb4: float
    m6a: float
    m8a: float
    er: float
    ser: float

    def to_dict(self) -> dict:
        return asdict(self)


def _moment_ratio(x: np.ndarray, power: int) -> float:
    """``<x^p> / <x^2>^(p/2)`` of x centred on its mean [-]."""
    x = x - x.mean()
    variance = np.mean(x ** 2)
    if variance == 0:
        raise ValueError("a constant signal has no normalised moment (variance 0)")
    return float(np.mean(x ** power) / variance ** (power // 2))


def without_orders(tsa: np.ndarray, orders) -> np.ndarray:
    """The TSA with these orders removed (their Fourier coefficients set to 0)."""
    X = np.fft.rfft(tsa)
    keep = [k for k in orders if 0 < k < X.size]
    X[keep] = 0.0
    return np.fft.irfft(X, n=tsa.size)


def only_orders(tsa: np.ndarray, orders) -> np.ndarray:
    """The part of the TSA at these orders."""
    return tsa - without_orders(tsa, orders)


def band_limited(tsa: np.ndarray, top: int) -> np.ndarray:
    """The TSA with every order above ``top`` removed."""
    X = np.fft.rfft(tsa)
    X[top + 1:] = 0.0
    return np.fft.irfft(X, n=tsa.size)


def amplitudes(tsa: np.ndarray, orders) -> np.ndarray:
    """c_k of these orders (2 |FFT_k| / P)."""
    X = np.fft.rfft(tsa)
    return np.array([2 * abs(X[k]) / tsa.size if 0 < k < X.size else 0.0 for k in orders])


def _mesh(gear: GearOrders) -> list[int]:
    return sorted({k for c in gear.mesh_components() for k in c})


def regular_signal(tsa: np.ndarray, gear: GearOrders) -> np.ndarray:
    """Shaft orders, every mesh component in the band and their first sidebands."""
    full = gear.in_band(tsa.size)
    return only_orders(tsa, set(SHAFT_ORDERS) | set(_mesh(full)) | set(full.sidebands(1)))


def difference_signal(tsa: np.ndarray, gear: GearOrders) -> np.ndarray:
    """TSA minus the regular signal (FM4, M6A, M8A, ER)."""
    return tsa - regular_signal(tsa, gear)


def residual(tsa: np.ndarray, gear: GearOrders) -> np.ndarray:
    """TSA minus shaft orders and every mesh component in the band (NA4's signal)."""
    full = gear.in_band(tsa.size)
    return without_orders(tsa, list(SHAFT_ORDERS) + _mesh(full))


def envelope(tsa: np.ndarray, gear: GearOrders) -> np.ndarray:
    """Envelope of the TSA band-passed to ``+- z_r / 2`` about the first dominant line
    (NB4's signal): modulus of the analytic signal."""
    P = tsa.size
    centre = gear.dominant()[0]
    half = gear.ring_teeth // 2
    X = np.fft.fft(tsa)
    analytic = np.zeros(P, dtype=complex)
    low, high = max(1, centre - half), min(centre + half, (P - 1) // 2)
    analytic[low:high + 1] = 2 * X[low:high + 1]
    return np.abs(np.fft.ifft(analytic))


def prepared(tsa: np.ndarray, gear: GearOrders) -> np.ndarray:
    """The TSA as the indicators see it (band-limited when ``gear.band`` > 0)."""
    return band_limited(tsa, gear.band) if gear.band else np.asarray(tsa, dtype=float)


def ensemble_variances(tsa: np.ndarray, gear: GearOrders) -> tuple[float, float]:
    """(variance of the residual, variance of the envelope) of one TSA, for NA4 / NB4."""
    x = prepared(tsa, gear)
    return float(np.var(residual(x, gear))), float(np.var(envelope(x, gear)))


def indicators(tsa: np.ndarray, gear: GearOrders, residual_variances,
               envelope_variances=None) -> Indicators:
    """Every indicator of one TSA; ``residual_variances`` (and ``envelope_variances``)
    are those of the run so far, this record's included (see :func:`ensemble_variances`);
    without ``envelope_variances`` NB4 uses this record's own."""
    tsa = prepared(tsa, gear)
    x = tsa - tsa.mean()
    rms = float(np.sqrt(np.mean(x ** 2)))
    full = gear.in_band(tsa.size)
    d = difference_signal(tsa, gear)
    y = regular_signal(tsa, gear)
    r = residual(tsa, gear)
    r = r - r.mean()
    s = envelope(tsa, gear)
    s = s - s.mean()
    ensemble = float(np.mean(residual_variances))
    envelope_ensemble = float(np.mean(envelope_variances)) if envelope_variances is not None \
        else float(np.mean(s ** 2))
    central = amplitudes(tsa, gear.dominant()).sum()
    ser = amplitudes(tsa, gear.sidebands(SER_SIDEBANDS)).sum() / central if central else math.inf
    y = y - y.mean()
    return Indicators(
        rms=rms, kurtosis=_moment_ratio(x, 4), crest_factor=float(np.max(np.abs(x)) / rms),
        fm0=float((tsa.max() - tsa.min()) / amplitudes(tsa, _mesh(full)).sum()),
        fm4=_moment_ratio(d, 4), na4=float(np.mean(r ** 4) / ensemble ** 2),
        nb4=float(np.mean(s ** 4) / envelope_ensemble ** 2) if envelope_ensemble else math.inf,
        m6a=_moment_ratio(d, 6), m8a=_moment_ratio(d, 8),
        er=float(np.sqrt(np.mean((d - d.mean()) ** 2)) / np.sqrt(np.mean(y ** 2))),
        ser=float(ser))
