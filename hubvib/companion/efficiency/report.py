"""Plain-text reports of ball/roller gear efficiency designs (seed 001), for the CLI."""
from __future__ import annotations

import math

from hubvib.companion.efficiency.core import CURVE_DEGREES, loss_curve
from hubvib.companion.efficiency.design import GearDesign, alpha1_label
from hubvib.companion.efficiency.table import PaperTable

SOURCE = ("Kapitonov 2024, Improving the efficiency of ball and roller gears by optimizing "
          "geometrics of engagement parts, Transport Engineering 3:20-30 (seed 001)")

_LINKS = (("driving", "driving link (single-period track, f1)"),
          ("fixed", "fixed link (multi-period track, f2)"),
          ("carrier", "carrier-separator (slots, f3)"))


def format_design(design: GearDesign, curve: bool = False) -> str:
    """Full report of one ratio: optimum, geometry, link losses (and the alpha1 curve)."""
    at, best, f = design.at, design.optimum, design.friction
    lines = [f"Ball/roller planetary gear i = {design.ratio} (z1 = 1, z2 = {at.z2}); {SOURCE}",
             f"friction: f1 = {f.f1:g} (rolling, driving track), f2 = {f.f2:g} (rolling with "
             f"sliding, fixed track), f3 = {f.f3:g} (sliding, carrier slots)",
             f"optimal alpha1: {math.degrees(best.whole.alpha1_rad):.0f} deg on whole degrees "
             f"(eta = {best.whole.eta * 100:.3f} %), "
             f"{math.degrees(best.continuous.alpha1_rad):.4f} deg continuous "
             f"(eta = {best.continuous.eta * 100:.3f} %)",
             f"at alpha1 = {alpha1_label(design)}: alpha2 = {math.degrees(at.alpha2_rad):.4f} deg "
             f"(eq. 11), psi = {at.psi:.5f}, eta = {at.eta * 100:.3f} %",
             "track geometry (eqs. 12, 13):",
             f"  {'satellite':<9} {'d_c [mm]':>9} {'R [mm]':>11} {'A [mm]':>11}"]
    for t in design.tracks:
        lines.append(f"  {t.satellite:<9} {t.satellite_diameter_m * 1e3:>9.3f} "
                     f"{t.mean_radius_m * 1e3:>11.7g} {t.amplitude_m * 1e3:>11.7g}")
    p = design.power
    lines += [f"link losses at input power W1 = {p.input_w:g} W (output W_out = eta W1 = "
              f"{p.output_w:.2f} W; W_k = psi_k W_out):",
              f"  {'link':<40} {'psi_k':>8} {'loss [W]':>9}"]
    for key, label in _LINKS:
        lines.append(f"  {label:<40} {getattr(at, 'psi_' + key):>8.5f} "
                     f"{getattr(p, key + '_w'):>9.2f}")
    lines.append(f"  {'total (= W1 - W_out)':<40} {at.psi:>8.5f} {p.total_loss_w:>9.2f}")
    order = sorted(_LINKS, key=lambda link: getattr(at, "psi_" + link[0]))
    lines.append("  loss ordering: " + " < ".join(key for key, _ in order))
    if curve:
        lines += ["", format_curve(design)]
    return "\n".join(lines)


def format_curve(design: GearDesign, degrees=CURVE_DEGREES) -> str:
    """Loss terms and efficiency against whole-degree alpha1 (the paper's Figs. 5-8)."""
    p_in = design.power.input_w
    lines = [f"loss terms against alpha1, i = {design.ratio}, input power {p_in:g} W:",
             f"{'alpha1':>6} {'alpha2':>8} {'psi_drv':>8} {'psi_fix':>8} {'psi_car':>8} "
             f"{'eta [%]':>8} {'W_drv':>7} {'W_fix':>7} {'W_car':>7} {'W_sum':>7}"]
    for c in loss_curve(design.ratio, degrees, design.friction):
        w = c.power(p_in)
        lines.append(f"{math.degrees(c.alpha1_rad):>6.0f} {math.degrees(c.alpha2_rad):>8.3f} "
                     f"{c.psi_driving:>8.5f} {c.psi_fixed:>8.5f} {c.psi_carrier:>8.5f} "
                     f"{c.eta * 100:>8.3f} {w.driving_w:>7.2f} {w.fixed_w:>7.2f} "
                     f"{w.carrier_w:>7.2f} {w.total_loss_w:>7.2f}")
    return "\n".join(lines)


