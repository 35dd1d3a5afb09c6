"""The elastic ring's answer with the crack moved to the other side of the pad relation
(``detection.pad_variant``), on the small synthetic elastic ring (no FE): the depths it
solves, the cases it asks for, and its rows beside the main answer's."""
from __future__ import annotations

import functools
from dataclasses import replace

import numpy as np
import pytest

from hubvib.meshing.crack import Crack

DEPTHS = (0.0, 0.004, 0.008, 0.012)

pytestmark = pytest.mark.slow  # the synthetic cases' coupled modes and the scene's options


@pytest.fixture(scope="module")
def main_answer():
    from hubvib.detection.elastic_model import elastic_result
    from hubvib.detection.options import detection_options
    from hubvib.elastic.options import parse_elastic_table
    from hubvib.studies.scene import load_scene

    options = replace(detection_options(load_scene(None)), samples=100)
    es = parse_elastic_table({"ring": "both", "pad_variant": True})
    result = elastic_result(None, DEPTHS, lambda d: Crack(0, d), es, options, list(_cases()))
    return result, es, options


@functools.lru_cache(maxsize=None)
def _cases() -> tuple:
    from tests.elastic.test_elastic_diagnose import _synthetic_cases

    return tuple(_synthetic_cases(DEPTHS))


def _run(main_answer, monkeypatch, cracked: bool):
    """pad_variant with the counterpart's cases the synthetic ring's (``cracked``) or its
    intact ring at every depth; returns (variant, the cracks asked for)."""
    from hubvib.design.presets import preset_design
    from hubvib.detection.pad_variant import pad_variant
    from hubvib.elastic import cases as elastic_cases
    from hubvib.reducer.stages import ring_gear

    result, es, options = main_answer
    asked = []

    def case_at(design, crack, scene, k_rest):
        asked.append(crack)
        return _cases()[DEPTHS.index(crack.depth) if cracked else 0]

    monkeypatch.setattr(elastic_cases, "cached_case", case_at)
    ring = ring_gear(preset_design("raba118"))
    variant = pad_variant(None, lambda d: Crack(0, d), es, options, result, DEPTHS, ring)
    return variant, asked


def test_the_counterpart_is_solved_until_every_crossing_is_found(main_answer, monkeypatch):
    """The crack of full strength at tooth 5 (Raba: the middle of the gap beside tooth 0's
    pad): the scene's depths are solved shallowest first and no further than the first at
    which every record length's family POD reaches the probability; every case asked for is
    at tooth 5; the scene's tooth's row is the main answer's POD bracket on those depths."""
    from hubvib.detection.resolution import bracket

    result, _, _ = main_answer
    variant, asked = _run(main_answer, monkeypatch, True)
    assert [c.tooth for c in asked] == [5] * len(asked)
    assert tuple(c.depth for c in asked) == variant.depths == DEPTHS[:len(variant.depths)]
    assert variant.scene_tooth.on_pad and not variant.other_tooth.on_pad
    assert variant.on_pad is variant.scene_tooth and variant.between is variant.other_tooth
    for t, words in variant.other_answer.items():
        assert not words.startswith("not within"), (t, words)
    k = len(variant.depths)
    for t in result.lengths:
        expected = bracket(DEPTHS[:k], result.pod[t][:k], result.detection_probability)
        assert variant.answer[t] == expected.words(), (t, variant.answer[t], expected)
    assert variant.samples == 100
    if k > 2:  # it stopped at the first depth that found them all
        from hubvib.detection.elastic_model import elastic_result

        shallower = elastic_result(None, DEPTHS[:k - 1], lambda d: Crack(5, d),
                                   main_answer[1], main_answer[2],
                                   list(_cases()[:k - 1]))
        assert not all(shallower.bracket(t).found for t in shallower.lengths)


def test_an_intact_counterpart_is_solved_at_every_depth_and_found_at_none(main_answer,
                                                                         monkeypatch):
    """A counterpart whose crack changes nothing (every case the intact ring): every depth
    of the sweep is solved and the answer is "not within the sweep (up to 12 mm)" for every
    record length; the report's row and results.json carry it."""
    from hubvib.reports.pad_sections import pad_variant_lines

    variant, asked = _run(main_answer, monkeypatch, False)
    assert variant.depths == DEPTHS and len(asked) == len(DEPTHS)
    assert set(variant.other_answer.values()) == {"not within the sweep (up to 12 mm)"}
    text = "\n".join(pad_variant_lines(variant, main_answer[0]))
    assert "| between pads | 5 (30.6 deg) | not within the sweep (up to 12 mm) |" in text
    assert "| on a support pad (the scene's) | 0 (2.5 deg) |" in text
    record = variant.to_dict()
    assert [v["tooth"] for v in record["variants"]] == [0, 5]
    assert record["depths_mm"] == [0.0, 4.0, 8.0, 12.0]
    assert np.allclose(record["variants"][1]["best_watched_shift_hz"], 0.0)
