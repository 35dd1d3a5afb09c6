"""The report's words on a ring model's detectability against its mounting
(:mod:`hubvib.detection.mounting_map`), for either ring: one summary, one table and one
section writer taking a ``MountingMap`` (or the rigid ``DetectabilityMap`` / elastic
``ElasticMap`` it is made from), Markdown lines.  The figure is
:func:`hubvib.detection.plots.map_figure`."""
from __future__ import annotations

import math

import numpy as np

from hubvib.detection.mode_names import rigid_label
from hubvib.detection.mounting_map import as_mounting_map
from hubvib.detection.numbers import depth_mm

__all__ = ["map_summary", "map_table", "map_section", "RIGID_INTRO"]

#: the rigid map's lead-in, before its table
RIGID_INTRO = ("The mounting is swept log-spaced in series with the FE ring body (whatever "
               "the scene's `apply`); each point is a Monte Carlo POD. Smallest detectable "
               "depth over all modes (`detectability_map.csv` has every mode, with the "
               "stiffness carrying its signal):")


def map_summary(mmap) -> list[str]:
    """Summary lines: the rigid ring one per mounting swept and stiffness carrying the
    signal; the elastic ring one on the family's smallest detectable depth over the
    scales and the ring's lowest mode of its own."""
    mmap = as_mounting_map(mmap)
    return (_rigid_summary(mmap.detail) if mmap.ring == "rigid"
            else _elastic_summary(mmap.detail))


def map_table(mmap) -> list[str]:
    """The table: the rigid ring per mounting value and sweep the smallest detectable
    depth among the modes whose signal is in the swept support and among all modes; the
    elastic ring per foundation scale the foundation, the ring's lowest mode, the family's
    depth and each followed watched mode's."""
    mmap = as_mounting_map(mmap)
    return _rigid_table(mmap.detail) if mmap.ring == "rigid" else _elastic_table(mmap.detail)


def map_section(mmap) -> list[str]:
    """The report section: heading, what was swept and how, (the elastic ring's summary)
    and the table."""
    mmap = as_mounting_map(mmap)
    if mmap.ring == "rigid":
        return ["## Detectability against the ring mounting", "", RIGID_INTRO, "",
                *_rigid_table(mmap.detail), ""]
    return _elastic_section(mmap.detail)


def _rigid_summary(dmap) -> list[str]:
    """One sentence per mounting swept and stiffness carrying the signal."""
    lines = []
    for swept, carrier in (("c_ru_mount", "c_ru"), ("c_r_mount", "c_r")):
        depth, carried = dmap.depth[swept], dmap.carried_by[swept]
        own = np.where(carried == carrier, depth, np.nan)
        rows = np.flatnonzero(~np.isnan(own).all(axis=1))
        if rows.size == 0:
            lines.append(f"- Modes with their signal in {carrier}: no crack of the sweep is "
                         f"detectable for any {swept} from {dmap.mounts[0]:.3g} to "
                         f"{dmap.mounts[-1]:.3g} N/m.")
            continue
        first = rows[0]
        stiff = np.nanmin(own[-1]) if not np.isnan(own[-1]).all() else math.nan
        lines.append(f"- Modes with their signal in {carrier}: detectable once {swept} >= "
                     f"{dmap.mounts[first]:.3g} N/m (from {depth_mm(np.nanmin(own[first]))} mm "
                     f"there; at {dmap.mounts[-1]:.3g} N/m from {depth_mm(stiff)} mm).")
    rp = {s: np.where(dmap.carried_by[s] == "c_rp", dmap.depth[s], np.nan)
          for s in ("c_ru_mount", "c_r_mount")}
    every = np.concatenate([~np.isnan(v).all(axis=1) for v in rp.values()])
    if every.any():
        where = ("at every mounting swept" if every.all() else
                 f"at {int(every.sum())} of the {every.size} mountings swept")
        lines.append(f"- Modes with their signal in c_rp (the cracked tooth's mesh, behind no "
                     f"mounting): detectable {where}, from "
                     f"{depth_mm(np.nanmin(np.concatenate([v.ravel() for v in rp.values()])))} mm.")
    return lines


def _rigid_table(dmap) -> list[str]:
    """Per mounting value and sweep: the smallest detectable depth among the modes whose
    signal is in the swept support, and among all modes."""
    lines = ["| mounting [N/m] | c_ru_mount swept: via c_ru [mm] | mode | any mode [mm] "
             "| c_r_mount swept: via c_r [mm] | mode | any mode [mm] |",
             "|---:|---:|---|---:|---:|---|---:|"]
    for m, mount in enumerate(dmap.mounts):
        cells = []
        for swept, carrier in (("c_ru_mount", "c_ru"), ("c_r_mount", "c_r")):
            depth = dmap.depth[swept][m]
            own = np.where(dmap.carried_by[swept][m] == carrier, depth, np.nan)
            if np.isnan(own).all():
                cells += ["not detectable", "-"]
            else:
                i = int(np.nanargmin(own))
                cells += [depth_mm(own[i]), rigid_label(i, dmap.kind[i],
                                                        dmap.frequency_hz[swept][m, i])]
            cells.append("not detectable" if np.isnan(depth).all()
                         else f"{depth_mm(np.nanmin(depth))} "
                              f"({dmap.carried_by[swept][m, int(np.nanargmin(depth))]})")
        lines.append(f"| {mount:.3g} | " + " | ".join(cells) + " |")
    return lines



