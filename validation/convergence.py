"""Error against run time: convergence studies of every FE quantity (SI units).

Each quantity is computed on a sequence of meshes, every element size times
``scale`` (coarse to fine, ratio sqrt 2 per level).  Per level: DOFs, wall
seconds for mesh / assembly (with the loads) / solve (with the measurement),
the value, and its error: against the exact or handbook value where one exists
(``annulus``, ``edge_crack``), else against a reference from the finest levels
(``reference_value``).  The ring's levels go three steps finer than the default
(scale 1) and the gear meshes' two, so that the reference of the levels the FE
stage uses comes from finer ones, not from themselves; at
the finest ring levels c_ru still rises by ~1.6e-4 per level (the tooth
boundary's element size drives it), so its reference is the finest value.

The work-conjugate ring stiffnesses (``c_ru_work``, ``c_r_work``, ``fem.ring_work``) and
the rim part ``c_ru_rim`` run on nested levels instead: one coarse mesh
(``NESTED_BASE``) split into four 0..3 times, so the element size halves everywhere
(ratio 2) as the theory of uniform refinement assumes; unstructured levels remeshed at
each size scatter the observed order by +-0.5 (measured).  Each row carries the observed
order of the triple of levels ending at it, and a Richardson limit is the reference only
where the last two orders (four levels) agree within ``STABLE_BAND`` and lie in
``ORDER_RANGE``; otherwise the finest value, and the errors are lower bounds.
The same work-conjugate quantities from one tooth pitch (``c_ru_sector``, ``c_r_sector``,
``fem.ring_sector``): the pitch meshed alone (``meshing.ring_sector``, ``SECTOR_BASE``,
finer at the load patch and the toothed boundary than ``NESTED_BASE`` since each size
costs 1/z as much), split 0..3 times, condensed exactly onto its cuts and held arc and
copied z times; the cheap route to a verified c_ru (``benchmarks.ring_2d``).
Rows are appended to ``convergence_<quantity>.levels.csv`` as each level
finishes; a rerun skips the levels already written (resume).
"""
from __future__ import annotations

import csv
import io
import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hubvib.fem.annulus import exact_k_theta, fe_k_theta
from hubvib.fem.edge_crack import fe_rotation_compliance, handbook_added_compliance
from hubvib.fem.material import Material
from hubvib.fem.ring_sector import sector_ring_work
from hubvib.fem.ring_stiffness import ring_stiffness
from hubvib.fem.tooth_stiffness import reducer_mesh_stiffness
from hubvib.foundation.files import MAX_FILE_BYTES, read_text
from hubvib.foundation.output import write_csv
from hubvib.meshing.levels import scaled_options
from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh
from hubvib.meshing.ring_sector import sector_mesh

#: coarse to fine; the default mesh is scale 1.  Enough where the reference is exact.
SCALES = (4.0, 2.0 * math.sqrt(2), 2.0, math.sqrt(2), 1.0)
#: the gear meshes' c_sp, c_rp: two levels finer than the default
MESH_SCALES = SCALES + (1 / math.sqrt(2), 0.5)
#: the ring's c_ru, c_r (one plane mesh per level): three, so that the reference of the
#: default comes from levels finer than it
RING_SCALES = MESH_SCALES + (1 / (2 * math.sqrt(2)),)
#: an observed Richardson order outside this range is not asymptotic convergence
ORDER_RANGE = (0.5, 8.0)
#: the last two observed orders must agree within this for Richardson extrapolation
STABLE_BAND = 0.3
#: coarse curved-P2 ring mesh of the nested levels [m] (2.0e4 DOFs; split 3 times: 1.1e6)
NESTED_BASE = MeshOptions(size=16e-3, tooth_size=4e-3, tip_size=1e-3, load_size=0.4e-3,
                          grading=1.0)
