"""The report's section on the ring-planet mesh stiffness: which c_rp the lumped model
uses and why, and what the other method gives (Markdown lines; stiffnesses in N/m,
shifts in Hz, depths in mm)."""
from __future__ import annotations

import numpy as np

from hubvib.detection.mesh_stiffness import MethodComparison, family_depths

__all__ = ["mesh_stiffness_section"]


def mesh_stiffness_section(model, iso: float, comparison: MethodComparison | None,
                           watched, pod=None) -> list[str]:
    """Report lines: which c_rp the lumped model uses and why, with the FE, ISO 6336-1
    and lumped values [N/m]; with ``comparison`` the shifts of the ``watched`` modes
    (0-based) under both methods and, with ``pod`` (the model's PodResult) and the
    comparison's ``other_pod``, the depth the watched family detects under each."""
    fe = model.c_rp_fe[0]
    lumped = model.params.c_rp
    lines = ["## Ring-planet mesh stiffness", ""]
    window = model.c_rp_fe_window[0] if model.c_rp_fe_window else float("nan")
    numbers = (f"FE intact c_rp {fe:.4g} N/m over the mesh cycle and {window:.4g} N/m over "
               f"the cracked tooth's contact window, ISO 6336-1 c_gamma_alpha b {iso:.4g} N/m")
    if model.c_rp_source == "fe":
        lines.append(
            f"The lumped model uses the FE intact c_rp = {fe:.4g} N/m for every planet "
            f"({numbers}): the design gives no c_rp, and one mesh stiffness serves the intact "
            "and the cracked tooth. The crack's FE compliance (1/ratio - 1) over the window's "
            "intact mean, in series with it, scales planet 1's c_rp by the FE cracked/intact "
            f"ratio's change times {fe / window:.4g} to first order (the two means' ratio).")
    else:
        lines.append(
            f"The lumped model uses the given c_rp = {lumped:.4g} N/m ({numbers}). A given "
            "value is an effective mesh stiffness that holds more compliance than the tooth "
            "pair's (for the paper's Raba 118/76 preset, its table's value). The crack adds "
            "the FE compliance (1/ratio - 1)/c_rp_FE (c_rp_FE: the intact mean over the "
            "contact window, the ratio's denominator) in series with it (method `series`, "
            "primary). Multiplying the given c_rp by the FE ratio instead (method `ratio`, "
            "the earlier method) treats all of it as the tooth pair's: an upper bound of "
            "the crack's effect.")
    lines.append("")
    if comparison is None:
        return lines
    lines += ["Time-averaged shift a record sees [Hz] under both methods, and planet 1's "
              "c_rp factor with the cracked tooth in mesh (`results.json`: "
              "`mesh_stiffness`, `c_rp_methods`):", ""]
    head = (f"| depth [mm] | factor {comparison.method} | factor {comparison.other} | "
            + " | ".join(f"rigid {i + 1} {comparison.method} | rigid {i + 1} {comparison.other}"
                         for i in watched))
    lines += [head + " |", "|---:|---:|---:|" + "---:|---:|" * len(watched)]
    for k, d in enumerate(comparison.depths):
        cells = [f"{comparison.shift_hz[k, i]:+.3g} | {comparison.other_shift_hz[k, i]:+.3g}"
                 for i in watched]
        lines.append(f"| {1e3 * d:.3g} | {comparison.factor[k]:.4f} | "
                     f"{comparison.other_factor[k]:.4f} | " + " | ".join(cells) + " |")
    lines.append("")
    if pod is None or comparison.other_pod is None:
        return lines
    mine, other = family_depths(pod), family_depths(comparison.other_pod)
    lines += [f"Smallest depth the watched modes detect together (POD >= "
              f"{pod.detection_probability:g}, family-wise false-alarm rate "
              f"{pod.false_alarm_rate:g}, no drift; the same Monte Carlo draws):", "",
              f"| record [s] | {comparison.method} (primary) | {comparison.other} |",
              "|---:|---:|---:|"]
    for T in mine:
        cells = ["none" if np.isnan(d) else f"{1e3 * d:.3g} mm" for d in (mine[T], other[T])]
        lines.append(f"| {T:g} | " + " | ".join(cells) + " |")
    return lines + [""]
