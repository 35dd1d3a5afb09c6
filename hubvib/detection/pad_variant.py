"""What the elastic ring's answer rests on that the scene fixes: where the cracked tooth
lies against the support pads (SI).

The same crack at the counterpart tooth (:func:`.pad_position.counterpart_tooth`: between
pads for a crack on a pad, on a pad for one between them), the sensor at the same place
from the cracked tooth (as records place it), the planets placed from it as for the
scene's tooth.  Its intact ring is computed anew: the pads do not repeat at that turn
(:func:`.pad_position.layout_repeats`).  To keep it cheap the counterpart is solved on the
scene's depths only, shallowest first, until every record length's POD crossing is found
(no bisection): its answer is the bracket those depths give ("between 3 and 6 mm"),
set beside the scene's tooth on the same depths (read from the main answer's POD there).
The counterpart goes through :func:`.elastic_model.elastic_result` with the main answer's
options (Monte Carlo reducers and watched-mode rule): one detection path.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubvib.foundation.output import finite_or_none

from .resolution import bracket
from .pad_position import PadPosition, counterpart_tooth, crack_position, moved_crack

__all__ = ["PadVariant", "pad_variant", "PAD_SOLVED"]

#: how the counterpart's depths are chosen, in words
PAD_SOLVED = ("the scene's depths only, shallowest first, until every record length's "
              "POD crossing is found; no depths added between them")


@dataclass(frozen=True)
class PadVariant:
    """The answer with the crack on a pad and between pads.

    ``scene_tooth``, ``other_tooth``: the two cracks' places (:class:`PadPosition`);
    ``depths``: those solved for both [m] (the first 0); ``answer``, ``other_answer``:
    record length [s] -> the POD crossing in words on ``depths`` (scene's tooth, the
    counterpart); ``watched``, ``other_watched``: each one's alarm family (labels);
    ``shift_hz``, ``other_shift_hz``: per depth the record change of each one's best
    watched mode [Hz]; ``sigma_hz``, ``other_sigma_hz``: that mode's identification
    scatter with records of ``record_length`` [Hz] [s]; ``samples``: Monte Carlo
    reducers behind the POD; ``how``: how the depths were chosen, in words."""

    scene_tooth: PadPosition
    other_tooth: PadPosition
    depths: tuple
    answer: dict
    other_answer: dict
    watched: tuple
    other_watched: tuple
    shift_hz: tuple
    other_shift_hz: tuple
    samples: int
    sigma_hz: float = float("nan")
    other_sigma_hz: float = float("nan")
    record_length: float = float("nan")
    how: str = PAD_SOLVED

    @property
    def on_pad(self) -> PadPosition:
        return self.scene_tooth if self.scene_tooth.on_pad else self.other_tooth

    @property
    def between(self) -> PadPosition:
        return self.other_tooth if self.scene_tooth.on_pad else self.scene_tooth

    def answer_of(self, position: PadPosition) -> dict:
        return self.answer if position is self.scene_tooth else self.other_answer

    def to_dict(self) -> dict:
        def side(position, answer, watched, shift, sigma):
            return dict(position.to_dict(), place=position.place,
                        scene_tooth=position is self.scene_tooth,
                        answer={f"{t:g}": words for t, words in answer.items()},
                        watched=list(watched),
                        best_watched_shift_hz=[finite_or_none(x) for x in shift],
                        best_watched_sigma_hz=finite_or_none(sigma))

        return {"depths_mm": [1e3 * d for d in self.depths], "depths_chosen": self.how,
                "monte_carlo_samples": self.samples,
                "sigma_record_length_s": finite_or_none(self.record_length),
                "variants": [side(self.scene_tooth, self.answer, self.watched, self.shift_hz,
                                  self.sigma_hz),
                             side(self.other_tooth, self.other_answer, self.other_watched,
                                  self.other_shift_hz, self.other_sigma_hz)]}


def _best_shift(result, index=None) -> tuple:
    """Per depth (of ``index``, default all) the record change of ``result``'s best
    watched mode [Hz]."""
    index = range(len(result.depths)) if index is None else index
    if not result.watched:
        return tuple(np.nan for _ in index)
    i = result.watched[0]
    return tuple(float(result.frequency_hz[k, i] - result.frequency_hz[0, i]) for k in index)


def _best_sigma(result, record_length: float) -> float:
    """The identification scatter of ``result``'s best watched mode [Hz]."""
    if not result.watched or record_length not in result.sigma_hz:
        return float("nan")
    return float(result.sigma_hz[record_length][result.watched[0]])


def pad_variant(design, crack_of, scene, options, main, depths, ring) -> PadVariant:
    """:class:`PadVariant` of the elastic ring's answer (module docstring).

    ``crack_of(depth)``: the scene's ``Crack`` of a depth [m]; ``scene``: the ``[elastic]``
    table; ``options``: the main answer's ``DetectionOptions``; ``main``: the main answer
    (``DetectionResult`` of the elastic ring, its ``detail.k_rest`` the rest spring);
    ``depths`` [m]: the sweep's (the first 0; each one of ``main.depths``), solved for the
    counterpart in order; ``ring``: the design's ``meshing.RingGear``.  The scene's
    tooth's answer on the solved depths is read from ``main``'s POD there (the POD at a
    depth does not depend on the depths beside it: the same Monte Carlo reducers),
    with ``main``'s watched family."""
    from hubvib.elastic.cases import cached_case

    from .elastic_model import elastic_result

    if len(depths) < 2 or depths[0] != 0:
        raise ValueError(f"depths = {tuple(depths)!r}: the intact ring (0) first, then at "
                         "least one crack depth")
    reference = crack_of(depths[-1])
    tooth = counterpart_tooth(ring, reference)

    def moved(depth):
        return moved_crack(crack_of(depth), tooth)

    k_rest = main.detail.k_rest
    lengths = sorted({*_record_lengths(), options.record_length})
    solved, other_cases = [], []
    result = None
    for depth in depths:
        solved.append(float(depth))
        other_cases.append(cached_case(design, moved(depth), scene, k_rest))
        if depth == 0:
            continue
        result = elastic_result(design, tuple(solved), moved, scene, options, other_cases)
        if all(result.bracket(t).found for t in lengths):
            break
    index = [list(main.depths).index(d) for d in solved]
    answer = {t: bracket(solved, np.asarray(main.pod[t])[index],
                         main.detection_probability).words() for t in main.lengths}
    length = options.record_length
    return PadVariant(
        crack_position(ring, reference), crack_position(ring, moved(depths[-1])),
        tuple(solved), answer, {t: result.answer(t) for t in result.lengths},
        tuple(main.watched_labels()), tuple(result.watched_labels()),
        _best_shift(main, index), _best_shift(result), result.samples,
        _best_sigma(main, length), _best_sigma(result, length), float(length))


def _record_lengths() -> tuple:
    from .pod import RECORD_LENGTHS

    return tuple(RECORD_LENGTHS)
