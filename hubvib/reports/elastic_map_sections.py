"""The report's words and figure for the elastic ring's detectability against its
mounting (:mod:`hubvib.detection.elastic_map`): Markdown lines and a matplotlib figure (imported only
when drawn)."""
from __future__ import annotations

import numpy as np

from hubvib.detection.elastic_map import ElasticMap

__all__ = ["map_summary", "map_table", "map_section", "map_figure"]


def _mm(depth: float) -> str:
    return "none" if not np.isfinite(depth) else f"{1e3 * depth:.3g}"


def _span(scales) -> str:
    finite = scales[np.isfinite(scales)]
    top = (f"{finite[-1]:g} x the reference and clamped on the arcs" if np.isinf(scales[-1])
           else f"{finite[-1]:g} x the reference")
    return f"from {finite[0]:g} to {top}"


def _scale(s: float) -> str:
    return "clamped" if np.isinf(s) else f"{s:.3g}"


def map_summary(emap: ElasticMap) -> list[str]:
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


def map_table(emap: ElasticMap) -> list[str]:
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


def map_section(emap: ElasticMap) -> list[str]:
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
        *map_summary(emap), "", *map_table(emap), ""]


def map_figure(name: str, emap: ElasticMap):
    """Smallest detectable depth against the foundation scale (family and the followed
    modes) and, beside it, the ring's lowest mode of its own and the followed modes'
    frequencies."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from hubvib.detection.plots import style

    fig, (left, right) = plt.subplots(1, 2, figsize=(14, 5))
    deepest = max(emap.depths)
    shallowest = min(d for d in emap.depths if d > 0)
    # the clamped ring (scale inf) drawn one step past the stiffest foundation
    finite = emap.scales[np.isfinite(emap.scales)]
    x = np.where(np.isfinite(emap.scales), emap.scales, finite[-1] * 3)
    left.plot(x, 1e3 * emap.family_depth, color="k", lw=3, alpha=0.35,
              label="family (watched anew per scale)")
    ref = emap.reference
    for j in range(emap.modes_hz.shape[1]):
        left.plot(x, 1e3 * emap.mode_depth[:, j], **style(j),
                  label=f"mode {emap.modes_hz[ref, j]:.0f} Hz at s = 1, alone")
        right.plot(x, emap.modes_hz[:, j], **style(j))
    left.axhline(1e3 * shallowest, color="0.6", lw=0.8, ls="-.",
                 label=f"shallowest crack computed {1e3 * shallowest:.3g} mm")
    right.plot(x, emap.lowest_ring_mode_hz, color="k", lw=2, ls="--",
               label="ring's lowest mode of its own")
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_xlim(float(x[0]), float(x[-1]) * 1.2)
        if np.isinf(emap.scales[-1]):
            ax.axvline(finite[-1] * 1.7, color="0.6", lw=0.8)
            ax.text(x[-1], 0.02, "clamped", transform=ax.get_xaxis_transform(),
                    ha="center", fontsize=8)
        ax.set_xlabel("foundation scale s (k_n, k_t x s) [-]")
        ax.grid(True, which="both", alpha=0.3)
    left.set_ylim(0, 1.05e3 * deepest)
    left.set_ylabel("smallest detectable crack depth [mm]")
    right.set_ylabel("intact frequency [Hz]")
    left.legend(fontsize=7)
    right.legend(fontsize=7)
    fig.suptitle(f"{name}: elastic ring, detectability against the foundation "
                 f"(k_n {emap.foundation[0]:.3g}, k_t {emap.foundation[1]:.3g} N/m^2 at s = 1)")
    return fig

