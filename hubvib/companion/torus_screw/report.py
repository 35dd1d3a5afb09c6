"""Plain-text reports of the torus screw gear analysis (seed 002), for the CLI."""
from __future__ import annotations

import math

from hubvib.companion.torus_screw.nx_scatter import PAPER_NX, interval_from_bounds
from hubvib.companion.torus_screw.gear import RollerForces, TorusScrewGear, OperatingPoint
from hubvib.companion.torus_screw.paper import TOLERANCE, Claim, PaperCell
from hubvib.companion.torus_screw.sweep import SweepRow

SOURCE = ("Prudnikov & Bodunova 2021, Distribution of forces between units of planetary torus "
          "screw gear (seed 002)")

_ROWS = (("N1_n", "N1 [N]", "{:.3f}"), ("N3_n", "N3 [N]", "{:.3f}"),
         ("S2p_n", "S2' [N]", "{:.3f}"), ("S2pp_n", "S2'' [N]", "{:.3f}"),
         ("M42_n_m", "M42 [N m]", "{:.4f}"), ("M1_n_m", "M1 [N m]", "{:.4f}"),
         ("eta", "eta [-]", "{:.4f}"))

_STATUS = {"agrees": "agrees", "differs": "DIFFERS", "fitted": "fitted",
           "not from the equations": "not eqs."}


def format_header(gear: TorusScrewGear, point: OperatingPoint) -> str:
    """Inputs: gear data, N2, friction, the operating point, inertia terms."""
    return "\n".join([
        f"Planetary torus screw gear, forces on one composite roller; {SOURCE}",
        f"M2 = {gear.output_torque_n_m:g} N m, n_p = {gear.rollers}, u = {gear.ratio:g}, "
        f"R2 = {gear.carrier_radius_m * 1e3:g} mm -> N2 = M2/(n_p R2) = "
        f"{gear.roller_load_n:.2f} N; delta_r = {gear.rolling_friction:g}, "
        f"delta_c = {gear.sliding_friction:g}",
        f"l4 = {gear.roller_length_m * 1e3:g} mm, r4 = {gear.finger_radius_m * 1e3:g} mm, "
        f"r0 = {gear.finger_journal_radius_m * 1e3:g} mm, "
        f"r42 = {gear.roller_journal_radius_m * 1e3:g} mm; Phi4 = "
        f"{point.centrifugal_force_n:.3g} N, M_U = {point.inertia_moment_n_m:.3g} N m",
        "eqs. (14)-(18) with the two print sign slips fixed (N3 terms of (14) and (16))"])


def format_point(point: OperatingPoint) -> str:
    return (f"alpha1 = {math.degrees(point.alpha1_rad):g} deg, alpha3 = "
            f"{math.degrees(point.alpha3_rad):g} deg, phi2 = {math.degrees(point.phi2_rad):g} deg")


