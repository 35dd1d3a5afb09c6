"""Figures of a crack study (matplotlib, imported here only).

Every curve gets its own colour, marker and line style (10 colours x 8 markers
x 4 line styles), and only modes that move are drawn: 18 modes on one
10-colour cycle could not be told apart.
"""
from __future__ import annotations

import math

import numpy as np

from .mode_names import mode_names
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
    return f"{name or i + 1}: {frequency_hz:.1f} Hz {kind}"


#: curves per panel at most: more cannot be told apart
PER_PANEL = 8


def relative_shift_figure(name: str, depths: np.ndarray, omega: np.ndarray, kind):
    """Instantaneous relative frequency shift [%] (planet 1 on the cracked tooth) against
    crack depth, moving modes only, at most :data:`PER_PANEL` curves per panel."""
    relative = omega / omega[0] - 1
    moving = moving_modes(relative)
    panels = [moving[j:j + PER_PANEL] for j in range(0, max(moving.size, 1), PER_PANEL)]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(panels), 1, figsize=(9, 4 * len(panels)), squeeze=False,
                             layout="constrained")
    for ax, modes in zip(axes[:, 0], panels):
        for n, i in enumerate(modes):
            ax.plot(1e3 * depths, 100 * relative[:, i], **style(n),
                    label=_label(i, omega[0, i] / (2 * math.pi), kind[i],
                                 mode_names(omega[0])[i]))
        if depths.size > 1:
            ax.axvline(1e3 * depths[1], color="0.6", lw=0.8, ls="-.",
                       label=f"shallowest crack computed {1e3 * depths[1]:.3g} mm")
        ax.set_xlabel("crack depth [mm]")
        ax.set_ylabel("instantaneous frequency shift [%]")
        ax.grid(True, alpha=0.3)
        _legend(ax)
    fig.suptitle(f"{name}: relative shift with planet 1 on the cracked tooth "
                 "(instantaneous; a record sees the time average)", fontsize=10)
    return fig


def shift_threshold_figure(name: str, pod):
    """|Shift| [Hz] a record sees against depth, with the alarm thresholds (log scale); the
    seven modes moving most against their identification scatter; the alarm thresholds
    of the watched modes as one grey band from the lowest to the highest."""
    fig, axes = _axes(layout="constrained")
    ax = axes[0, 0]
    nominal = pod.nominal
    shift = -nominal.shift_hz
    relative = nominal.shift_hz / nominal.frequency_hz[0]
    moving = moving_modes(relative)
    strongest = moving[np.argsort(-np.abs(shift[-1, moving]) / pod.sigma_hz[moving],
                                  kind="stable")][:PER_PANEL - 1]
    for n, i in enumerate(sorted(strongest)):
        positive = shift[:, i] > 0
        ax.plot(1e3 * pod.depths[positive], shift[positive, i], **style(n),
                label=_label(i, nominal.frequency_hz[0, i], pod.kind[i],
                             mode_names(nominal.frequency_hz[0])[i]))
    low, high = pod.threshold_hz[pod.watched].min(), pod.threshold_hz[pod.watched].max()
    ax.axhspan(low, high * 1.0001, color="k", alpha=0.15,
               label=f"alarm thresholds of the watched modes {low:.3g}-{high:.3g} Hz")
    ax.set_yscale("log")
    ax.set_xlabel("crack depth [mm]")
    ax.set_ylabel("frequency drop seen by a record [Hz]")
    ax.set_title(f"{name}: frequency drop against the alarm threshold")
    ax.grid(True, which="both", alpha=0.3)
    _legend(ax)
    return fig


