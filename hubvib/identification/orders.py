"""The carrier-locked (deterministic) part of a gearbox record, fitted and removed (SI).

A planetary reducer at constant speed adds to its broadband response lines at every
multiple of the carrier frequency ``f_c``: the mesh orders, their planet-pass sidebands,
the planet-pass and shaft orders.  A record a fraction of a revolution longer or shorter
than whole revolutions puts them between frequency lines, and their leakage (falling only
as 1 / distance) covers the broadband response far from each line.  Here each order's
complex amplitude is fitted by projecting the record on ``exp(i k 2 pi f_c t)`` at the
exact order frequency (orthogonal to within the record's fraction of a revolution) and
subtracted, orders ``1 .. f_s / (2 f_c)``: what remains is the broadband (ambient) part
that operational modal analysis identifies.
"""
from __future__ import annotations

import math

import numpy as np

#: samples per chunk of the projection
CHUNK = 1 << 16


def order_amplitudes(values: np.ndarray, sample_rate: float, carrier_hz: float,
                     max_order: int | None = None) -> np.ndarray:
    """Complex amplitude of carrier orders 1 .. max_order (default: below Nyquist) [same
    unit as ``values``]: ``x(t) ~ Re sum_k A_k exp(i k 2 pi f_c t)``."""
    x = np.asarray(values, dtype=float)
    x = x - x.mean()
    top = int(math.floor(0.5 * sample_rate / carrier_hz - 1e-9))
    top = top if max_order is None else min(top, int(max_order))
    orders = np.arange(1, top + 1)
    total = np.zeros(top, dtype=complex)
    for lo in range(0, x.size, CHUNK):
        t = np.arange(lo, min(lo + CHUNK, x.size)) / sample_rate
        phase = np.exp(-2j * math.pi * carrier_hz * np.outer(orders, t))
        total += phase @ x[lo:lo + CHUNK]
    return 2 * total / x.size


def remove_orders(values: np.ndarray, sample_rate: float, carrier_hz: float,
                  max_order: int | None = None) -> np.ndarray:
    """``values`` less its carrier-locked part (:func:`order_amplitudes`) and mean."""
    if not (math.isfinite(carrier_hz) and carrier_hz > 0):
        raise ValueError(f"carrier_hz = {carrier_hz!r}; allowed: > 0")
    x = np.asarray(values, dtype=float)
    A = order_amplitudes(x, sample_rate, carrier_hz, max_order)
    orders = np.arange(1, A.size + 1)
    out = x - x.mean()
    for lo in range(0, x.size, CHUNK):
        t = np.arange(lo, min(lo + CHUNK, x.size)) / sample_rate
        out[lo:lo + CHUNK] -= (A @ np.exp(2j * math.pi * carrier_hz * np.outer(orders, t))).real
    return out
