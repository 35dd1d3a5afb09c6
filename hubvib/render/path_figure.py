"""Picture of a crack path on the ring: the cracked tooth, its neighbours, the rim and the
support pads (matplotlib, off-screen; coordinates SI inside, drawn in mm)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from hubvib.foundation.output import save_figure
from hubvib.meshing.polyline_crack import tooth_outline
from hubvib.meshing.ring_gear import RingGear

#: the picture's unit: mm, as the step sizes and depths its title and the report state
MM = 1e3


def path_figure(ring: RingGear, tooth: int, path: np.ndarray, title: str = ""):
    """The matplotlib figure of the polyline ``path`` [m] (mouth first) around ring tooth
    ``tooth``, with the load point of that tooth; axes in mm."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 6), layout="constrained")
    for k in range(tooth - 2, tooth + 3):
        ax.plot(*(MM * tooth_outline(ring, k % ring.teeth)).T, color="0.2", lw=1,
                label="ring teeth and rim")
    pitch = 2 * math.pi / ring.teeth
    centre = ring.tooth_angle(tooth)
    arc = np.linspace(centre - 2.5 * pitch, centre + 2.5 * pitch, 100)
    ax.plot(MM * ring.outer_radius * np.cos(arc), MM * ring.outer_radius * np.sin(arc),
            color="0.2", lw=1, label="ring teeth and rim")
    for lo, hi in ring.supports.arcs():
        held = np.linspace(lo, hi, 50)
        near = np.abs(np.angle(np.exp(1j * (held - centre)))) < 2.5 * pitch
        if np.any(near):
            ax.plot(MM * ring.outer_radius * np.cos(held[near]),
                    MM * ring.outer_radius * np.sin(held[near]), color="tab:blue", lw=4,
                    label="support pad")
    ax.plot(*(MM * np.asarray(path)).T, color="red", lw=1.5, marker=".", ms=3,
            label="crack path")
    load, _ = ring.load_point(tooth)
    ax.plot(*(MM * np.asarray(load)), "g^", label="mesh force")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(title, fontsize=10)
    handles, labels = ax.get_legend_handles_labels()
    unique = dict(zip(labels, handles))  # one entry per kind of line
    ax.legend(unique.values(), unique.keys(), loc="best", fontsize=8)
    return fig


def render_path(ring: RingGear, tooth: int, path: np.ndarray, out: Path,
                title: str = "") -> Path:
    """PNG of :func:`path_figure`, written atomically to ``out``."""
    return save_figure(path_figure(ring, tooth, path, title), out)
