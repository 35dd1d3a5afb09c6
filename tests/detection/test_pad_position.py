"""Where a ring crack lies against the support pads: the classification and the counterpart
tooth against the design's support arcs, worked out here from the design file's numbers."""
from __future__ import annotations

import math

import pytest

from hubvib.design.presets import preset_design
from hubvib.detection.pad_position import (counterpart_tooth, crack_position, layout_repeats,
                                           mouth_angle, moved_crack)
from hubvib.meshing.crack import Crack
from hubvib.reducer.stages import ring_gear


def _arcs(design):
    """The design's support arcs, (middle, half width) [rad], from its SupportSpec."""
    s = design.supports
    return [(s.first + 2 * math.pi * j / s.count, s.arc / 2) for j in range(s.count)]


def _on_arc(angle, arcs) -> bool:
    return any(abs(math.remainder(angle - middle, 2 * math.pi)) <= half for middle, half in arcs)


@pytest.mark.parametrize("preset", ["raba118", "hub4"])
def test_each_tooth_is_on_a_pad_exactly_when_its_crack_mouth_is_within_an_arc(preset):
    design = preset_design(preset)
    ring = ring_gear(design)
    arcs = _arcs(design)
    pitch = 2 * math.pi / design.ring.teeth
    for tooth in range(ring.teeth):
        crack = Crack(tooth, 0.003)
        angle = mouth_angle(ring, crack)
        # a root crack's mouth lies on the fillet beside its tooth, within a tooth pitch
        assert abs(math.remainder(angle - tooth * pitch, 2 * math.pi)) < pitch, (
            f"tooth {tooth}: mouth at {math.degrees(angle):.3f} deg, not within a tooth "
            "pitch of the tooth's centre line (meshing.ring_gear: tooth k at 2 pi k / z)")
        position = crack_position(ring, crack)
        assert position.on_pad == _on_arc(angle, arcs), (
            f"{preset} tooth {tooth}: on_pad {position.on_pad} against the design's arcs "
            f"(middles first + 2 pi j / count, width {math.degrees(design.supports.arc):g} deg)")


def test_the_raba_crack_of_tooth_0_is_on_pad_0_and_its_counterpart_tooth_5_mid_gap():
    """Raba 118/76: 64 ring teeth (5.625 deg), six 20 deg pads centred on 0, 60 .. 300 deg.
    Tooth 0's crack mouth (2.46 deg) is on pad 0; the gaps beside it are centred on +-30
    deg; the tooth whose crack mouth is nearest either middle, found here by brute force,
    is the counterpart; moved back, its counterpart is on a pad again."""
    design = preset_design("raba118")
    ring = ring_gear(design)
    crack = Crack(0, 0.003)
    assert crack_position(ring, crack).on_pad
    s = design.supports
    gaps = [s.first + math.pi / s.count, s.first - math.pi / s.count]
    nearest = min(range(ring.teeth), key=lambda k: min(
        abs(math.remainder(mouth_angle(ring, Crack(k, 0.003)) - g, 2 * math.pi)) for g in gaps))
    other = counterpart_tooth(ring, crack)
    assert other == nearest == 5, (other, nearest)
    moved = crack_position(ring, moved_crack(crack, other))
    assert not moved.on_pad
    gap_offset = math.pi / s.count - abs(moved.from_pad_middle)
    assert math.degrees(gap_offset) < 0.5 * 360 / ring.teeth, (
        "the counterpart lies within half a tooth pitch of the gap's middle")
    back = counterpart_tooth(ring, moved_crack(crack, other))
    assert crack_position(ring, Crack(back, 0.003)).on_pad


@pytest.mark.parametrize("preset", ["raba118", "hub4"])
def test_pads_repeat_only_at_turns_of_a_whole_pad_pitch(preset):
    """Turning by k teeth maps the pads onto themselves iff k (360 / z) is a multiple of
    360 / count: k count / z an integer."""
    design = preset_design(preset)
    ring = ring_gear(design)
    for k in range(ring.teeth):
        expected = (k * design.supports.count) % design.ring.teeth == 0
        assert layout_repeats(ring, k) == expected, (preset, k)
    other = counterpart_tooth(ring, Crack(0, 0.003))
    assert not layout_repeats(ring, other), "the counterpart's intact ring is another ring"


def test_a_ring_held_all_round_has_no_pads():
    from dataclasses import replace

    from hubvib.meshing.ring_gear import Supports

    ring = replace(ring_gear(preset_design("raba118")), supports=Supports(count=0))
    with pytest.raises(ValueError, match="supports.count = 0"):
        crack_position(ring, Crack(0, 0.003))