def format_designs(designs: tuple[GearDesign, ...]) -> str:
    """One line per ratio."""
    names = [t.satellite for t in designs[0].tracks]
    head = (f"{'i':>4} {'z2':>3} {'a1* [deg]':>9} {'a1 cont':>8} {'a1 [deg]':>8} "
            f"{'a2 [deg]':>9} {'eta [%]':>8} {'loss [W]':>9}")
    head += "".join(f" {'R_' + n + ' [mm]':>14} {'A_' + n + ' [mm]':>14}" for n in names)
    p_in = designs[0].power.input_w
    lines = [f"Ball/roller planetary gears; {SOURCE}", f"losses at input power {p_in:g} W", head]
    for d in designs:
        row = (f"{d.ratio:>4} {d.at.z2:>3} {math.degrees(d.optimum.whole.alpha1_rad):>9.0f} "
               f"{math.degrees(d.optimum.continuous.alpha1_rad):>8.4f} "
               f"{math.degrees(d.at.alpha1_rad):>8.4g} {math.degrees(d.at.alpha2_rad):>9.4f} "
               f"{d.at.eta * 100:>8.3f} {d.power.total_loss_w:>9.2f}")
        row += "".join(f" {t.mean_radius_m * 1e3:>14.7g} {t.amplitude_m * 1e3:>14.7g}"
                       for t in d.tracks)
        lines.append(row)
    return "\n".join(lines)


_TABLE_ROWS = (("alpha1_deg", "alpha1 [deg]", "{:.0f}"), ("alpha2_deg", "alpha2 [deg]", "{:.4f}"),
               ("z2", "z2", "{:.0f}"), ("R_ball_mm", "R_ball [mm]", "{:.7g}"),
               ("A_ball_mm", "A_ball [mm]", "{:.7g}"), ("R_roller_mm", "R_roller [mm]", "{:.7g}"),
               ("A_roller_mm", "A_roller [mm]", "{:.7g}"), ("eta_percent", "eta [%]", "{:.3f}"))


def format_table(table: PaperTable) -> str:
    """The paper's table layout, computed, with the cell-by-cell agreement summary."""
    ratios = [d.ratio for d in table.designs]
    cells = {(c.quantity, c.ratio): c for c in table.cells}
    lines = [f"Optimal geometry recomputed from eqs. (1)-(13); {SOURCE}, Table",
             f"{'parameter':<14}" + "".join(f"{'i = ' + str(i):>12}" for i in ratios)]
    for key, label, fmt in _TABLE_ROWS:
        if not any((key, i) in cells for i in ratios):
            continue
        row = f"{label:<14}"
        for i in ratios:
            cell = cells.get((key, i))
            text = "" if cell is None else fmt.format(cell.computed) + ("*" if cell.slip else "")
            row += f"{text:>12}"
        lines.append(row)
    lines += summarize_table(table)
    return "\n".join(lines)


def summarize_table(table: PaperTable) -> list[str]:
    """Sentences on the agreement with the printed table, generated from the cells."""
    compared = [c for c in table.cells if c.agrees is not None]
    if not compared:
        return ["(no printed values to compare: the paper's table is for its friction "
                "coefficients and ratios 5..30)"]
    good = [c for c in compared if c.agrees]
    lines = [f"against the printed table: {len(good)} of {len(compared)} cells within tolerance"]
    rel = [abs(c.deviation) for c in good if c.kind == "rel"]
    if rel:
        lines[-1] += f" (R, A: max relative deviation {max(rel):.1e}, tolerance 1e-5)"
    for c in compared:
        if c.slip:
            lines.append(f"* {c.quantity} at i = {c.ratio}: {c.slip}; the equations give "
                         f"{c.computed:.4f}")
        elif not c.agrees:
            lines.append(f"! {c.quantity} at i = {c.ratio}: computed {c.computed:.7g}, "
                         f"printed {c.published:.7g}")
        if c.quantity == "eta_percent":
            lines.append(f"eta at i = {c.ratio}: {c.computed:.2f} % (paper: "
                         f"{c.published:g} %)")
    return lines
