"""Condition indicators of a time-synchronous average (TSA) over one carrier revolution.

Definitions follow the review of Lebold et al. 2000 ("Review of vibration analysis
methods for gearbox diagnostics and prognostics", 54th MFPT), adapted to a
planetary stage seen from a sensor on the ring.  There, for N equally spaced
planets, the line at the mesh order ``m z_r`` itself cancels and the dominant
line of mesh harmonic m is the multiple of N nearest to ``m z_r`` (McFadden &
Smith 1985); that line and ``m z_r`` are the *mesh components*, the multiples of
N next to them on either side the *first-order sidebands*.

- RMS, kurtosis ``mean(x^4) / mean(x^2)^2`` and crest factor ``max|x| / RMS`` of
  the TSA with its mean removed.
- FM0 = peak-to-peak of the TSA / sum of the mesh-component amplitudes (Stewart 1977).
- FM4 = kurtosis of the *difference* signal: TSA minus shaft orders (1, 2), mesh
  components and first-order sidebands.
- NA4 = fourth moment of the *residual* signal (TSA minus shaft orders and mesh
  components) over the squared mean variance of the residuals of the run so far
  (the ensemble: the intact records and every depth up to this one).
- SER (sideband energy ratio) = sum of the 6 sidebands at ``+-n N`` around each
  mesh component / sum of the mesh components, harmonics 1..H.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

INDICATORS = ("rms", "kurtosis", "crest_factor", "fm0", "fm4", "na4", "ser")
SHAFT_ORDERS = (1, 2)
SER_SIDEBANDS = 6


@dataclass(frozen=True)
class GearOrders:
    """What the indicators need to know of the stage: z_r, N, harmonics analysed."""

    ring_teeth: int
    n_planets: int
    harmonics: int

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
    """Values of one record [unit of the signal where it has one, else -]."""

    rms: float
    kurtosis: float
    crest_factor: float
    fm0: float
    fm4: float
    na4: float
    ser: float

    def to_dict(self) -> dict:
        return asdict(self)


def _kurtosis(x: np.ndarray) -> float:
    x = x - x.mean()
    return float(np.mean(x ** 4) / np.mean(x ** 2) ** 2)


def without_orders(tsa: np.ndarray, orders) -> np.ndarray:
    """The TSA with these orders removed (their Fourier coefficients set to 0)."""
    X = np.fft.rfft(tsa)
    keep = [k for k in orders if 0 < k < X.size]
    X[keep] = 0.0
    return np.fft.irfft(X, n=tsa.size)


def amplitudes(tsa: np.ndarray, orders) -> np.ndarray:
    """c_k of these orders (2 |FFT_k| / P)."""
    X = np.fft.rfft(tsa)
    return np.array([2 * abs(X[k]) / tsa.size if 0 < k < X.size else 0.0 for k in orders])


def residual(tsa: np.ndarray, gear: GearOrders) -> np.ndarray:
    """TSA minus shaft orders and mesh components (NA4's signal)."""
    mesh = [k for c in gear.mesh_components() for k in c]
    return without_orders(tsa, list(SHAFT_ORDERS) + mesh)


def indicators(tsa: np.ndarray, gear: GearOrders, residual_variances) -> Indicators:
    """Every indicator of one TSA; ``residual_variances`` are those of the run so far
    (including this record's, ``np.var(residual(tsa, gear))``)."""
    x = tsa - tsa.mean()
    rms = float(np.sqrt(np.mean(x ** 2)))
    mesh = [k for c in gear.mesh_components() for k in c]
    dominant = gear.dominant()
    first = gear.sidebands(1)
    difference = without_orders(tsa, list(SHAFT_ORDERS) + mesh + first)
    r = residual(tsa, gear)
    r = r - r.mean()
    ensemble = float(np.mean(residual_variances))
    central = amplitudes(tsa, dominant).sum()
    ser = amplitudes(tsa, gear.sidebands(SER_SIDEBANDS)).sum() / central if central else math.inf
    return Indicators(
        rms=rms, kurtosis=_kurtosis(x), crest_factor=float(np.max(np.abs(x)) / rms),
        fm0=float((tsa.max() - tsa.min()) / amplitudes(tsa, mesh).sum()),
        fm4=_kurtosis(difference), na4=float(np.mean(r ** 4) / ensemble ** 2), ser=float(ser))
