"""Figures of the elastic ring beside the rigid one (matplotlib, imported here only; SI
inside, drawn in mm and Hz): the watched modes of both ring models against crack depth, the
elastic ring's watched modes with the crack open, record-averaged and closed, and the
crack's open length over a carrier revolution.

Every function takes plain arrays, so the figures do not depend on the result types that
hold them; every curve has its own colour, marker and line style.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
           "tab:pink", "tab:gray", "tab:olive", "tab:cyan")
MARKERS = ("o", "s", "^", "v", "D", "P", "X", "*")
LINES = ("-", "--", ":", "-.")
#: the three crack states of a mode: line style, marker, colour
STATES = {"open": ("-", "o", "tab:red"), "record-averaged": ("--", "s", "tab:blue"),
          "closed": (":", "^", "k")}


def curve_style(i: int) -> dict:
    """Colour, marker and line style of curve ``i``: all three differ between the first
    four curves, the pair (colour, marker) for the first 40."""
    return {"color": COLOURS[i % len(COLOURS)], "marker": MARKERS[i % len(MARKERS)],
            "linestyle": LINES[i % len(LINES)], "markersize": 6, "linewidth": 1.8}


def _figure(rows: int, cols: int, size: tuple):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt.subplots(rows, cols, figsize=size, squeeze=False, layout="constrained")


def _legend_below(fig, ax, ncol: int = 2) -> None:
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="outside lower center", ncol=ncol, fontsize=9)


#: what the elastic ring's change is, by whether the crack's load cycle was computed
ELASTIC_RECORD = "a record's change under the working load (crack breathing)"
ELASTIC_OPEN = "crack held open, planet 1 half a planet pitch away"
RIGID_RECORD = "a record's change, planet 1 on the cracked tooth part of the time"


def both_models_figure(name: str, rigid_depths, rigid_change_hz, rigid_labels: Sequence[str],
                       elastic_depths, elastic_change_hz, elastic_labels: Sequence[str],
                       elastic_statistic: str = ELASTIC_OPEN,
                       rigid_statistic: str = RIGID_RECORD):
    """The watched modes' frequency change from the intact ring [Hz] against crack depth,
    the rigid ring (9 + 3N model) on the left and the elastic ring on the right, each on a
    scale of its own (they differ by two orders of magnitude), each panel's title saying
    what its change is (``rigid_statistic``, ``elastic_statistic``).

    Parameters
    ----------
    rigid_depths, elastic_depths : array (depths,)  [m]
    rigid_change_hz, elastic_change_hz : array (depths, modes)  [Hz]
        The change a record sees, one column per watched mode (NaN: not tracked there).
    rigid_labels, elastic_labels : sequence of str
        One legend label per column.
    """
    fig, axes = _figure(1, 2, (14, 6.4))
    panels = ((f"rigid ring (9 + 3N model)\n{rigid_statistic}", rigid_depths,
               rigid_change_hz, rigid_labels),
              (f"elastic ring (FE ring coupled)\n{elastic_statistic}", elastic_depths,
               elastic_change_hz, elastic_labels))
    for ax, (title, depths, change, labels) in zip(axes[0], panels):
        change = np.asarray(change, dtype=float).reshape(len(depths), -1)
        for j, label in enumerate(labels):
            ax.plot(1e3 * np.asarray(depths), change[:, j], **curve_style(j), label=label)
        ax.set_xlabel("crack depth [mm]")
        ax.set_ylabel("frequency change from the intact ring [Hz]")
        ax.set_title(title, fontsize=11)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=9, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1)
    fig.suptitle(f"{name}: watched modes against crack depth, both ring models", fontsize=12)
    return fig


def crack_states_figure(name: str, depths, intact_hz, open_hz, labels: Sequence[str],
                        averaged_hz=None):
    """Each watched mode of the elastic ring against crack depth with the crack's faces
    open (free), record-averaged over the carrier revolution (when ``averaged_hz`` is
    given) and closed (tied: the intact ring), one panel per mode on a scale of its own.

    Parameters
    ----------
    depths : array (depths,)  [m]
    intact_hz : array (modes,)  [Hz]
        The intact (= closed) frequency of each mode.
    open_hz : array (depths, modes)  [Hz]
    labels : sequence of str
        One panel title per mode.
    averaged_hz : array (depths, modes) or None  [Hz]
        The record-averaged frequency; None: its line is left out.
    """
    intact_hz = np.asarray(intact_hz, dtype=float).ravel()
    open_hz = np.asarray(open_hz, dtype=float).reshape(len(depths), -1)
    modes = intact_hz.size
    cols = min(2, max(modes, 1))
    rows = max(1, -(-modes // cols))
    fig, axes = _figure(rows, cols, (7 * cols, 3.6 * rows + 1.2))
    mm = 1e3 * np.asarray(depths, dtype=float)
    curves = {"open": open_hz,
              "closed": np.broadcast_to(intact_hz, open_hz.shape)}
    if averaged_hz is not None:
        curves = {"open": open_hz,
                  "record-averaged": np.asarray(averaged_hz, dtype=float).reshape(
                      open_hz.shape), "closed": curves["closed"]}
    for j, ax in enumerate(axes.ravel()):
        if j >= modes:
            ax.set_visible(False)
            continue
        for state, values in curves.items():
            line, marker, colour = STATES[state]
            ax.plot(mm, values[:, j], ls=line, marker=marker, color=colour, lw=1.8, ms=6,
                    label=_state_label(state))
        ax.set_title(labels[j], fontsize=10)
        ax.set_xlabel("crack depth [mm]")
        ax.set_ylabel("frequency [Hz]")
        ax.grid(True, alpha=0.3)
    fig.suptitle(f"{name}: elastic ring, watched modes against crack depth", fontsize=12)
    if modes:
        _legend_below(fig, axes.ravel()[0], ncol=len(curves))
    return fig


def _state_label(state: str) -> str:
    return {"open": "crack open (faces free)",
            "record-averaged": "record-averaged over a carrier revolution",
            "closed": "crack closed (faces tied = intact)"}[state]


def open_length_figure(name: str, depths, states: Sequence[tuple], ring_teeth: int | None = None):
    """The crack's open length [mm] against the carrier position (planet 1's ring tooth)
    over one planet pitch (the pattern of every planet in turn), one curve per crack depth.

    Parameters
    ----------
    depths : array (depths,)  [m]
        The crack depth of each curve.
    states : sequence of (carrier_tooth, open_length_m)
        Per depth: planet 1's ring tooth at each carrier position [-] and the length of the
        crack that is open there [m] (arrays of one length).
    ring_teeth : int or None
        The ring's tooth count: the x axis spans one revolution.
    """
    if len(states) != len(depths):
        raise ValueError(f"open_length_figure: {len(states)} states for {len(depths)} depths")
    fig, axes = _figure(1, 1, (10, 6))
    ax = axes[0, 0]
    for j, (depth, (tooth, length)) in enumerate(zip(depths, states)):
        tooth = np.asarray(tooth, dtype=float)
        length = np.asarray(length, dtype=float)
        if tooth.shape != length.shape:
            raise ValueError(f"open_length_figure: depth {1e3 * depth:.3g} mm has "
                             f"{tooth.size} carrier positions but {length.size} open lengths")
        order = np.argsort(tooth, kind="stable")
        ax.plot(tooth[order], 1e3 * length[order], **curve_style(j),
                label=f"crack {1e3 * depth:.3g} mm")
    ax.set_xlabel("carrier position: planet 1's ring tooth (tooth 0 cracked)")
    ax.set_ylabel("open length of the crack [mm]")
    if ring_teeth:
        ax.set_xlim(0, ring_teeth)
    ax.set_ylim(bottom=0.0, top=1.08e3 * max(float(np.max(depths, initial=0.0)), 1e-6))
    ax.grid(True, alpha=0.3)
    ax.set_title(f"{name}: crack state over one planet pitch (it repeats for each planet)",
                 fontsize=12)
    _legend_below(fig, ax, ncol=min(4, max(len(depths), 1)))
    return fig
