"""What ``hubvib efficiency`` writes and prints beyond the report text (seed 001): each
design with its loss curve over the driving-track lift angle, and the CSV and figures."""
from __future__ import annotations

from pathlib import Path

from hubvib.foundation.output import save_figure, write_csv

from hubvib.companion.efficiency.core import CURVE_DEGREES, loss_curve
from hubvib.companion.efficiency.plot import efficiency_figure, link_loss_figure


def design_with_curve(design) -> dict:
    """``design.to_dict()`` with ``curve``: per lift angle of ``CURVE_DEGREES`` the losses
    and the powers [W] at the design's input power."""
    rows = []
    for c in loss_curve(design.ratio, CURVE_DEGREES, design.friction):
        power = c.power(design.power.input_w)
        rows.append({**c.to_dict(), "driving_w": power.driving_w, "fixed_w": power.fixed_w,
                     "carrier_w": power.carrier_w, "total_loss_w": power.total_loss_w})
    return {**design.to_dict(), "curve": rows}


def write_efficiency_files(out: Path, designs) -> list[Path]:
    """The curves of every design as ``efficiency_curves.csv``, a loss figure per ratio and,
    for several ratios, the efficiency against the ratio; returns the paths written."""
    rows = [{"ratio": d.ratio, **row} for d in designs for row in design_with_curve(d)["curve"]]
    files = [write_csv(out / "efficiency_curves.csv", rows)]
    friction, power = designs[0].friction, designs[0].power.input_w
    for d in designs:
        files.append(save_figure(link_loss_figure(d.ratio, friction, power),
                                 out / f"efficiency_losses_i{d.ratio}.png"))
    if len(designs) > 1:
        files.append(save_figure(efficiency_figure([d.ratio for d in designs], friction),
                                 out / "efficiency_eta.png"))
    return files
