"""Figures of a crack study (matplotlib, imported here only).

Every curve gets its own colour, marker and line style (10 colours x 8 markers
x 4 line styles), and only modes that move are drawn: 18 modes on one
10-colour cycle could not be told apart.
"""
from __future__ import annotations

import math

import numpy as np

from .mode_names import mode_names, rigid_curve_label
from .numbers import ROUND_OFF

COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
           "tab:pink", "tab:gray", "tab:olive", "tab:cyan")
MARKERS = ("o", "s", "^", "v", "D", "P", "X", "*")
LINES = ("-", "--", ":", "-.")
#: a mode "moves" when its relative shift exceeds this (100x the eigensolver round-off)
MOVING = 100 * ROUND_OFF


def style(i: int) -> dict:
    """Distinct line style of curve ``i`` (unique for the first 40 curves)."""
    return {"color": COLOURS[i % len(COLOURS)], "marker": MARKERS[i % len(MARKERS)],
            "linestyle": LINES[(i // len(COLOURS)) % len(LINES)], "markersize": 4}


def moving_modes(relative: np.ndarray) -> np.ndarray:
    """Indices of the columns of ``relative`` (relative shifts, rows = depths) that move."""
    return np.flatnonzero(np.abs(relative).max(axis=0) > MOVING)


def _axes(ncols: int = 1, **options):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt.subplots(1, ncols, figsize=(7 * ncols, 5), squeeze=False, **options)


def _label(i: int, frequency_hz: float, kind: str, name: str | None = None) -> str:
    return rigid_curve_label(name or str(i + 1), frequency_hz, kind)


#: curves per panel at most: more cannot be told apart
PER_PANEL = 8


def relative_shift_figure(name: str, depths: np.ndarray, omega: np.ndarray, kind):
    """Size of the instantaneous relative frequency shift [%] (planet 1 on the cracked
    tooth) against crack depth on a log axis, moving modes only, at most
    :data:`PER_PANEL` curves per panel, each panel's legend below it.  The modes move by
    parts per million to per cent: on a linear axis most lay on zero under the one that
    moves most."""
    relative = omega / omega[0] - 1
    moving = moving_modes(relative)
    panels = [moving[j:j + PER_PANEL] for j in range(0, max(moving.size, 1), PER_PANEL)]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(panels), 1, figsize=(9, 5.6 * len(panels)), squeeze=False,
                             layout="constrained")
    names = mode_names(omega[0])
    for ax, modes in zip(axes[:, 0], panels):
        sizes = []
        for n, i in enumerate(modes):
            size = 100 * np.abs(relative[:, i])
            size = np.where(size > 0, size, np.nan)  # the intact ring: no shift to draw
            sizes.append(size)
            ax.plot(1e3 * depths, size, **(style(n) | {"linestyle": LINES[n % len(LINES)],
                                                       "markersize": 5}),
                    label=_label(i, omega[0, i] / (2 * math.pi), kind[i], names[i]))
        if depths.size > 1:
            ax.axvline(1e3 * depths[1], color="0.6", lw=0.8, ls="-.",
                       label=f"shallowest crack computed {1e3 * depths[1]:.3g} mm")
        ax.set_xlabel("crack depth [mm]")
        ax.set_ylabel("|instantaneous frequency shift| [%] (log axis)")
        ax.grid(True, which="both", alpha=0.3)
        if sizes and np.isfinite(np.concatenate(sizes)).any():
            ax.set_yscale("log")
            shown = np.concatenate(sizes)
            shown = shown[np.isfinite(shown)]
            ax.set_ylim(shown.min() / 2, shown.max() * 2)
        if ax.get_legend_handles_labels()[0] and modes.size:
            ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
        else:
            ax.text(0.5, 0.5, "no mode moves", transform=ax.transAxes, ha="center")
    fig.suptitle(f"{name}: relative shift with planet 1 on the cracked tooth "
                 "(instantaneous; a record sees the time average)", fontsize=10)
    return fig


def shift_threshold_figure(name: str, pod):
    """|Shift| [Hz] a record sees against depth, with the alarm thresholds (log scale); the
    seven modes moving most against their identification scatter; the alarm thresholds
    of the watched modes as one grey band from the lowest to the highest.  The legend sits
    below the panel; the log axis spans the data and the band with a margin, so no tick
    label lies on the axes' top edge under the title."""
    fig, axes = _axes(layout="constrained")
    fig.set_size_inches(8, 6.5)
    ax = axes[0, 0]
    nominal = pod.nominal
    shift = -nominal.shift_hz
    relative = nominal.shift_hz / nominal.frequency_hz[0]
    moving = moving_modes(relative)
    strongest = moving[np.argsort(-np.abs(shift[-1, moving]) / pod.sigma_hz[moving],
                                  kind="stable")][:PER_PANEL - 1]
    shown = []
    for n, i in enumerate(sorted(strongest)):
        positive = shift[:, i] > 0
        shown.append(shift[positive, i])
        ax.plot(1e3 * pod.depths[positive], shift[positive, i],
                **(style(n) | {"linestyle": LINES[n % len(LINES)], "markersize": 5}),
                label=_label(i, nominal.frequency_hz[0, i], pod.kind[i],
                             mode_names(nominal.frequency_hz[0])[i]))
    low, high = pod.threshold_hz[pod.watched].min(), pod.threshold_hz[pod.watched].max()
    ax.axhspan(low, high * 1.0001, color="k", alpha=0.15, zorder=0,
               label=f"alarm thresholds of the watched modes {low:.3g}-{high:.3g} Hz")
    ax.set_yscale("log")
    values = np.concatenate(shown + [np.array([low, high])])
    values = values[np.isfinite(values) & (values > 0)]
    ax.set_ylim(values.min() / 2.5, values.max() * 2.5)
    ax.set_xlabel("crack depth [mm]")
    ax.set_ylabel("frequency drop seen by a record [Hz]")
    ax.set_title(f"{name}: frequency drop against the alarm threshold", pad=12)
    ax.grid(True, which="both", alpha=0.3)
    _legend_below(fig, ax)
    return fig


def pod_figure(name: str, pod, modes):
    """POD against depth: left the watched modes together per record length with the
    required POD and the false-alarm rate (linear axis); right each of ``modes`` (0-based)
    alone on a log axis, where the small single-mode PODs (near the false-alarm rate) are
    told apart, with the rate each mode alone alarms at (where its curve starts).  One
    legend below the panels."""
    fig, axes = _axes(2, layout="constrained")
    family, single = axes[0]
    fig.set_size_inches(13, 6.5)
    depth_mm = 1e3 * pod.depths
    f0 = pod.nominal.frequency_hz[0]
    for n, T in enumerate(sorted(pod.family_pod)[:3]):
        family.plot(depth_mm, pod.family_pod[T], color=("k", "tab:blue", "tab:red")[n],
                    lw=2.0, ls=("-", "--", ":")[n], marker=("o", "s", "^")[n], ms=5,
                    label=f"watched modes together, {T:g} s records", zorder=3)
    # a mode alone alarms at its own threshold's rate (Sidak share of the family's): the
    # single-mode curves start on that line, not on the family's
    rates = ((family, pod.false_alarm_rate, "false-alarm rate of the family"),
             (single, pod.per_mode_rate, "false-alarm rate of each mode alone"))
    for ax, rate, words in rates:
        ax.axhline(pod.detection_probability, color="0.35", lw=1.0, ls=(0, (6, 3)),
                   label=f"required POD {pod.detection_probability:g}", zorder=1)
        ax.axhline(rate, color="0.35", lw=1.0, ls=(0, (1, 2)), label=f"{words} {rate:.3g}",
                   zorder=1)
        if len(pod.depths) > 1:
            ax.axvline(depth_mm[1], color="0.6", lw=0.8, ls="-.", zorder=1,
                       label=f"shallowest crack computed {depth_mm[1]:.3g} mm")
        ax.set_xlabel("crack depth [mm]")
        ax.set_ylabel("probability of detection")
        ax.grid(True, which="both", alpha=0.3)
    family.set_ylim(-0.02, 1.02)
    family.set_title("watched modes together", fontsize=10)
    floor = 0.5 * min(pod.per_mode_rate, pod.false_alarm_rate)
    for n, i in enumerate(modes):
        single.plot(depth_mm, np.maximum(pod.pod[:, i], floor), **(style(n) | {
                    "linestyle": LINES[n % len(LINES)], "markersize": 6}), zorder=3,
                    label=_label(i, f0[i], pod.kind[i], mode_names(f0)[i]))
    single.set_yscale("log")
    single.set_ylim(floor, 1.5)
    single.set_title(f"each mode alone (records of the scene's length; log axis, "
                     f"clipped at {floor:.2g})", fontsize=10)
    fig.suptitle(f"{name}: probability of detection ({pod.samples} Monte Carlo samples)",
                 fontsize=11)
    # one legend below both panels: two side by side ran into each other at a legible size
    entries = {}
    for ax in (family, single):
        for handle, label in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(label, handle)
    fig.legend(list(entries.values()), list(entries), loc="outside lower center", ncol=3,
               fontsize=9)
    return fig


#: the mounting axis's margin beyond the swept range (a factor)
MARGIN = 10 ** 0.2
#: the markers of the stiffness carrying the signal in the detectability map
CARRIERS = (("c_ru", "tab:blue", "o"), ("c_r", "tab:orange", "s"), ("c_rp", "tab:green", "^"))


def map_figure(name: str, mmap, deepest: float | None = None,
               shallowest: float | None = None):
    """Smallest detectable depth against the mounting, for either ring model
    (``mmap``: a :class:`.mounting_map.MountingMap`, or a rigid ``DetectabilityMap`` /
    elastic ``ElasticMap`` it is made from), one panel per swept mounting: the line over
    all modes (``any mode``; the elastic ring's family) drawn black on top; where the model
    names the stiffness carrying the signal (the rigid ring), a large marker at each
    detecting mounting whose colour and shape name it (the label rule of the modes table),
    else each mode alone as a thin line; mountings where nothing of the sweep is detectable
    shaded.  Only what is drawn is in the legend (one, below the panels); the sweep's
    shallowest crack is marked: nothing below it was computed.  ``deepest`` and
    ``shallowest`` [m] default to the map's depths."""
    from .mounting_map import as_mounting_map

    mmap = as_mounting_map(mmap)
    deepest = mmap.deepest if deepest is None else deepest
    shallowest = mmap.shallowest if shallowest is None else shallowest
    fig, axes = _axes(len(mmap.panels), layout="constrained")
    fig.set_size_inches(max(7 * len(mmap.panels), 9), 6.2)
    entries = {}
    for ax, panel in zip(axes[0], mmap.panels):
        _map_panel(ax, panel, mmap.line_label, entries, shallowest)
        ax.set_ylim(0, 1.05e3 * deepest)
        ax.set_ylabel("smallest detectable crack depth [mm]")
        if len(mmap.panels) > 1:
            ax.set_title(f"{panel.axis_name} swept ({panel.held})", fontsize=10)
    fig.suptitle(f"{name}: detectability against the ring mounting" if mmap.ring == "rigid"
                 else f"{name}: {mmap.ring} ring, detectability against the foundation "
                      f"({mmap.panels[0].held})")
    if entries:
        fig.legend(list(entries.values()), [h.get_label() for h in entries.values()],
                   loc="outside lower center",
                   ncol=min(len(entries), 2 * len(mmap.panels) + 1), fontsize=10)
    return fig


def _map_panel(ax, panel, line_label: str, entries: dict, shallowest) -> None:
    """One swept mounting of :func:`map_figure` on ``ax``, its legend handles into
    ``entries``; a stiff limit (``inf``, last) drawn one step past the stiffest value."""
    values = np.asarray(panel.axis_values, dtype=float)
    finite = values[np.isfinite(values)]
    x = np.where(np.isfinite(values), values, finite[-1] * 3)
    depth, carried = panel.depth, panel.carried_by
    smallest = np.asarray(panel.any_mode, dtype=float)
    if carried is not None:
        for carrier, colour, marker in CARRIERS:
            masked = np.where((carried == carrier) & ~np.isnan(depth), depth, np.inf)
            best = masked.min(axis=1)
            # the marker where this stiffness carries the mode that sets the smallest depth
            at = np.isfinite(best) & np.isclose(best, smallest)
            if at.any():
                entries[f"signal in {carrier}"] = ax.plot(
                    x[at], 1e3 * best[at], ls="none", marker=marker, ms=11,
                    mfc=colour, mec="k", mew=0.8, color=colour, zorder=2,
                    label=f"signal in {carrier}")[0]
    else:
        for j, mode in enumerate(panel.mode_names):
            if np.isfinite(depth[:, j]).any():
                label = f"{mode}, alone"
                entries[label] = ax.plot(x, 1e3 * depth[:, j], lw=1.0, zorder=2,
                                         label=label, **style(j))[0]
    if np.isfinite(smallest).any():
        # without carrier marks a point between undetectable mountings needs its own mark
        entries[line_label] = ax.plot(x, 1e3 * smallest, color="k", lw=1.8, zorder=3,
                                      label=line_label,
                                      marker="o" if carried is None else None, ms=5)[0]
    for lo, hi in _runs(x, ~np.isfinite(smallest)):
        entries["nothing of the sweep detectable"] = ax.axvspan(
            lo, hi, color="0.9", lw=0, zorder=0, label="nothing of the sweep detectable")
    if shallowest is not None:
        entries["shallowest"] = ax.axhline(
            1e3 * shallowest, color="0.4", lw=1.0, ls="-.", zorder=1,
            label=f"shallowest crack computed {1e3 * shallowest:.3g} mm")
    ax.set_xscale("log")
    # explicit: where no mounting detects anything every curve is NaN, and a log axis
    # cannot take its limits from no data; a margin of a fifth of a decade: the end
    # markers drawn whole
    ax.set_xlim(float(np.min(x)) / MARGIN, float(np.max(x)) * MARGIN)
    if x.size > finite.size:
        ax.axvline(finite[-1] * 1.7, color="0.6", lw=0.8)
        ax.text(x[-1], 0.02, "clamped", transform=ax.get_xaxis_transform(), ha="center",
                fontsize=8)
    ax.set_xlabel(f"{panel.axis_name} [{panel.axis_unit}]")
    ax.grid(True, which="both", alpha=0.3)


def _runs(x: np.ndarray, mask: np.ndarray) -> list[tuple[float, float]]:
    """The spans of ``x`` (ascending, log-spaced) where ``mask`` holds, each widened by
    half a step to both sides and clipped to the ends of ``x``."""
    if x.size < 2:
        return []
    edges = np.sqrt(x[1:] * x[:-1])
    lo_edges = np.concatenate([[x[0]], edges])
    hi_edges = np.concatenate([edges, [x[-1]]])
    spans, start = [], None
    for k, on in enumerate(mask):
        if on and start is None:
            start = k
        if start is not None and (not on or k == mask.size - 1):
            end = k if on else k - 1
            spans.append((float(lo_edges[start]), float(hi_edges[end])))
            start = None
    return spans


AT_MEAN = "at the FE mean mesh ratio over the engagement"
AT_MINIMUM = "at the minimum mesh ratio"


def carrier_figure(name: str, carrier, kind):
    """What planet 1 on the cracked tooth does to each mode that moves (deepest crack):
    the size of the frequency change at the FE mean mesh ratio over the engagement and at
    its minimum, one row per mode on a log axis (the modes move by parts per million to
    per cent: on a linear axis most lie on zero); beside it, one passage of the mode that
    moves most against the carrier angle (the model switches the cracked mesh on for the
    engagement, so the change is a step)."""
    fig, axes = _axes(2, layout="constrained", width_ratios=(3, 2))
    fig.get_layout_engine().set(w_pad=0.3)  # the right panel's y label reads as its own
    rows, passage = axes[0]
    out = carrier.omega_out[-1]
    relative = carrier.omega_angle / out - 1
    low = carrier.omega_angle_min / out - 1
    moving = moving_modes(np.vstack([relative, low]))
    fig.suptitle(f"{name}: planet 1 on the cracked tooth (deepest crack)", fontsize=10)
    if moving.size == 0:
        for ax in (rows, passage):
            _legend(ax)
        return fig
    fig.set_size_inches(14, max(5.0, 1.8 + 0.32 * moving.size))

    def peak(change):
        return change[np.abs(change).argmax(axis=0), np.arange(change.shape[1])]

    mean, minimum = 100 * np.abs(peak(relative)), 100 * np.abs(peak(low))
    y = -np.arange(moving.size)
    rows.plot(mean[moving], y, ls="none", marker="o", ms=5, color="tab:blue", label=AT_MEAN)
    rows.plot(minimum[moving], y, ls="none", marker="o", ms=10, mfc="none", mew=1.5,
              color="tab:red", label=AT_MINIMUM)
    rows.set_xscale("log")
    names = mode_names(carrier.omega_out[0])
    rows.set_yticks(y, [_label(i, out[i] / (2 * math.pi), kind[i], names[i]) for i in moving],
                    fontsize=8)
    rows.set_ylim(y[-1] - 0.7, 0.7)
    rows.set_xlabel("|frequency change| while planet 1 meshes the cracked tooth [%] (log "
                    "axis)")
    rows.set_ylabel("rigid mode: intact frequency, type")
    rows.grid(True, which="both", axis="x", alpha=0.3)
    # above the rows, where it covers none of them
    rows.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2)
    strongest = moving[np.argmax(minimum[moving])]
    angle = np.degrees(carrier.angle)
    passage.plot(angle, 100 * relative[:, strongest], color="tab:blue", lw=1.5,
                 label=AT_MEAN)
    passage.plot(angle, 100 * low[:, strongest], color="tab:red", lw=1.5, ls="--",
                 label=AT_MINIMUM)
    timing = carrier.timing
    passage.axvspan(0, math.degrees(timing.pass_angle), color="k", alpha=0.08,
                    label=f"cracked tooth in mesh ({timing.pass_seconds * 1e3:.3g} ms)")
    passage.set_xlabel("carrier angle from the start of the engagement [deg]")
    passage.set_ylabel("frequency change [%]")
    passage.set_title(f"one passage, rigid {names[strongest]} "
                      f"({out[strongest] / (2 * math.pi):.1f} Hz)", fontsize=9)
    shown = 100 * np.concatenate([relative[:, strongest], low[:, strongest]])
    span = np.ptp(shown) or 1.0
    # room below the curves for the legend
    passage.set_ylim(shown.min() - 0.35 * span, shown.max() + 0.08 * span)
    passage.grid(True, alpha=0.3)
    passage.legend(fontsize=7, loc="lower center")
    return fig


def _legend_below(fig, ax, ncol: int = 2):
    """The legend of ``ax`` below it, outside the data (a constrained-layout figure)."""
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="outside lower center", ncol=ncol, fontsize=9)
    else:
        ax.text(0.5, 0.5, "no mode moves", transform=ax.transAxes, ha="center")


def _legend(ax):
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    else:
        ax.text(0.5, 0.5, "no mode moves", transform=ax.transAxes, ha="center")
