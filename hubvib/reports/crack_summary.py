"""The crack study's console lines: per mode its shift and the depth it detects from."""
from __future__ import annotations

import math
from pathlib import Path

from hubvib.detection.numbers import percent

__all__ = ["crack_lines"]


def crack_lines(scene, result, folder: Path) -> list[str]:
    """The console lines of ``result`` (a ``studies.crack_study.CrackStudyResult``): per mode
    its shift at the deepest crack and the depth it detects the crack from."""
    out = [f"scene {scene.name!r}: ring crack depths "
           f"{', '.join(f'{1e3 * d:.3g}' for d in result.depths)} mm "
           f"({result.computed} FE cases computed, {len(result.fe) - result.computed} cached)"]
    rows = result.mode_rows()
    physical = "detectable_depth_mm" in rows[0]
    if physical:
        pod = scene.detection.detection_probability
        last = f"detectable from (POD >= {pod:g}), via"
    else:
        last = f"smallest crack shifting >= {scene.threshold_percent:g} %"
    out.append(f"{'mode':>4} {'type':<13} {'f intact [Hz]':>13} {'inst. shift [%]':>15} "
               + (f"{'record shift [Hz]':>17} {'sigma [Hz]':>10} " if physical else "")
               + f"{'follows':>10}  {last}")
    for r in rows:
        depth = r["detectable_depth_mm"] if physical else r["smallest_detectable_depth_mm"]
        where = f" ({r['signal_in']})" if physical and depth is not None else ""
        record = (f"{r['record_shift_at_deepest_hz']:>+17.3g} {r['sigma_hz']:>10.3g} "
                  if physical else "")
        out.append(f"{r['mode']:>4} {r['kind']:<13} {r['frequency_intact_hz']:>13.3f} "
                   f"{percent(r['shift_at_deepest_percent']):>15} {record}{r['follows']:>10}  "
                   f"{'not detectable' if depth is None else f'{depth:.3g} mm'}{where}")
    out.append("inst. shift: at the deepest crack with planet 1 on the cracked tooth"
               + ("; record shift: the time-averaged shift a record sees there; sigma: "
                  "standard deviation of one identified frequency; detectable: on this mode "
                  "alone at the family-corrected false-alarm rate" if physical else "")
               + "; follows: relative sensitivity above 0.01")
    if physical and result.detection is not None:
        pod_result = result.detection.pod
        parts = [f"{T:g} s: " + ("none" if math.isnan(d) else f"from {1e3 * d:.3g} mm")
                 for T in sorted(pod_result.family_pod)
                 for d in [pod_result.family_detectable_depth(T)]]
        out.append(f"watched modes {', '.join(str(int(i) + 1) for i in pod_result.watched)} "
                   f"together (family-wise false-alarm rate {pod_result.false_alarm_rate:g}), "
                   f"crack detectable (POD >= {pod:g}) with records of " + "; ".join(parts))
    out.append(f"\nreport: {folder / 'report.md'} (in a browser: {folder / 'report.html'})")
    return out