#: element size relative to ``NESTED_BASE`` of each nested level (0..3 splits)
NESTED_SCALES = (1.0, 0.5, 0.25, 0.125)
#: coarse curved-P2 mesh of one tooth pitch for the sector levels (``meshing.ring_sector``)
#: [m]: the load patch 4x, the toothed boundary 2x and the support ends 10x finer than
#: ``NESTED_BASE`` (each size costs 1/z as much on one pitch); the support ends so fine
#: that their clamped-free singularity's order-1 term (about 1.4e-3 relative per mm of
#: the element size there, measured) stays below 2e-5 on every level
SECTOR_BASE = MeshOptions(size=16e-3, tooth_size=2e-3, tip_size=0.1e-3, load_size=0.1e-3,
                          grading=1.0)
#: quantities on the nested levels (``RingStiffness.work``) and their attribute
WORK_QUANTITIES = {"c_ru_work": "c_ru", "c_r_work": "c_r", "c_ru_rim": "c_ru_rim"}
#: the same work-conjugate quantities on the nested pitch levels (``fem.ring_sector``)
SECTOR_QUANTITIES = {"c_ru_sector": "c_ru", "c_r_sector": "c_r"}
#: every quantity on nested levels (ratio 2)
NESTED_QUANTITIES = (*WORK_QUANTITIES, *SECTOR_QUANTITIES)
#: what theory gives for the observed order (in the element size h) of each quantity
EXPECTED_ORDER = {
    "c_ru_work": "energy functional f^T u, curved P2: 2p = 4 where the solution is smooth; "
                 "the traction jumps at the load-patch ends (u ~ r log r) give 2 (with a "
                 "log) and the clamped-free support ends (u ~ r^0.5, 2 lambda) 1, the "
                 "asymptotic rate; so the observed order lies in [1, 4] and falls towards "
                 "1 once the support-end term (graded mesh there) dominates",
    "c_r_work": "as c_ru_work, in [1, 4]; the x/y loads push on the supports, so the "
                "support ends' order 1 shows earlier",
    "c_ru_rim": "a reading on the root lands, not an energy functional: no one-signed "
                "error, no expected order",
    "c_ru_sector": "as c_ru_work (the same functional on a pitch mesh copied z times), in "
                   "[1, 4]; with the support ends 10x finer the order-1 term stays below "
                   "2e-5 and the orders lie near 3 (load-patch ends 2 with a log, the "
                   "smooth part 4)",
    "c_r_sector": "as c_r_work, in [1, 4]",
}
COLUMNS = ("scale", "dofs", "seconds_mesh", "seconds_assembly", "seconds_solve",
           "seconds_total", "value", "reference", "error", "relative_error", "observed_order")
QUANTITIES = ("c_ru", "c_r", "c_sp", "c_rp", "annulus", "edge_crack", *NESTED_QUANTITIES)
#: the quantities of a reducer's gears (``Gears``); the others have exact references
GEAR_QUANTITIES = ("c_ru", "c_r", "c_sp", "c_rp", *NESTED_QUANTITIES)
UNITS = {"c_ru": "N/m", "c_r": "N/m", "c_sp": "N/m", "c_rp": "N/m", "annulus": "N m/rad",
         "edge_crack": "rad/(N m)", **{q: "N/m" for q in NESTED_QUANTITIES}}


@dataclass(frozen=True)
class Gears:
    """The built gears whose stiffnesses a study converges: the ring gear
    (``meshing.ring_gear.RingGear``) for c_ru, c_r and the sun and planet bodies
    (``meshing.gear_body.GearBody``) with it for c_sp, c_rp.  The layers above build them
    from a design (``hubvib.reducer``); validation imports the stages only."""

    ring: object
    sun: object = None
    planet: object = None


def _sector_level(scale: float, which: str, ring) -> dict:
    """A pitch level: its DOFs are the whole ring's with this pitch mesh; "assembly" is the
    pitch's assembly and condensation, "solve" the held arcs and the ring of cuts."""
    mesh = sector_mesh(ring, SECTOR_BASE, nested_refinements(scale))
    result = sector_ring_work(ring, mesh)
    return {"dofs": result.dofs, "seconds_mesh": mesh.info["seconds"],
            "seconds_assembly": result.seconds["condense"],
            "seconds_solve": result.seconds["solve"],
            "value": getattr(result, SECTOR_QUANTITIES[which])}


