"""Every stiffness of a design's lumped model with its error estimate and run time: the FE
ring (c_ru, c_r: the work-conjugate rim parts the lumped model uses, the root-land
readings beside them; plane, and solid on request), the FE mesh stiffness (c_sp, c_rp, mean over
the mesh cycle) and the bearings (c_p, c_c, Palmgren line contact).  ``hubvib stiffness``
prints it.  SI units: N/m, m, s."""
from __future__ import annotations

import math
import time

from hubvib.reducer import bearing_stiffness, gear_body, material, ring_gear
from hubvib.reducer.stages import FE_MESH, FE_RING, ISO_MESH, ISO_SINGLE, labelled
from hubvib.fem.estimate import RingEstimate, estimate_mesh, estimate_ring
from hubvib.meshing.crack import Crack


def bearing_rows(design) -> dict:
    """c_p and c_c of the design's bearings (those it gives), with the time they took [s]."""
    started = time.perf_counter()
    rows = bearing_stiffness(design)
    for row in rows.values():
        row.update(value_N_m=row["tangent_N_m"], seconds_total=time.perf_counter() - started,
                   sun_torque_N_m=design.sun_torque)
    return rows


def stiffness_parts(crack_depth: float = 0.0, solid: bool = False) -> int:
    """How many FE parts ``stiffness_table`` computes (the mesh stiffness, then the ring per
    case, plane and solid): its ``on_part`` calls."""
    return 1 + (2 if crack_depth > 0 else 1) * (2 if solid else 1)


def stiffness_table(design, crack_depth: float = 0.0, solver: str = "auto",
                    solid: bool = False, on_part=None) -> dict[str, dict]:
    """Case name ("intact", and "crack D m" when ``crack_depth`` [m] > 0, a root crack at
    tooth 0) -> quantity (c_ru, c_r, [c_ru 3D, c_r 3D,] c_sp, c_rp, c_p, c_c) -> its row
    (``value_N_m``, ``error_N_m``, ``seconds_total``, ...: the JSON of ``hubvib stiffness``).

    ``on_part(label)`` is called after each FE part (``stiffness_parts`` of them: progress).

    Raises ``ValueError`` naming the design or ``--crack-depth`` for a design whose planets
    are not equally spaced (the FE ring model loads equally spaced planets only) or a depth
    that is not a finite number >= 0.
    """
    if not design.equally_spaced:
        raise ValueError(f"design {design.name!r}: the FE ring model loads equally spaced planets "
                         "only")
    if not (math.isfinite(crack_depth) and crack_depth >= 0):
        raise ValueError(f"--crack-depth = {crack_depth!r}; allowed: a finite depth >= 0 [m] "
                         "(0 = intact only)")
    ring, steel = ring_gear(design), material(design)
    cases = {"intact": None}
    if crack_depth > 0:
        crack = Crack(0, crack_depth)
        crack.path(ring)  # validate before any meshing
        cases[f"crack {crack_depth:g} m"] = crack
    # c_sp, c_rp are intact means in both cases; the cracked run adds the cracked tooth's
    # engagement to c_rp, so one run serves both
    done = on_part or (lambda label: None)
    estimates = estimate_mesh(gear_body(design, "sun"), gear_body(design, "planet"), ring,
                              list(cases.values())[-1], material=steel)
    done("c_sp, c_rp")
    mesh_rows = {key: e.to_dict() for key, e in estimates.items()}
    intact_mesh_rows = {key: e.to_dict(engaged=False) for key, e in estimates.items()}
    bearings = bearing_rows(design)
    out = {}
    for name, crack in cases.items():
        ring_options = dict(solver=solver, material=steel, n_planets=design.n_planets,
                            definition="rim")
        rows = _ring_rows(estimate_ring(ring, crack, **ring_options), "")
        done(f"c_ru, c_r {name}")
        if solid:
            rows.update(_ring_rows(estimate_ring(ring, crack, solid=True, **ring_options),
                                   " 3D"))
            done(f"c_ru, c_r {name}, solid")
        rows.update(intact_mesh_rows if crack is None else mesh_rows)
        rows.update(bearings)
        out[name] = rows
    return out


#: the methods of the ring rows' values, by row suffix ("" plane, " 3D" solid)
RING_METHODS = {"": FE_RING, " 3D": f"{FE_RING}, solid"}


def named_values(rows: dict) -> dict[str, float]:
    """Every value of one case of ``stiffness_table`` by ``key (method)`` [N/m]: the names
    ``hubvib design check`` gives its values (``hubvib.reducer.stages.labelled``), so one
    name holds one value wherever it is printed."""
    out = {}
    for key, row in rows.items():
        name, _, solid = key.partition(" ")
        if name in ("c_ru", "c_r"):
            out[labelled(name, RING_METHODS[f" {solid}" if solid else ""])] = row["value_N_m"]
        elif key in ("c_sp", "c_rp"):
            out[labelled(key, FE_MESH)] = row["value_N_m"]
            out[labelled(key, ISO_MESH)] = row["iso_c_gamma_N_m"]
            out[labelled(key, ISO_SINGLE)] = row["iso_c_single_N_m"]
        elif key in ("c_p", "c_c"):
            out[labelled(key, row["method"])] = row["tangent_N_m"]
            out[labelled(key, row["secant_method"])] = row["secant_N_m"]
    return out


def _ring_rows(r: RingEstimate, suffix: str) -> dict:
    """The JSON rows of one ring estimate (keys with units: the output boundary); the
    root-land readings beside the values (``root_land_N_m``, ``root_land_error_N_m``)."""
    common = {"seconds_total": r.seconds_total, "dofs": r.dofs, "solver": r.solver}
    return {f"c_ru{suffix}": {"value_N_m": r.c_ru, "error_N_m": r.c_ru_error,
                              "min_N_m": r.c_ru_min, "max_N_m": r.c_ru_max,
                              "root_land_N_m": r.c_ru_root_land,
                              "root_land_error_N_m": r.c_ru_root_land_error, **common},
            f"c_r{suffix}": {"value_N_m": r.c_r, "error_N_m": r.c_r_error,
                             "root_land_N_m": r.c_r_root_land,
                             "root_land_error_N_m": r.c_r_root_land_error, **common}}
