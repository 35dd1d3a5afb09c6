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
    from hubvib.studies.stiffness import stiffness_parts, stiffness_table

    design = design_from_argument(reducer_name(args))
    sweep_cache()  # what a killed run left in the cache, before this one adds to it
    with progress(stiffness_parts(args.crack_depth, args.solid), "FE stiffness", "part") as bar:
        out = stiffness_table(design, args.crack_depth, args.solver, args.solid,
                              on_part=lambda label: bar.update(1, label))
    if args.json:
        print(json_text({"cases": {name: case.to_dict() for name, case in out.items()},
                         "named_values": {name: case.named_values()
                                          for name, case in out.items()},
                         "lumped_from_design_table": design.lumped_fields}))
        return 0
    for name, case in out.items():
        print(f"== {name} ==")
        lines = _lines(case)
        width = max(len(line[1]) for line in lines)
        print(f"{'':8} {'method':<{width}} {'value [N/m]':>12} {'+-':>9} {'min':>11} {'max':>11} "
              f"{'time [s]':>9}  independent checks")
        for key, method, value, error, span, seconds, checks in lines:
            error_text = f"{error:9.1e}" if error is not None else f"{'formula':>9}"
            span_text = (f"{span[0]:11.4e} {span[1]:11.4e}" if span is not None
                         else f"{'':11} {'':11}")
            print(f"{key:8} {method:<{width}} {value:12.5e} {error_text} {span_text} "
                  f"{seconds:9.1f}  {checks}")
        c_rp = case.mesh.get("c_rp")
        if case.cracked and c_rp is not None and c_rp.engaged is not None:
            print(f"c_rp over the cracked tooth's contact +- one base pitch: mean "
                  f"{c_rp.engaged:.5e} (intact {c_rp.engaged_intact:.5e}, "
                  f"{100 * (c_rp.engaged / c_rp.engaged_intact - 1):+.2f} %), min "
                  f"{c_rp.engaged_min:.5e} "
                  f"({100 * (c_rp.engaged_min / c_rp.engaged_intact_min - 1):+.2f} %)")
    if len(out) == 2:
        intact, cracked = (case.ring for case in out.values())
        print(f"crack changes: c_ru {100 * (cracked.c_ru / intact.c_ru - 1):+.2f} %, "
              f"c_r {100 * (cracked.c_r / intact.c_r - 1):+.2f} %")
        print("the highest c_ru over carrier positions can rise with the crack: where a planet "
              "loads the cracked tooth, its root land is cut by the crack mouth (the tooth's "
              "own softening is in c_rp's engaged value); the mean falls")
    m = design.material
    print(f"design {design.name!r}: plane stress, E {m.E / 1e9:g} GPa, nu {m.nu:g}, face width "
          f"{1e3 * design.face_width:g} mm; ring supports clamped; +- = three-level error of "
          "the default mesh (fine, twice and four times coarser: Richardson with the observed "
          "order where it lies in 0.5..4, else the larger level difference); c_p/c_c: Palmgren "
          "line contact, tangent stiffness at the operating load (sun "
          f"torque {design.sun_torque:g} N m)")
    replaced = [k for k in _keys(next(iter(out.values()))) if k in design.lumped_fields]
    if replaced:
        print(f"the lumped model of design {design.name!r} takes "
              + ", ".join(f"{k} = {design.lumped_fields[k]:.6g}" for k in replaced)
              + " N/m from design.lumped instead (hubvib design check lists every field)")
    for note in design.notes:
        print(f"note: {note}")
    if args.solid:
        print("3D: P2 tetrahedra, +- = three-level error over the solid levels (the "
              "benchmark's reference level agrees to ~0.3 %, README)")
    return 0


def _keys(case) -> list[str]:
    """The case's quantities in table order."""
    return [line[0] for line in _lines(case)]


def _lines(case) -> list[tuple]:
    """One table line per quantity of a ``StiffnessCase``: (key, method, value [N/m],
    error [N/m] or None (a formula), (min, max) [N/m] or None, seconds, checks)."""
    from hubvib.reducer.stages import FE_MESH, ISO_MESH, ISO_SINGLE
    from hubvib.studies.stiffness import RING_METHODS

    lines = []
    for suffix, ring in case.rings().items():
        where = "solid, planet 1 on tooth 0" if suffix else "plane stress"
        common = f"{ring.dofs} DOFs, {ring.solver}, {where}"
        method = RING_METHODS[suffix]
        lines.append((f"c_ru{suffix}", method, ring.c_ru, ring.c_ru_error,
                      (ring.c_ru_min, ring.c_ru_max), ring.seconds_total,
                      f"{common}; rim part (lumped model's), root land "
                      f"{ring.c_ru_root_land:.4e}"))
        lines.append((f"c_r{suffix}", method, ring.c_r, ring.c_r_error, None,
                      ring.seconds_total,
                      f"{common}; rim part (lumped model's), root land {ring.c_r_root_land:.4e}"))
    for key, e in case.mesh.items():
        lines.append((key, FE_MESH, e.value, e.error, (e.min, e.max), e.seconds_total,
                      f"eps {e.contact_ratio:.3f}; analytical {e.analytic:.4e} "
                      f"({100 * (e.value / e.analytic - 1):+.1f} %); {ISO_MESH} "
                      f"{e.iso_c_gamma:.4e} ({100 * (e.value / e.iso_c_gamma - 1):+.1f} %"
                      f"{'' if e.iso_in_range else ', shifts outside ISO range'}); "
                      f"{ISO_SINGLE} {e.iso_c_single:.4e}"))
    for key, b in case.bearings.items():
        lines.append((key, b.method, b.tangent, None, None, b.seconds_total,
                      f"{b.secant_method} {b.secant:.4e}; {b.rollers} rollers x "
                      f"{1e3 * b.roller_length:.0f} mm"))
    return lines
