"""``hubvib stiffness``: every stiffness of the lumped model with its error estimate and run time."""
from __future__ import annotations

from hubvib.fem.solvers import SOLVERS
from hubvib.foundation.output import json_text

from ._reducer import add_reducer_options, reducer_name
from .design import design_from_argument


def add_parser(sub) -> None:
    p = sub.add_parser("stiffness", help="every stiffness of the lumped model: FE c_ru, c_r, "
                       "c_sp, c_rp; bearing c_p, c_c")
    add_reducer_options(p)
    p.add_argument("--crack-depth", type=float, default=0.0, metavar="D",
                   help="root crack length at tooth 0 [m] (metres: 0.005 = 5 mm); 0 = intact only")
    p.add_argument("--solid", action="store_true",
                   help="also c_ru and c_r of the solid (3D) ring, ~1 min per case")
    p.add_argument("--solver", default="auto", choices=SOLVERS,
                   help="sparse solver of c_ru, c_r; auto: PARDISO if installed (2D and 3D), else "
                   "SuperLU in 2D and below 6e4 DOFs, else AMG-CG")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.runtime.cache_check import sweep_cache
    from hubvib.runtime.progress import progress
    from hubvib.studies.stiffness import named_values, stiffness_parts, stiffness_table

    design = design_from_argument(reducer_name(args))
    sweep_cache()  # what a killed run left in the cache, before this one adds to it
    with progress(stiffness_parts(args.crack_depth, args.solid), "FE stiffness", "part") as bar:
        out = stiffness_table(design, args.crack_depth, args.solver, args.solid,
                              on_part=lambda label: bar.update(1, label))
    if args.json:
        print(json_text({"cases": out,
                         "named_values": {name: named_values(rows) for name, rows in out.items()},
                         "lumped_from_design_table": design.lumped_fields}))
        return 0
    for name, rows in out.items():
        print(f"== {name} ==")
        width = max(len(_method(key, r)) for key, r in rows.items())
        print(f"{'':8} {'method':<{width}} {'value [N/m]':>12} {'+-':>9} {'min':>11} {'max':>11} "
              f"{'time [s]':>9}  independent checks")
        for key, r in rows.items():
            error = f"{r['error_N_m']:9.1e}" if "error_N_m" in r else f"{'formula':>9}"
            span = (f"{r['min_N_m']:11.4e} {r['max_N_m']:11.4e}" if "min_N_m" in r
                    else f"{'':11} {'':11}")
            print(f"{key:8} {_method(key, r):<{width}} {r['value_N_m']:12.5e} {error} {span} "
                  f"{r['seconds_total']:9.1f}  " + _checks(key, r))
        if "c_rp" in rows and "engaged_N_m" in rows["c_rp"]:
            r = rows["c_rp"]
            print(f"c_rp over the cracked tooth's contact +- one base pitch: mean {r['engaged_N_m']:.5e} "
                  f"(intact {r['engaged_intact_N_m']:.5e}, "
                  f"{100 * (r['engaged_N_m'] / r['engaged_intact_N_m'] - 1):+.2f} %), min "
                  f"{r['engaged_min_N_m']:.5e} ({100 * (r['engaged_min_N_m'] / r['engaged_intact_min_N_m'] - 1):+.2f} %)")
    if len(out) == 2:
        intact, cracked = out.values()
        print("crack changes: " + ", ".join(
            f"{k} {100 * (cracked[k]['value_N_m'] / intact[k]['value_N_m'] - 1):+.2f} %"
            for k in ("c_ru", "c_r")))
        print("the highest c_ru over carrier positions can rise with the crack: where a planet "
              "loads the cracked tooth, its root land is cut by the crack mouth (the tooth's "
              "own softening is in c_rp's engaged value); the mean falls")
    m = design.material
    print(f"design {design.name!r}: plane stress, E {m.E / 1e9:g} GPa, nu {m.nu:g}, face width "
          f"{1e3 * design.face_width:g} mm; ring supports clamped; +- = fine minus twice-coarser "
          "mesh; c_p/c_c: Palmgren line contact, tangent stiffness at the operating load (sun "
          f"torque {design.sun_torque:g} N m)")
    replaced = [k for k in next(iter(out.values())) if k in design.lumped_fields]
    if replaced:
        print(f"the lumped model of design {design.name!r} takes "
              + ", ".join(f"{k} = {design.lumped_fields[k]:.6g}" for k in replaced)
              + " N/m from design.lumped instead (hubvib design check lists every field)")
    for note in design.notes:
        print(f"note: {note}")
    if args.solid:
        print("3D: P2 tetrahedra, +- = difference to the next coarser solid level (the "
              "benchmark's reference level agrees to ~0.3 %, README)")
    return 0


def _method(key: str, r: dict) -> str:
    """How the row's value is obtained, as ``hubvib design check`` names it."""
    from hubvib.reducer.stages import FE_MESH
    from hubvib.studies.stiffness import RING_METHODS

    if key in ("c_sp", "c_rp"):
        return FE_MESH
    if key in ("c_p", "c_c"):
        return r["method"]
    name, _, solid = key.partition(" ")
    return RING_METHODS[f" {solid}" if solid else ""]


def _checks(key: str, r: dict) -> str:
    from hubvib.reducer.stages import ISO_MESH, ISO_SINGLE

    if key in ("c_sp", "c_rp"):
        return (f"eps {r['contact_ratio']:.3f}; analytical {r['analytic_N_m']:.4e} "
                f"({100 * (r['value_N_m'] / r['analytic_N_m'] - 1):+.1f} %); {ISO_MESH} "
                f"{r['iso_c_gamma_N_m']:.4e} "
                f"({100 * (r['value_N_m'] / r['iso_c_gamma_N_m'] - 1):+.1f} %"
                f"{'' if r['iso_in_range'] else ', shifts outside ISO range'}); "
                f"{ISO_SINGLE} {r['iso_c_single_N_m']:.4e}")
    if key in ("c_p", "c_c"):
        return (f"{r['secant_method']} {r['secant_N_m']:.4e}; "
                f"{r['rollers']} rollers x {1e3 * r['roller_length_m']:.0f} mm")
    where = "solid, planet 1 on tooth 0" if key.endswith("3D") else "plane stress"
    land = (f"; rim part (lumped model's), root land {r['root_land_N_m']:.4e}"
            if "root_land_N_m" in r else "")
    return f"{r['dofs']} DOFs, {r['solver']}, {where}{land}"
