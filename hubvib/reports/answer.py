"""The short answer from the ring model that holds at the watched modes: which model leads,
its bold sentence, the other model's comparison row, and the console's last line.

The rigid ring (9 + 3N) holds below the top of its validity band
(``hubvib.elastic.validity.ValidityBand``, computed from the elastic ring's intact case);
the elastic ring holds up to the band it was compared over.  The model whose band covers
its watched modes leads; when both do, the rigid ring (the simpler model) leads; when
neither does, the elastic ring (the wider band).  Without the elastic ring, or its band,
the rigid ring's answer stands alone.
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Lead", "lead", "lead_lines", "answer_line"]

#: the ring models' names in the report
NAMES = {"rigid": "rigid ring (9 + 3N)", "elastic": "elastic ring"}


@dataclass(frozen=True)
class Lead:
    """``leader`` and ``other`` (``detection.result.DetectionResult`` or None), and why
    the other does not lead (``reason``; empty when it stands alone)."""

    leader: object
    other: object
    reason: str


def _khz(values) -> str:
    low, high = min(values), max(values)
    return f"{low / 1e3:.1f}-{high / 1e3:.1f} kHz" if high > low else f"{low / 1e3:.1f} kHz"


def lead(rigid, elastic, band) -> Lead:
    """Which model's answer leads (module docstring): ``rigid``, ``elastic`` (results or
    None) and ``band`` (the rigid model's ``ValidityBand`` or None)."""
    if elastic is None or rigid is None or band is None:
        return Lead(rigid if rigid is not None else elastic, None, "")
    rigid_hz = [float(rigid.intact_hz[i]) for i in rigid.watched]
    elastic_hz = [float(elastic.intact_hz[i]) for i in elastic.watched]
    rigid_holds = bool(rigid_hz) and all(band.holds_for(f) for f in rigid_hz)
    elastic_holds = all(f <= band.compared_to_hz for f in elastic_hz)
    rigid_why = (f"rigid ring: holds below {band.band_top_hz:.0f} Hz; watched modes "
                 f"{_khz(rigid_hz)}" if rigid_hz else "rigid ring: no watched modes")
    if rigid_holds:
        return Lead(rigid, elastic, f"elastic ring: the rigid ring holds at its watched "
                                    f"modes ({_khz(rigid_hz)}, below {band.band_top_hz:.0f} Hz)")
    if elastic_holds:
        return Lead(elastic, rigid, rigid_why)
    return Lead(elastic, rigid, rigid_why + f"; the elastic ring compared up to "
                                            f"{band.compared_to_hz:.0f} Hz only")


def _answers(result) -> str:
    return "; ".join(f"{t:g} s: {result.answer(t)}" for t in result.lengths)


def lead_lines(which: Lead) -> list[str]:
    """The short answer's opening: the leading model's bold sentence and the other model's
    comparison row with its reason."""
    leader = which.leader
    if leader is None:
        return []
    watched = ", ".join(leader.watched_labels()) or "none"
    holds = ", the model that holds at the watched modes," if which.other is not None else ""
    lines = [f"**On the {NAMES[leader.ring]}{holds} the depth from which a crack is detected "
             f"(family POD >= {leader.detection_probability:g}) is, with records of "
             f"{_answers(leader)}.** Watched: {watched}."]
    if which.other is not None:
        lines += ["", f"Comparison ({which.reason}): {_answers(which.other)}."]
    return lines + [""]


def answer_line(which: Lead) -> str | None:
    """The console's last line: the leading model's POD crossing per record length."""
    leader = which.leader
    if leader is None:
        return None
    tail = "" if which.other is None else f" (comparison: {which.reason})"
    return (f"{NAMES[leader.ring]}: crack detected (POD >= {leader.detection_probability:g}) "
            f"at {_answers(leader)}{tail}")