def pod_figure(name: str, pod, modes):
    """POD against depth for ``modes`` (0-based) against the reducer's own baseline; the
    best of them against the model's spectrum as one grey line."""
    fig, axes = _axes()
    ax = axes[0, 0]
    f0 = pod.nominal.frequency_hz[0]
    for n, i in enumerate(modes):
        ax.plot(1e3 * pod.depths, pod.pod[:, i], **style(n),
                label=_label(i, f0[i], pod.kind[i], mode_names(f0)[i]))
    for n, T in enumerate(sorted(pod.family_pod)[:3]):
        ax.plot(1e3 * pod.depths, pod.family_pod[T], color="k", lw=2.5 - 0.5 * n,
                ls=("-", "--", ":")[n], marker="o", ms=3,
                label=f"watched modes together, {T:g} s records")
    ax.axhline(pod.detection_probability, color="k", lw=0.8, ls="--",
               label=f"required POD {pod.detection_probability:g}")
    ax.axhline(pod.false_alarm_rate, color="k", lw=0.8, ls=":",
               label=f"false-alarm rate {pod.false_alarm_rate:g}")
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("crack depth [mm]")
    ax.set_ylabel("probability of detection")
    ax.axvline(1e3 * pod.depths[1], color="0.6", lw=0.8, ls="-.",
               label=f"shallowest crack computed {1e3 * pod.depths[1]:.3g} mm")
    ax.set_title(f"{name}: probability of detection ({pod.samples} Monte Carlo samples; "
                 f"single modes: records of the scene's length)", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    return fig


def map_figure(name: str, dmap, deepest: float, shallowest: float | None = None):
    """Smallest detectable depth against the mounting, per stiffness carrying the signal
    (the label rule of the modes table) and over all modes; the sweep's shallowest crack
    marked: nothing below it was computed."""
    fig, axes = _axes(2)
    for ax, swept in zip(axes[0], ("c_ru_mount", "c_r_mount")):
        depth, carried = dmap.depth[swept], dmap.carried_by[swept]
        ax.plot(dmap.mounts, 1e3 * dmap.smallest(swept), color="k", lw=3, alpha=0.35,
                label="any mode")
        if shallowest is not None:
            ax.axhline(1e3 * shallowest, color="0.6", lw=0.8, ls="-.",
                       label=f"shallowest crack computed {1e3 * shallowest:.3g} mm")
        for n, carrier in enumerate(("c_ru", "c_r", "c_rp")):
            masked = np.where((carried == carrier) & ~np.isnan(depth), depth, np.inf)
            best = masked.min(axis=1)
            best = np.where(np.isinf(best), np.nan, best)
            ax.plot(dmap.mounts, 1e3 * best, **style(n), label=f"signal in {carrier}")
        ax.set_xscale("log")
        # explicit: where no mounting detects anything every curve is NaN, and a log axis
        # cannot take its limits from no data
        ax.set_xlim(float(np.min(dmap.mounts)), float(np.max(dmap.mounts)))
        ax.set_ylim(0, 1.05e3 * deepest)
        ax.set_xlabel(f"{swept} [N/m]")
        ax.set_ylabel("smallest detectable crack depth [mm]")
        other = dmap.fixed[swept]
        ax.set_title(f"{swept} swept ({'c_r' if swept == 'c_ru_mount' else 'c_ru'}_mount "
                     f"{'rigid' if math.isinf(other) else f'{other:.3g} N/m'})", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"{name}: detectability against the ring mounting (gap: not detectable)")
    return fig


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
    rows.set_ylabel("mode: intact frequency, type")
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
    passage.set_title(f"one passage, mode {strongest + 1} "
                      f"({out[strongest] / (2 * math.pi):.1f} Hz)", fontsize=9)
    shown = 100 * np.concatenate([relative[:, strongest], low[:, strongest]])
    span = np.ptp(shown) or 1.0
    # room below the curves for the legend
    passage.set_ylim(shown.min() - 0.35 * span, shown.max() + 0.08 * span)
    passage.grid(True, alpha=0.3)
    passage.legend(fontsize=7, loc="lower center")
    return fig


def _legend(ax):
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    else:
        ax.text(0.5, 0.5, "no mode moves", transform=ax.transAxes, ha="center")
