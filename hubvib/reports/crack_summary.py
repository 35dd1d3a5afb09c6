"""The crack study's console lines: per mode its shift and the depth it detects from."""
from __future__ import annotations

import math
from pathlib import Path

from hubvib.detection.numbers import percent
from hubvib.reports.answer import answer_line, lead

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
    out.append(f"{'rigid ring (9 + 3N)':<24}")
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
        rigid = result.rigid
        out.append(f"rigid ring: watched modes {', '.join(rigid.watched_labels())} together "
                   f"(family-wise false-alarm rate {rigid.false_alarm_rate:g}), crack "
                   f"detected (POD >= {pod:g}) with records of "
                   + "; ".join(f"{t:g} s: {rigid.answer(t)}" for t in rigid.lengths))
    if result.elastic is not None:
        elastic = result.elastic
        out.append(f"elastic ring: watched modes {', '.join(elastic.watched_labels())}"
                   + ("" if not elastic.added_depths else
                      f"; depths added {', '.join(f'{1e3 * d:.3g}' for d in elastic.added_depths)}"
                      " mm"))
    out.append(f"\nreport: {folder / 'report.md'} (in a browser: {folder / 'report.html'})")
    last = answer_line(lead(result.rigid, result.elastic, result.elastic_validity))
    if last is not None and (physical or result.elastic is not None):
        out.append(last)
    return out