def _mm(depth: float) -> str:
    return "none" if not np.isfinite(depth) else f"{1e3 * depth:.3g}"


def _span(scales) -> str:
    finite = scales[np.isfinite(scales)]
    top = (f"{finite[-1]:g} x the reference and clamped on the arcs" if np.isinf(scales[-1])
           else f"{finite[-1]:g} x the reference")
    return f"from {finite[0]:g} to {top}"


def _scale(s: float) -> str:
    return "clamped" if np.isinf(s) else f"{s:.3g}"


def _elastic_summary(emap) -> list[str]:
    """One sentence on the family's smallest detectable depth over the scales, one on the
    ring's lowest mode of its own."""
    s, depth = emap.scales, emap.family_depth
    shallowest = min(d for d in emap.depths if d > 0)
    found = np.isfinite(depth)
    if not found.any():
        first = f"no crack of the sweep is detectable at any foundation {_span(s)}"
    elif np.all(depth[found] == shallowest) and found.all():
        first = (f"the sweep's shallowest crack, {1e3 * shallowest:.3g} mm, is detectable at "
                 f"every foundation {_span(s)} (nothing shallower was computed)")
    else:
        low, high = np.nanmin(depth), np.nanmax(depth)
        first = (f"the smallest detectable depth lies between {1e3 * low:.3g} and "
                 f"{1e3 * high:.3g} mm over the foundations {_span(s)}"
                 + ("" if found.all() else
                    f"; none of the sweep at s = {', '.join(_scale(x) for x in s[~found])}"))
    ring = emap.lowest_ring_mode_hz
    second = (f"the ring's lowest mode of its own rises from {ring[0]:.0f} Hz (n = "
              f"{emap.lowest_ring_mode_n[0]}) to {ring[-1]:.0f} Hz (n = "
              f"{emap.lowest_ring_mode_n[-1]})" if np.isfinite(ring[[0, -1]]).all() else
              "the ring has no elastic mode of its own in the basis at some scales")
    return [f"- Elastic ring against its foundation: {first}; {second}."]


def _elastic_table(emap) -> list[str]:
    """Per foundation scale: the foundation, the ring's lowest mode, the family's smallest
    detectable depth and each followed watched mode's (its frequency there)."""
    ref = emap.reference
    heads = [f"elastic {emap.modes_hz[ref, j]:.1f} Hz mode [mm]"
             for j in range(emap.modes_hz.shape[1])]
    lines = ["| s | k_n [N/m^2] | k_t [N/m^2] | lowest ring mode [Hz] (n) | family [mm] | "
             + " | ".join(heads) + (" |" if heads else ""),
             "|---:|---:|---:|---:|---:|" + "---:|" * len(heads)]
    for k, s in enumerate(emap.scales):
        f = emap.lowest_ring_mode_hz[k]
        ring = "-" if not np.isfinite(f) else f"{f:.0f} ({emap.lowest_ring_mode_n[k]})"
        cells = []
        for j in range(emap.modes_hz.shape[1]):
            hz = emap.modes_hz[k, j]
            cells.append("(lost)" if not np.isfinite(hz) else
                         f"{_mm(emap.mode_depth[k, j])} ({hz:.0f} Hz)")
        if np.isinf(s):
            lines.append(f"| clamped | - | - | {ring} | {_mm(emap.family_depth[k])} | "
                         + " | ".join(cells) + (" |" if cells else ""))
            continue
        lines.append(f"| {s:.3g} | {s * emap.foundation[0]:.3g} | {s * emap.foundation[1]:.3g} "
                     f"| {ring} | {_mm(emap.family_depth[k])} | " + " | ".join(cells)
                     + (" |" if cells else ""))
    return lines


def _elastic_section(emap) -> list[str]:
    """The report section: what was swept and how, the summary and the table."""
    shallowest = min(d for d in emap.depths if d > 0)
    return [
        "## Elastic ring against its mounting", "",
        "The elastic ring's Winkler foundation on the support arcs (reference k_n "
        f"{emap.foundation[0]:.4g}, k_t {emap.foundation[1]:.4g} N/m^2, s = 1) scaled by s, "
        "both stiffnesses together; per crack depth the FE ring is reduced once for every "
        "scale (its modes, the planets' contact responses and the support arcs' reaction "
        "responses), each scale a small coupled problem. The detection rule is the elastic "
        "ring's above at each scale (planet 1 away from the cracked tooth, own intact "
        f"baseline, records of {emap.record_length:g} s, family POD >= "
        f"{emap.detection_probability:g}, POD `{emap.pod_name}`); the family's watched modes "
        "are chosen anew at each scale. The modes' columns follow the watched modes of "
        "s = 1 over the scales (subspace match between neighbouring scales; '(lost)' where "
        f"none continues them), each alone at the family's per-mode rate. 'none': no depth "
        f"of the sweep; its shallowest crack is {1e3 * shallowest:.3g} mm, nothing "
        "shallower was computed.", "",
        *_elastic_summary(emap), "", *_elastic_table(emap), ""]
