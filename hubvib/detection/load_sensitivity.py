"""What the elastic ring's answer rests on that is not known: the crack's closure gap and
the load's size (SI).

Under the working load the crack's faces open and close as the planets pass
(``hubvib.elastic.loaded``); with a closure gap (roughness, residual compression of a
case-hardened root: the faces separate only where the free opening exceeds it) the state
depends on the torque.  Each case of the sweep carries its pitch spectra for the torque
fractions ``TORQUE_FRACTIONS`` and gaps ``CLOSURE_GAPS``; per variant this gives the
smallest detectable depth per record length, from the same cases, the same watched-mode
rule and the nominal reducer's POD (identification noise only: the Monte Carlo of the
main answer, over parameter scatter, is not repeated per variant).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from hubvib.elastic.loaded import CLOSURE_GAPS, TORQUE_FRACTIONS
from hubvib.foundation.output import explained, finite_or_none

from .elastic_model import RecordLoad, elastic_result

__all__ = ["LoadVariant", "load_sensitivity"]


@dataclass(frozen=True)
class LoadVariant:
    """One load variant's answer.

    ``torque_fraction`` of the design's sun torque [-], ``gap`` [m]; ``answer``: record
    length [s] -> the POD crossing in words; ``open_share``: per depth the share of
    carrier positions with the faces apart [-] (NaN: intact); ``watched``: the alarm
    family's labels; ``depths`` [m]."""

    torque_fraction: float
    gap: float
    answer: dict
    open_share: tuple
    watched: tuple
    depths: tuple

    def to_dict(self) -> dict:
        return explained(
            {"torque_fraction": self.torque_fraction, "closure_gap_m": self.gap,
             "answer": {f"{t:g}": words for t, words in self.answer.items()},
             "open_share": [finite_or_none(x) for x in self.open_share],
             "watched": list(self.watched), "depths_m": list(self.depths)},
            open_share="null at a depth without a loaded state (intact: no crack faces; or "
                       "the faces open at every position, through the rim)")


def load_sensitivity(design, depths, crack_of, scene, options, cases) -> tuple:
    """A :class:`LoadVariant` per closure gap and torque fraction the cases carry (zero
    gap once: its state does not depend on the torque's size), over ``depths`` [m] and
    their ``cases`` (``ElasticCase``, the first intact)."""
    nominal = replace(options, samples=0)
    out = []
    for gap in CLOSURE_GAPS:
        for fraction in (TORQUE_FRACTIONS[:1] if gap == 0 else TORQUE_FRACTIONS):
            result = elastic_result(design, depths, crack_of, scene, nominal, cases,
                                    load=RecordLoad(float(fraction), float(gap)))
            out.append(LoadVariant(
                float(fraction), float(gap), {t: result.answer(t) for t in result.lengths},
                tuple(float(x) for x in np.asarray(result.detail.open_share)),
                tuple(result.watched_labels()), tuple(result.depths)))
    return tuple(out)
