"""The report's rows for where the crack lies against the support pads
(``detection.pad_variant.PadVariant``)."""
from __future__ import annotations

import math

__all__ = ["pad_variant_lines"]


def _hz(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x:+.1f} Hz"


def pad_variant_lines(variant, main=None) -> list[str]:
    """The smallest detectable depth with the crack on a support pad and between pads, one
    row each, and the main answer's bracket (``main``: the elastic ring's
    ``DetectionResult``, whose added depths resolve the scene's tooth further); [] without
    a variant."""
    if variant is None:
        return []
    lengths = sorted(variant.answer)
    depths = ", ".join(f"{1e3 * d:g}" for d in variant.depths)
    rows = ["## What the answer rests on: the crack on a pad or between pads", "",
            f"The hub holds the ring on support pads ({math.degrees(variant.on_pad.pad_width):.3g}"
            f" deg arcs every {math.degrees(variant.on_pad.pad_pitch):.3g} deg). The same crack "
            "at the tooth of the other relation to them, the sensor as far from the cracked "
            "tooth, the planets placed from it: where the family POD crosses the required "
            f"probability on the depths {depths} mm ({variant.how}; "
            f"{variant.samples} Monte Carlo reducers, as the main answer):", "",
            "| crack | tooth (crack mouth) | " + " | ".join(f"{t:g} s records" for t in lengths)
            + " |", "|---|---:|" + "---|" * len(lengths)]
    for position in (variant.on_pad, variant.between):
        answer = variant.answer_of(position)
        scene = " (the scene's)" if position is variant.scene_tooth else ""
        rows.append(f"| {position.place}{scene} | {position.tooth} "
                    f"({math.degrees(position.angle):.1f} deg) | "
                    + " | ".join(answer.get(t, "-") for t in lengths) + " |")
    rows.append("")
    deepest = 1e3 * variant.depths[-1]

    def change(shift, sigma, watched) -> str:
        against = (f", {abs(shift) / sigma:.3g} times its {variant.record_length:g} s "
                   f"scatter of {sigma:.2f} Hz" if math.isfinite(sigma) and sigma > 0
                   and math.isfinite(shift) else "")
        return f"{_hz(shift)} ({watched[0] if watched else '-'}{against})"

    rows.append(
        f"Record change of each one's best watched mode at {deepest:g} mm: "
        f"{change(variant.shift_hz[-1], variant.sigma_hz, variant.watched)} with the "
        f"scene's tooth {variant.scene_tooth.tooth}, "
        f"{change(variant.other_shift_hz[-1], variant.other_sigma_hz, variant.other_watched)}"
        f" with tooth {variant.other_tooth.tooth}.")
    if main is not None:
        rows.append("With the depths added to resolve it, the scene's tooth gives: "
                    + "; ".join(f"{t:g} s: {main.answer(t)}" for t in lengths if t in main.pod)
                    + ".")
    return rows + ["", "`results.json` (`pad_variant`) has both cracks' places against the "
                   "pads, their watched modes and best-mode changes per depth.", ""]
