"""Error against run time: convergence studies of every FE quantity (SI units).

Each quantity is computed on a sequence of meshes, every element size times
``scale`` (coarse to fine, ratio sqrt 2 per level).  Per level: DOFs, wall
seconds for mesh / assembly (with the loads) / solve (with the measurement),
the value, and its error: against the exact or handbook value where one exists
(``annulus``, ``edge_crack``), else against a reference from the finest levels
(``reference_value``).  The ring's levels go three steps finer than the default
(scale 1) and the gear meshes' two, so that the reference of the levels the FE
stage uses comes from finer ones, not from themselves (issue 17, item 19); at
the finest ring levels c_ru still rises by ~1.6e-4 per level (the tooth
boundary's element size drives it), so its reference is the finest value.
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
from hubvib.fem.ring_stiffness import ring_stiffness
from hubvib.fem.tooth_stiffness import reducer_mesh_stiffness
from hubvib.foundation.files import MAX_FILE_BYTES, read_text
from hubvib.meshing.levels import scaled_options
from hubvib.meshing.ring_mesh import ring_mesh

#: coarse to fine; the default mesh is scale 1.  Enough where the reference is exact.
SCALES = (4.0, 2.0 * math.sqrt(2), 2.0, math.sqrt(2), 1.0)
#: the gear meshes' c_sp, c_rp: two levels finer than the default
MESH_SCALES = SCALES + (1 / math.sqrt(2), 0.5)
#: the ring's c_ru, c_r (one plane mesh per level): three, so that the reference of the
#: default comes from levels finer than it
RING_SCALES = MESH_SCALES + (1 / (2 * math.sqrt(2)),)
#: an observed Richardson order outside this range is not asymptotic convergence
ORDER_RANGE = (0.5, 8.0)
COLUMNS = ("scale", "dofs", "seconds_mesh", "seconds_assembly", "seconds_solve",
           "seconds_total", "value", "reference", "error", "relative_error")
QUANTITIES = ("c_ru", "c_r", "c_sp", "c_rp", "annulus", "edge_crack")
#: the quantities of a reducer's gears (``Gears``); the others have exact references
GEAR_QUANTITIES = ("c_ru", "c_r", "c_sp", "c_rp")
UNITS = {"c_ru": "N/m", "c_r": "N/m", "c_sp": "N/m", "c_rp": "N/m", "annulus": "N m/rad",
         "edge_crack": "rad/(N m)"}


@dataclass(frozen=True)
class Gears:
    """The built gears whose stiffnesses a study converges: the ring gear
    (``meshing.ring_gear.RingGear``) for c_ru, c_r and the sun and planet bodies
    (``meshing.gear_body.GearBody``) with it for c_sp, c_rp.  The layers above build them
    from a design (``hubvib.build``); validation imports the stages only."""

    ring: object
    sun: object = None
    planet: object = None


def _ring_level(scale: float, which: str, ring) -> dict:
    mesh = ring_mesh(ring, None, scaled_options(scale))
    result = ring_stiffness(ring, mesh)
    return {"dofs": result.dofs, "seconds_mesh": mesh.info["seconds"],
            "seconds_assembly": result.seconds["assembly"] + result.seconds["loads"],
            "seconds_solve": result.seconds["solve"] + result.seconds["measure"],
            "value": getattr(result, which)}


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
    if quantity in ("c_ru", "c_r"):
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
    if quantity in ("c_ru", "c_r"):
        return RING_SCALES
    return MESH_SCALES if quantity in ("c_sp", "c_rp") else SCALES


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
    Richardson limit of the last three values when their observed order lies in
    ``ORDER_RANGE``, else the last (finest) value, whose distance to the others is then a
    lower bound of their error."""
    if len(values) < 3:
        return float(values[-1]), "finest level"
    limit, order = richardson(values, ratio)
    if ORDER_RANGE[0] <= order <= ORDER_RANGE[1]:
        return limit, f"Richardson, observed order {order:.2f}"
    shown = "oscillating" if order != order else f"{order:.2f}"
    return float(values[-1]), f"finest level (observed order {shown}: not asymptotic)"


def with_errors(rows: list[dict]) -> tuple[list[dict], str | None]:
    """Rows with ``reference`` and errors filled; how the reference was obtained (None when
    each row carries its exact reference)."""
    how = None
    if rows and "reference" in rows[0]:
        reference = [r["reference"] for r in rows]
    else:
        limit, how = (reference_value([r["value"] for r in rows], math.sqrt(2)) if rows
                      else (float("nan"), "no levels"))
        reference = [limit] * len(rows)
    out = []
    for row, ref in zip(rows, reference):
        error = abs(row["value"] - ref)
        out.append(dict(row, reference=ref, error=error, relative_error=error / abs(ref)))
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
    rows, how = with_errors(sorted(numbers, key=lambda r: -r["scale"]))
    table = folder / f"convergence_{quantity}.csv"
    with open(table, "w", newline="") as handle:
        writer = csv.DictWriter(handle, COLUMNS)
        writer.writeheader()
        for r in rows:
            writer.writerow({k: r.get(k, "") for k in COLUMNS})
    _plot(rows, quantity, how, folder / f"convergence_{quantity}.png")
    return table


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
    fields = [c for c in COLUMNS if c not in ("error", "relative_error")]
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