def _ring_level(scale: float, which: str, ring) -> dict:
    if which in SECTOR_QUANTITIES:
        return _sector_level(scale, which, ring)
    if which in WORK_QUANTITIES:
        mesh = ring_mesh(ring, None, NESTED_BASE, nested_refinements(scale))
    else:
        mesh = ring_mesh(ring, None, scaled_options(scale))
    result = ring_stiffness(ring, mesh)
    value = (getattr(result.work, WORK_QUANTITIES[which]) if which in WORK_QUANTITIES
             else getattr(result, which))
    return {"dofs": result.dofs, "seconds_mesh": mesh.info["seconds"],
            "seconds_assembly": result.seconds["assembly"] + result.seconds["loads"],
            "seconds_solve": result.seconds["solve"] + result.seconds["measure"],
            "value": value}


def nested_refinements(scale: float) -> int:
    """Splits of ``NESTED_BASE`` for the relative element size ``scale`` (1, 1/2, 1/4...)."""
    n = round(-math.log2(scale))
    if not 0 <= n <= 4 or not math.isclose(scale, 2.0 ** -n, rel_tol=1e-9):
        raise ValueError(f"nested level scale {scale!r}, allowed 2^-n with n in 0..4")
    return n


def _mesh_level(scale: float, which: str, gears: Gears) -> dict:
    if gears.sun is None or gears.planet is None:
        raise ValueError(f"{which} needs the sun and planet bodies (Gears.sun, Gears.planet)")
    result = reducer_mesh_stiffness(gears.sun, gears.planet, gears.ring,
                                    scaled_options(scale))[which]
    return {"dofs": result.dofs, "value": result.value,
            **{f"seconds_{k}": v for k, v in result.seconds.items()}}


ANNULUS = (0.08, 0.10, 0.01)  # inner, outer radius, thickness [m]
STRIP = (0.01, 0.001, 0.4)  # width, thickness [m], a/W


def _annulus_level(scale: float) -> dict:
    a, b, t = ANNULUS
    started = time.perf_counter()
    value, dofs = fe_k_theta(a, b, t, Material(), 4e-3 * scale, 2)
    return {"dofs": dofs, "seconds_solve": time.perf_counter() - started, "value": value,
            "reference": exact_k_theta(a, b, t, Material())}


def _strip_level(scale: float) -> dict:
    W, t, ratio = STRIP
    started = time.perf_counter()
    sizes = {"size": W / 10 * scale, "tip_size": W / 400 * scale}
    cracked, dofs = fe_rotation_compliance(ratio * W, W, t, **sizes)
    intact, _ = fe_rotation_compliance(0.0, W, t, **sizes)
    return {"dofs": dofs, "seconds_solve": time.perf_counter() - started,
            "value": cracked - intact, "reference": handbook_added_compliance(ratio * W, W, t)}


def compute_level(quantity: str, scale: float, gears: Gears | None = None) -> dict:
    """One level's row (without the error columns); the reducer's quantities (c_ru, c_r,
    c_sp, c_rp) are those of ``gears``."""
    if quantity in GEAR_QUANTITIES and gears is None:
        raise ValueError(f"quantity {quantity!r} needs the built gears (Gears)")
    if quantity in ("c_ru", "c_r", *NESTED_QUANTITIES):
        row = _ring_level(scale, quantity, gears.ring)
    elif quantity in ("c_sp", "c_rp"):
        row = _mesh_level(scale, quantity, gears)
    elif quantity == "annulus":
        row = _annulus_level(scale)
    elif quantity == "edge_crack":
        row = _strip_level(scale)
    else:
        raise ValueError(f"quantity {quantity!r}, allowed: {', '.join(QUANTITIES)}")
    row = {"scale": scale, "seconds_mesh": 0.0, "seconds_assembly": 0.0, **row}
    row["seconds_total"] = row["seconds_mesh"] + row["seconds_assembly"] + row["seconds_solve"]
    return row


