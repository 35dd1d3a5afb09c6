"""Picture of a crack path on the ring: the cracked tooth, its neighbours, the rim and the
support pads (matplotlib, off-screen; SI coordinates)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from hubvib.foundation.output import save_figure
from hubvib.meshing.crack_path import tooth_outline
from hubvib.meshing.ring_gear import RingGear


def render_path(ring: RingGear, tooth: int, path: np.ndarray, out: Path,
                title: str = "") -> Path:
    """PNG of the polyline ``path`` [m] (mouth first) around ring tooth ``tooth``, with the
    load point of that tooth; written atomically to ``out``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 6))
    for k in range(tooth - 2, tooth + 3):
        ax.plot(*tooth_outline(ring, k % ring.teeth).T, color="0.2", lw=1)
    pitch = 2 * math.pi / ring.teeth
    centre = ring.tooth_angle(tooth)
    arc = np.linspace(centre - 2.5 * pitch, centre + 2.5 * pitch, 100)
    ax.plot(ring.outer_radius * np.cos(arc), ring.outer_radius * np.sin(arc), color="0.2", lw=1)
    label = "support pad"
    for lo, hi in ring.supports.arcs():
        held = np.linspace(lo, hi, 50)
        near = np.abs(np.angle(np.exp(1j * (held - centre)))) < 2.5 * pitch
        if np.any(near):
            ax.plot(ring.outer_radius * np.cos(held[near]),
                    ring.outer_radius * np.sin(held[near]), color="tab:blue", lw=4, label=label)
            label = None
    ax.plot(*np.asarray(path).T, color="red", lw=1.5, marker=".", ms=3, label="crack path")
    load, _ = ring.load_point(tooth)
    ax.plot(*load, "g^", label="mesh force")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title, fontsize=10)
    ax.legend(loc="best", fontsize=8)
    return save_figure(fig, out)
