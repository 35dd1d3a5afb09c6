"""Where a ring crack lies against the support pads the hub holds the ring by (SI, angles
[rad]).

The ring sits on ``supports.count`` arcs of its outer surface, each ``supports.width``
wide, centred on ``first_angle + 2 pi j / count`` (``meshing.ring_gear.Supports``).  A
crack's place is the polar angle of its mouth (where it leaves the tooth fillet; a root
crack runs outwards from there); it lies on a pad when that angle falls within an arc.

The counterpart of a crack is the tooth with the other relation to the pads: for a crack
on a pad, the tooth whose crack mouth lies nearest the middle of one of the two gaps
beside that pad (the span of rim the pads leave free; a tooth just past a pad's edge is
still within the pad's hold); for a crack between pads, the tooth whose crack mouth lies
nearest the middle of the nearest pad.  Rotating the ring by a whole number of teeth moves
the crack against the pads, which repeat every ``2 pi / count`` only: the intact ring with
its planets placed from the counterpart tooth is another ring on its pads (a rotation
that maps the pads onto themselves would keep the crack's relation to them).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

__all__ = ["PadPosition", "crack_position", "counterpart_tooth", "moved_crack",
           "layout_repeats"]


@dataclass(frozen=True)
class PadPosition:
    """A crack's place against the pads.

    ``tooth``: the cracked tooth; ``angle``: its crack mouth's polar angle in [0, 2 pi)
    [rad]; ``on_pad``: within a support arc; ``pad``: the nearest arc's index;
    ``from_pad_middle``: signed angle from that arc's middle (counter-clockwise positive)
    [rad]; ``pad_width``, ``pad_pitch``: an arc's width and the arcs' spacing [rad]."""

    tooth: int
    angle: float
    on_pad: bool
    pad: int
    from_pad_middle: float
    pad_width: float
    pad_pitch: float

    @property
    def place(self) -> str:
        return "on a support pad" if self.on_pad else "between pads"

    def words(self) -> str:
        """``tooth 0 (crack mouth at 2.5 deg, on a support pad: 2.5 deg from the middle
        of pad 0; pads 20 deg wide every 60 deg)``."""
        middle = (f"{math.degrees(abs(self.from_pad_middle)):.1f} deg from the middle of "
                  f"pad {self.pad}" if self.on_pad else
                  f"{math.degrees(self.pad_pitch / 2 - abs(self.from_pad_middle)):.1f} deg "
                  "from the middle of the gap")
        return (f"tooth {self.tooth} (crack mouth at {math.degrees(self.angle):.1f} deg, "
                f"{self.place}: {middle}; pads {math.degrees(self.pad_width):.3g} deg wide "
                f"every {math.degrees(self.pad_pitch):.3g} deg)")

    def to_dict(self) -> dict:
        return {"tooth": self.tooth, "mouth_angle_deg": math.degrees(self.angle),
                "on_pad": self.on_pad, "pad": self.pad,
                "from_pad_middle_deg": math.degrees(self.from_pad_middle),
                "pad_width_deg": math.degrees(self.pad_width),
                "pad_pitch_deg": math.degrees(self.pad_pitch)}


def _wrapped(angle: float) -> float:
    """``angle`` in (-pi, pi] [rad]."""
    return math.remainder(angle, 2 * math.pi)


def mouth_angle(ring, crack) -> float:
    """Polar angle of ``crack``'s mouth on ``ring`` (a ``meshing.RingGear``), in [0, 2 pi)
    [rad]."""
    x, y = crack.mouth(ring)[:2]
    return math.atan2(y, x) % (2 * math.pi)


def crack_position(ring, crack) -> PadPosition:
    """Where ``crack`` (a ``meshing.crack.Crack``; its depth does not matter) lies against
    ``ring``'s support pads.  Raises ValueError for a ring held all round (no pads)."""
    supports = ring.supports
    if supports.count == 0:
        raise ValueError("supports.count = 0: the whole outer surface is held, there are "
                         "no pads to lie on or between")
    angle = mouth_angle(ring, crack)
    pitch = 2 * math.pi / supports.count
    pad = round((angle - supports.first_angle) / pitch) % supports.count
    offset = _wrapped(angle - supports.first_angle - pad * pitch)
    return PadPosition(int(crack.tooth), angle, abs(offset) <= supports.width / 2, int(pad),
                       offset, supports.width, pitch)


def counterpart_tooth(ring, crack) -> int:
    """The tooth whose crack (``crack`` moved there) has the other relation to the pads
    (module docstring): the one nearest a gap's middle beside ``crack``'s pad when it is
    on a pad, nearest the middle of its nearest pad when it is between pads; of two
    equally near, the counter-clockwise one."""
    here = crack_position(ring, crack)
    supports = ring.supports
    middle = supports.first_angle + here.pad * here.pad_pitch
    targets = ((middle + here.pad_pitch / 2, middle - here.pad_pitch / 2) if here.on_pad
               else (middle,))
    best, best_key = None, None
    for tooth in range(ring.teeth):
        angle = mouth_angle(ring, moved_crack(crack, tooth))
        for rank, target in enumerate(targets):
            key = (round(abs(_wrapped(angle - target)), 12), rank)
            if best_key is None or key < best_key:
                best, best_key = tooth, key
    return int(best)


def moved_crack(crack, tooth: int):
    """``crack`` at the root of ``tooth`` (same depth, direction and start)."""
    return replace(crack, tooth=int(tooth))


def layout_repeats(ring, teeth: int) -> bool:
    """Whether turning the ring by ``teeth`` tooth pitches maps its pads onto themselves
    (then a crack there has the same relation to them, and the intact ring with its
    planets placed from there is the same ring)."""
    supports = ring.supports
    if supports.count == 0:
        return True
    turns = teeth * supports.count / ring.teeth
    return math.isclose(turns, round(turns), abs_tol=1e-9)