def scales_of(quantity: str) -> tuple[float, ...]:
    """The levels of ``quantity``'s study, coarse to fine."""
    if quantity in NESTED_QUANTITIES:
        return NESTED_SCALES
    if quantity in ("c_ru", "c_r"):
        return RING_SCALES
    return MESH_SCALES if quantity in ("c_sp", "c_rp") else SCALES


def ratio_of(quantity: str) -> float:
    """Element-size ratio between successive levels of ``quantity``'s study."""
    return 2.0 if quantity in NESTED_QUANTITIES else math.sqrt(2)


def observed_orders(values, ratio: float) -> list[float]:
    """Observed order of each triple of successive values (nan where not monotone)."""
    return [richardson(values[i - 2:i + 1], ratio)[1] for i in range(2, len(values))]


def richardson(values, ratio: float) -> tuple[float, float]:
    """Extrapolated limit and observed order from the last three values of a sequence whose
    mesh size shrinks by ``ratio`` per step."""
    v1, v2, v3 = values[-3:]
    d1, d2 = v2 - v1, v3 - v2
    if d1 == 0 or d2 == 0 or d1 * d2 < 0:
        return float(v3), float("nan")  # not in the asymptotic range
    order = math.log(abs(d1 / d2)) / math.log(ratio)
    return float(v3 + d2 / (ratio ** order - 1)), order


def reference_value(values, ratio: float) -> tuple[float, str]:
    """Reference for a sequence without an exact value, and how it was obtained: the
    Richardson limit of the last three values when the observed orders of the last two
    triples (four levels) both lie in ``ORDER_RANGE`` and agree within ``STABLE_BAND``,
    else the last (finest) value, whose distance to the others is then a lower bound of
    their error."""
    if len(values) < 3:
        return float(values[-1]), "finest level"
    limit, order = richardson(values, ratio)
    orders = observed_orders(values, ratio)[-2:]
    shown = ", ".join("oscillating" if o != o else f"{o:.2f}" for o in orders)
    if len(orders) < 2:
        return float(values[-1]), (f"finest level (one triple, observed order {shown}: "
                                   "stability not shown)")
    if all(ORDER_RANGE[0] <= o <= ORDER_RANGE[1] for o in orders) and (
            abs(orders[0] - orders[1]) <= STABLE_BAND):
        return limit, f"Richardson, observed order {order:.2f} (stable: {shown})"
    return float(values[-1]), f"finest level (observed orders {shown}: not asymptotic)"


def with_errors(rows: list[dict], ratio: float = math.sqrt(2)
                ) -> tuple[list[dict], str | None]:
    """Rows with ``reference``, errors and the observed order of the triple ending at each
    row filled; how the reference was obtained (None when each row carries its exact
    reference).  ``ratio``: element-size ratio between successive rows."""
    how = None
    if rows and "reference" in rows[0]:
        reference = [r["reference"] for r in rows]
    else:
        limit, how = (reference_value([r["value"] for r in rows], ratio) if rows
                      else (float("nan"), "no levels"))
        reference = [limit] * len(rows)
    orders = [float("nan")] * min(2, len(rows)) + observed_orders(
        [r["value"] for r in rows], ratio)
    out = []
    for row, ref, order in zip(rows, reference, orders):
        error = abs(row["value"] - ref)
        out.append(dict(row, reference=ref, error=error, relative_error=error / abs(ref),
                        observed_order=order))
    return out, how


