"""Figures of a crack study (matplotlib, imported here only).

Every curve gets its own colour, marker and line style (10 colours x 8 markers
x 4 line styles), and only modes that move are drawn: 18 modes on one
10-colour cycle could not be told apart.
"""
from __future__ import annotations

import math

import numpy as np

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


def _axes(ncols: int = 1):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt.subplots(1, ncols, figsize=(7 * ncols, 5), squeeze=False)


def _label(i: int, frequency_hz: float, kind: str) -> str:
    return f"{i + 1}: {frequency_hz:.1f} Hz {kind}"


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
                    label=_label(i, omega[0, i] / (2 * math.pi), kind[i]))
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
    seven modes moving most against their identification scatter."""
    fig, axes = _axes()
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
                label=_label(i, nominal.frequency_hz[0, i], pod.kind[i]))
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
                label=_label(i, f0[i], pod.kind[i]))
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


def carrier_figure(name: str, carrier, kind):
    """Frequencies against carrier angle over one passage of planet 1, deepest crack:
    solid at the FE mean ratio of the cracked mesh, thin dotted at its minimum ratio."""
    fig, axes = _axes()
    ax = axes[0, 0]
    out = carrier.omega_out[-1]
    relative = carrier.omega_angle / out - 1
    low = carrier.omega_angle_min / out - 1
    angle = np.degrees(carrier.angle)
    for n, i in enumerate(moving_modes(np.vstack([relative, low]))):
        s = style(n)
        ax.plot(angle, 100 * relative[:, i], color=s["color"], linestyle=s["linestyle"],
                marker=s["marker"], markevery=8, markersize=4,
                label=_label(i, out[i] / (2 * math.pi), kind[i]))
        ax.plot(angle, 100 * low[:, i], color=s["color"], lw=0.7, ls=":")
    timing = carrier.timing
    ax.axvspan(0, math.degrees(timing.pass_angle), color="k", alpha=0.05,
               label=f"cracked tooth in mesh ({timing.pass_seconds * 1e3:.3g} ms)")
    ax.set_xlabel("carrier angle from the start of the engagement [deg]")
    ax.set_ylabel("frequency change against no planet on the crack [%]")
    ax.set_title(f"{name}: one passage of planet 1 (dotted: minimum mesh ratio)")
    ax.grid(True, alpha=0.3)
    _legend(ax)
    return fig


def _legend(ax):
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    else:
        ax.text(0.5, 0.5, "no mode moves", transform=ax.transAxes, ha="center")
