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

from dataclasses import dataclass

import numpy as np

from .bfft import IdentificationError, IdentifiedMode, identify_mode
from .law import KAPPA
from .records import Record

#: fewest band half-widths (in zeta f) a mode needs free of neighbours: closer ones leak
#: into the band and bias a single-mode fit
MIN_KAPPA = 3.0


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
    """

    index: tuple
    modes: tuple
    skipped: dict


def identifiable(predicted_hz, damping_ratio: float, record: Record) -> tuple[dict, dict]:
    """Band half-width ``kappa`` [-] per identifiable predicted mode, and the reason per
    skipped one."""
    f = np.asarray(predicted_hz, dtype=float)
    kappas, skipped = {}, {}
    nyquist = 0.5 * record.sample_rate
    for i, fi in enumerate(f):
        others = np.delete(f, i)
        gap = np.abs(others - fi).min() if others.size else np.inf
        width = damping_ratio * fi
        kappa = min(KAPPA, 0.5 * gap / width)
        if fi <= 0:
            skipped[i] = "rigid-body mode"
        elif gap < 2 * width:
            skipped[i] = (f"within {gap:.3g} Hz of another mode, inside its half-power "
                          f"bandwidth {2 * width:.3g} Hz (close modes)")
        elif kappa < MIN_KAPPA:
            skipped[i] = (f"a neighbour {gap:.3g} Hz away leaves a band of only "
                          f"{kappa:.2g} zeta f (at least {MIN_KAPPA:g} needed)")
        elif fi * (1 + kappa * damping_ratio) >= nyquist:
            skipped[i] = f"above the Nyquist frequency {nyquist:g} Hz of the record"
        elif 2 * kappa * width * record.duration < 8:
            skipped[i] = (f"fewer than 8 frequency lines in its band for a "
                          f"{record.duration:g} s record")
        else:
            kappas[i] = kappa
    return kappas, skipped


def identify_modes(record: Record, predicted_hz, damping_ratio: float,
                   acceleration: bool = True, lines: bool = False) -> ModeIdentification:
    """Identify every identifiable predicted mode [Hz] in ``record``; ``lines``: leave the
    spectral lines of a running machine out of each band (:func:`.bfft.line_mask`)."""
    kappas, skipped = identifiable(predicted_hz, damping_ratio, record)
    index, modes = [], []
    for i in sorted(kappas):
        try:
            modes.append(identify_mode(record.values, record.sample_rate,
                                       float(predicted_hz[i]), damping_ratio, kappas[i],
                                       acceleration, lines))
            index.append(i)
        except IdentificationError as exc:
            skipped[i] = str(exc)
    return ModeIdentification(tuple(index), tuple(modes), skipped)
