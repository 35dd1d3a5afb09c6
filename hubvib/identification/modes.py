"""The natural frequencies of known modes from one record, each with its uncertainty (SI).

A mode is identified on its own (:mod:`.bfft`) in a band around its predicted
frequency.  The band is narrowed so that it holds no other predicted mode
(half-width at most half the gap to the nearest one, and at most
``KAPPA zeta f``); a mode closer than ``2 zeta f`` (its half-power bandwidth) to
another cannot be told apart from it by a single-mode method, and one whose band
would be narrower than ``MIN_KAPPA zeta f`` picks up its neighbour's tail: both
are skipped, as
is one whose fit finds no resonance in its band (Au et al. 2021, "Understanding and managing identification uncertainty of close
modes in operational modal analysis", MSSP 147).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .bfft import IdentificationError, IdentifiedMode, identify_mode
from .law import KAPPA
from .records import Record

#: fewest band half-widths (in zeta f) a mode needs free of neighbours: closer ones leak
#: into the band and bias a single-mode fit
MIN_KAPPA = 3.0
#: fewest frequency lines a band needs
MIN_LINES = 8
#: what lets a mode whose fit found no resonance be identified
MORE_FORCING = ("broadband (ambient) forcing that lifts its resonance above the measurement "
                "noise and the mesh lines, or a longer record")
#: why one of a degenerate pair is skipped (``other``: the pair's other mode, 1-based)
DEGENERATE = ("at the frequency of mode {other} (close modes: a degenerate pair, which a "
              "single-mode fit cannot separate)")
#: what lets one of a degenerate pair be identified
CLOSE_MODE_METHOD = ("a close-mode (multi-sensor) identification, which hubvib does not "
                     "ship; a crack that splits the pair by more than its bandwidth")


def _down(value: float) -> str:
    """``value`` > 0 rounded down to three significant digits (a bound that holds as
    printed)."""
    step = 10.0 ** (math.floor(math.log10(value)) - 2)
    count = math.floor(value / step)
    if count * step > value:  # value / step rounded up to a whole number
        count -= 1
    return f"{count * step:.3g}"


@dataclass(frozen=True)
class ModeIdentification:
    """Identified modes of one record.

    Attributes
    ----------
    index : tuple of int
        Predicted modes identified (0-based, into the predicted frequencies).
    modes : tuple of IdentifiedMode
        Their identification, in the same order.
    skipped : dict
        Predicted mode (0-based) -> why it was not identified.
    helps : dict
        Skipped mode (0-based) -> what would make it identifiable (record length, damping,
        sample rate, forcing), in a few words.
    """

    index: tuple
    modes: tuple
    skipped: dict
    helps: dict = field(default_factory=dict)


def _screen(predicted_hz, damping_ratio: float, record: Record):
    """Band half-width per identifiable mode; reason and remedy per skipped one."""
    f = np.asarray(predicted_hz, dtype=float)
    kappas, skipped, helps = {}, {}, {}
    nyquist = 0.5 * record.sample_rate
    for i, fi in enumerate(f):
        others = np.delete(f, i)
        gap = np.abs(others - fi).min() if others.size else np.inf
        nearest = int(np.argmin(np.abs(others - fi))) if others.size else 0
        nearest += nearest >= i  # its index into f
        width = damping_ratio * fi
        kappa = min(KAPPA, 0.5 * gap / width)
        separating = 100 * gap / (2 * MIN_KAPPA * fi)  # damping [%] that frees the band
        if fi <= 0:
            skipped[i], helps[i] = "rigid-body mode", ""
        elif gap < 2 * width:
            if gap <= 1e-9 * fi:
                skipped[i] = DEGENERATE.format(other=nearest + 1)
                helps[i] = CLOSE_MODE_METHOD
            else:
                skipped[i] = (f"within {gap:.3g} Hz of mode {nearest + 1}, inside its half-"
                              f"power bandwidth {2 * width:.3g} Hz (close modes)")
                helps[i] = f"modal damping below {_down(separating)} %"
        elif kappa < MIN_KAPPA:
            skipped[i] = (f"mode {nearest + 1}, a neighbour {gap:.3g} Hz away, leaves a band "
                          f"of only {_down(kappa)} zeta f (at least {MIN_KAPPA:g} needed)")
            helps[i] = f"modal damping below {_down(separating)} %"
        elif fi * (1 + kappa * damping_ratio) >= nyquist:
            skipped[i] = f"above the Nyquist frequency {nyquist:g} Hz of the record"
            helps[i] = (f"a sample rate above {2 * fi * (1 + kappa * damping_ratio):.4g} Hz")
        elif 2 * kappa * width * record.duration < MIN_LINES:
            skipped[i] = (f"fewer than {MIN_LINES} frequency lines in its band for a "
                          f"{record.duration:g} s record")
            helps[i] = f"records of at least {MIN_LINES / (2 * kappa * width):.3g} s"
        else:
            kappas[i] = kappa
    return kappas, skipped, helps


def identifiable(predicted_hz, damping_ratio: float, record: Record) -> tuple[dict, dict]:
    """Band half-width ``kappa`` [-] per identifiable predicted mode, and the reason per
    skipped one."""
    kappas, skipped, _ = _screen(predicted_hz, damping_ratio, record)
    return kappas, skipped


def identify_modes(record: Record, predicted_hz, damping_ratio: float,
                   acceleration: bool = True, lines: bool = False) -> ModeIdentification:
    """Identify every identifiable predicted mode [Hz] in ``record``; ``lines``: leave the
    spectral lines of a running machine out of each band (:func:`.bfft.line_mask`)."""
    kappas, skipped, helps = _screen(predicted_hz, damping_ratio, record)
    index, modes = [], []
    for i in sorted(kappas):
        try:
            modes.append(identify_mode(record.values, record.sample_rate,
                                       float(predicted_hz[i]), damping_ratio, kappas[i],
                                       acceleration, lines))
            index.append(i)
        except IdentificationError as exc:
            skipped[i], helps[i] = str(exc), MORE_FORCING
    return ModeIdentification(tuple(index), tuple(modes), skipped, helps)