def run_study(quantity: str, folder: Path, gears: Gears | None = None, scales=None,
              progress=print) -> Path:
    """Compute (or resume) the study over ``scales`` (default ``scales_of(quantity)``);
    CSV with errors and a log-log plot in ``folder``.  ``gears``: the built gears of the
    reducer's quantities (c_ru, c_r, c_sp, c_rp)."""
    if quantity not in QUANTITIES:
        raise ValueError(f"quantity {quantity!r}, allowed: {', '.join(QUANTITIES)}")
    scales = scales_of(quantity) if scales is None else scales
    folder.mkdir(parents=True, exist_ok=True)
    raw = folder / f"convergence_{quantity}.levels.csv"
    done = _read(raw)
    for scale in scales:
        if any(math.isclose(float(r["scale"]), scale, rel_tol=1e-9) for r in done):
            continue
        row = compute_level(quantity, scale, gears)
        _append(raw, row)
        done.append(row)
        progress(f"{quantity}: scale {scale:.3f}, {row['dofs']} DOFs, "
                 f"{row['seconds_total']:.2f} s, value {row['value']:.8e}")
    numbers = [{k: float(v) for k, v in r.items() if v not in ("", None)} for r in done]
    rows, how = with_errors(sorted(numbers, key=lambda r: -r["scale"]), ratio_of(quantity))
    table = write_csv(folder / f"convergence_{quantity}.csv",
                      [{k: r.get(k, "") for k in COLUMNS} for r in rows], COLUMNS)
    _plot(rows, quantity, how, folder / f"convergence_{quantity}.png")
    return table


def study_note(quantity: str, table: Path) -> str:
    """How the reference of the study in ``table`` was obtained, the observed orders and
    what theory expects (the lines ``hubvib convergence`` prints under the table)."""
    with open(table, newline="", encoding="utf-8") as handle:
        rows = [{k: float(v) for k, v in r.items() if v not in ("", None)}
                for r in csv.DictReader(handle)]
    if not rows:
        return f"{quantity}: no levels"
    exact = quantity in ("annulus", "edge_crack")
    how = "exact or handbook value" if exact else reference_value(
        [r["value"] for r in rows], ratio_of(quantity))[1]
    orders = ", ".join(f"{r['observed_order']:.2f}" if math.isfinite(
        r.get("observed_order", math.nan)) else "not monotone" for r in rows[2:])
    lines = [f"reference: {how}", f"observed orders (successive triples): {orders or '-'}"]
    if quantity in EXPECTED_ORDER:
        lines.append(f"expected: {EXPECTED_ORDER[quantity]}")
    return "\n".join(lines)


def _read(path: Path) -> list[dict]:
    """The finished levels of a resumed study (rows without a value are recomputed);
    a damaged file is refused naming it, the line and what to do (it said only
    ``'utf-8' codec can't decode byte 0xe9``)."""
    if not path.exists():
        return []
    what = "convergence levels file"
    text = read_text(path, what, ValueError, kind="CSV", max_bytes=MAX_FILE_BYTES)
    rows = []
    for line, row in enumerate(csv.DictReader(io.StringIO(text, newline="")), start=2):
        if not row.get("value"):
            continue
        try:
            cells = {k: float(v) for k, v in row.items() if v not in ("", None)}
        except (TypeError, ValueError, AttributeError):
            cells = None
        if cells is None or None in row or "scale" not in cells or not all(
                math.isfinite(v) for v in cells.values()):
            raise ValueError(f"{what} {str(path)!r} line {line}: {dict(row)} is not a level of "
                             f"finite numbers; delete the file to compute every level again")
        rows.append(row)
    return rows


def _append(path: Path, row: dict) -> None:
    fields = [c for c in COLUMNS if c not in ("error", "relative_error", "observed_order")]
    new = not path.exists()
    with open(path, "a", newline="") as handle:
        writer = csv.DictWriter(handle, fields)
        if new:
            writer.writeheader()
        writer.writerow({k: row.get(k, "") for k in fields})
        handle.flush()


def _plot(rows: list[dict], quantity: str, how: str | None, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    seconds = np.array([r["seconds_total"] for r in rows])
    errors = np.array([r["relative_error"] for r in rows])
    keep = errors > 0
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.loglog(seconds[keep], errors[keep], "o-")
    for r, e in zip(rows, errors):
        if e > 0:
            ax.annotate(f"{int(r['dofs'])}", (r["seconds_total"], e), fontsize=7)
    ax.set_xlabel("wall time, mesh + assembly + solve [s]")
    ax.set_ylabel("relative error")
    how = how or "exact reference"
    ax.set_title(f"{quantity} [{UNITS[quantity]}]: error vs time\nreference: {how}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
