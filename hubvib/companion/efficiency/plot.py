"""Figures of the ball/roller gear losses against the driving-track lift angle (seed 001).

matplotlib is imported inside the functions (off-screen Agg backend); each returns a figure for
:func:`hubvib.foundation.output.save_figure`.
"""
from __future__ import annotations

import math

from hubvib.companion.efficiency.core import CURVE_DEGREES, Friction, loss_curve


def link_loss_figure(ratio: int, friction: Friction, input_power_w: float,
                     degrees=CURVE_DEGREES):
    """Link losses [W] and efficiency against alpha1 for one ratio (the paper's Figs. 5, 6)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    curve = loss_curve(ratio, degrees, friction)
    powers = [c.power(input_power_w) for c in curve]
    fig, (ax_w, ax_eta) = plt.subplots(1, 2, figsize=(11, 4.5))
    for key, label in (("driving_w", "driving link (f1)"), ("fixed_w", "fixed link (f2)"),
                       ("carrier_w", "carrier-separator (f3)"), ("total_loss_w", "total")):
        ax_w.plot(degrees, [getattr(p, key) for p in powers], marker=".", label=label)
    ax_w.set_xlabel("driving-track lift angle alpha1 [deg]")
    ax_w.set_ylabel(f"power loss [W] at input {input_power_w:g} W")
    ax_w.set_title(f"i = {ratio}: link losses")
    ax_w.legend(fontsize=8)
    ax_w.grid(alpha=0.3)
    best = min(curve, key=lambda c: c.psi)
    ax_eta.plot(degrees, [c.eta * 100 for c in curve], marker=".")
    ax_eta.axvline(math.degrees(best.alpha1_rad), color="k", lw=0.7, ls=":")
    ax_eta.set_xlabel("driving-track lift angle alpha1 [deg]")
    ax_eta.set_ylabel("efficiency eta [%]")
    ax_eta.set_title(f"i = {ratio}: eta, best {best.eta * 100:.2f} % at "
                     f"{math.degrees(best.alpha1_rad):.0f} deg")
    ax_eta.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def efficiency_figure(ratios, friction: Friction, degrees=CURVE_DEGREES):
    """Relative loss psi and efficiency against alpha1 for several ratios (Figs. 7, 8)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_psi, ax_eta) = plt.subplots(1, 2, figsize=(11, 4.5))
    for ratio in ratios:
        curve = loss_curve(ratio, degrees, friction)
        ax_psi.plot(degrees, [c.psi for c in curve], label=f"i = {ratio}")
        ax_eta.plot(degrees, [c.eta * 100 for c in curve], label=f"i = {ratio}")
    for ax, label in ((ax_psi, "relative loss psi [-]"), (ax_eta, "efficiency eta [%]")):
        ax.set_xlabel("driving-track lift angle alpha1 [deg]")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    return fig