def format_comparison(results: tuple[RollerForces, ...],
                      cells: dict[str, tuple[PaperCell, ...]] | None,
                      finger_spacing_m: float) -> str:
    """Both finger types side by side, each computed value beside the printed one."""
    with_paper = cells is not None
    width = 44 if with_paper else 22
    lines = [f"{'':<13}" + "".join(f"{r.fingers + ' fingers':^{width}}" for r in results)]
    sub = (f"{'computed':>11} {'paper':>8} {'dev[%]':>7} {'status':<9}" if with_paper
           else f"{'computed':>11}")
    lines.append(f"{'quantity':<13}" + "".join(f" {sub:<{width - 1}}" for _ in results))
    gamma = "".join(f" {math.degrees(r.gamma_rad):>11.3f}".ljust(width) for r in results)
    lines.append(f"{'gamma [deg]':<13}" + gamma)
    for key, label, fmt in _ROWS:
        row = f"{label:<13}"
        for r in results:
            value = r.to_dict()[key]
            text = f" {'-' if value is None else fmt.format(value):>11}"
            if with_paper:
                cell = next(c for c in cells[r.fingers] if c.quantity == key)
                dev = ("--" if cell.status == "not from the equations"
                       else f"{cell.deviation * 100:+.2f}")
                text += f" {cell.published:>8g} {dev:>7} {_STATUS[cell.status]:<9}"
            row += text.ljust(width)
        lines.append(row)
    lines.append(f"{'det A [m^2]':<13}"
                 + "".join(f" {r.determinant:>11.3e}".ljust(width) for r in results))
    if any(r.fingers == "spherical" for r in results):
        lines.append(f"spherical: gamma = arctan(S4 / (2 r4)) with S4 = "
                     f"{finger_spacing_m * 1e3:g} mm")
    lines.append("S2', S2'' are signed; the paper prints magnitudes (dev compares |S2|)")
    if any(r.eta is None for r in results):
        lines.append("eta '-': M1 <= 0, the input does not drive the gear at these angles")
    if with_paper:
        labels = {key: label for key, label, _ in _ROWS}
        by_tol: dict[float, list[str]] = {}
        for key, tol in TOLERANCE.items():
            by_tol.setdefault(tol, []).append(labels[key].split(" [")[0])
        lines.append("agrees: |dev| within " + "; ".join(
            f"{', '.join(names)} {tol * 100:g} %" for tol, names in sorted(by_tol.items()))
            + " (the seed reference's tolerances; eta takes M1's)")
        notes: dict[str, list[str]] = {}
        for group in cells.values():
            for c in group:
                if c.note:
                    notes.setdefault(c.note, []).append(f"{c.fingers} {labels[c.quantity]}")
        lines += [f"{', '.join(where)}: {note}" for note, where in notes.items()]
    return "\n".join(line.rstrip() for line in lines)


def format_claims(claims: tuple[Claim, ...]) -> str:
    lines = ["the paper's claims, checked:"]
    for c in claims:
        lines.append(f"  [{'holds' if c.holds else 'does NOT hold'}] {c.claim}: {c.evidence}")
    return "\n".join(lines)


def format_nx() -> str:
    """The NX experiment: printed bounds -> centre and Delta (eqs. 21-22) -> eta."""
    lines = ["NX experiment (eqs. 21-22: [y_min, y_max] = mean -/+ k S), M2 = 150 N m, u = 48:",
             f"  {'factor':<38} {'y_min':>6} {'y_max':>6} {'centre':>7} {'k S':>6} "
             f"{'screened M1':>11} {'eta':>8} {'printed':>7}"]
    for f in PAPER_NX:
        interval = interval_from_bounds(f.low, f.high)
        lines.append(f"  {f.label:<38} {f.low:>6.3f} {f.high:>6.3f} {interval.mean:>7.4f} "
                     f"{interval.half_width:>6.4f} {f.screened_mean:>11.3f} "
                     f"{f.efficiency():>8.5f} {f.published_eta:>7g}")
    return "\n".join(lines)


def format_sweep(rows: tuple[SweepRow, ...]) -> str:
    """One line per operating point: N1, N3, M1, eta for each finger shape."""
    kinds = [f.fingers[:3] for f in rows[0].forces]
    head = f"{'phi2':>7} {'alpha1':>8} {'alpha3':>8}" + "".join(
        f" {'N1_' + k:>9} {'N3_' + k:>9} {'M1_' + k:>8} {'eta_' + k:>8}" for k in kinds)
    lines = [head]
    for r in rows:
        line = (f"{math.degrees(r.point.phi2_rad):>7.2f} {math.degrees(r.point.alpha1_rad):>8.3f}"
                f" {math.degrees(r.point.alpha3_rad):>8.3f}")
        for f in r.forces:
            eta = "-" if f.eta is None else f"{f.eta:.4f}"
            line += f" {f.n1_n:>9.2f} {f.n3_n:>9.2f} {f.m1_n_m:>8.4f} {eta:>8}"
        lines.append(line)
    return "\n".join(lines)
