"""``hubvib stiffness``: FE stiffnesses of the ring gear with error estimate and run time."""
from __future__ import annotations

import json
import time

NOT_YET = ("c_sp", "c_rp", "c_p", "c_c")


def add_parser(sub) -> None:
    p = sub.add_parser("stiffness", help="FE ring stiffness c_ru, c_r (intact and cracked)")
    p.add_argument("--preset", default="raba118", choices=["raba118"])
    p.add_argument("--crack-depth", type=float, default=0.0, metavar="D",
                   help="root crack length at tooth 0 [m]; 0 = intact only")
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def scaled_options(scale: float):
    """The default plane mesh with every element size times ``scale``."""
    from meshing.ring_mesh import MeshOptions

    default = MeshOptions()
    return MeshOptions(size=scale * default.size, tooth_size=scale * default.tooth_size,
                       tip_size=scale * default.tip_size, load_size=scale * default.load_size)


def estimate(ring, crack, scale: float = 1.0) -> dict:
    """c_ru and c_r on the default mesh (sizes times ``scale``) and on one twice as coarse.

    The estimated error is the difference between the two (an upper bound when
    the convergence is monotone with rate >= 1; see the annulus study).
    """
    from fem.ring_stiffness import ring_stiffness
    from meshing.ring_mesh import ring_mesh

    fine_options, coarse_options = scaled_options(scale), scaled_options(2 * scale)
    results = {}
    for name, options in (("coarse", coarse_options), ("fine", fine_options)):
        started = time.perf_counter()
        mesh = ring_mesh(ring, crack, options)
        meshed = time.perf_counter()
        result = ring_stiffness(ring, mesh)
        results[name] = (result, meshed - started, time.perf_counter() - meshed)
    fine, coarse = results["fine"][0], results["coarse"][0]
    return {
        "c_ru_N_m": fine.c_ru, "c_ru_error_N_m": abs(fine.c_ru - coarse.c_ru),
        "c_ru_min_N_m": float(fine.c_ru_positions.min()),
        "c_ru_max_N_m": float(fine.c_ru_positions.max()),
        "c_r_N_m": fine.c_r, "c_r_error_N_m": abs(fine.c_r - coarse.c_r),
        "dofs": fine.dofs, "seconds_mesh": results["fine"][1],
        "seconds_fe": results["fine"][2],
        "seconds_total": sum(r[1] + r[2] for r in results.values()),
    }


def run(args) -> int:
    from meshing import raba118
    from meshing.crack import Crack

    ring = raba118.ring_gear()
    cases = {"intact": None}
    if args.crack_depth > 0:
        crack = Crack(0, args.crack_depth)
        crack.path(ring)  # validate before any meshing
        cases[f"crack {args.crack_depth:g} m"] = crack
    out = {name: estimate(ring, crack) for name, crack in cases.items()}
    if args.json:
        print(json.dumps({"cases": out, "not_available": list(NOT_YET)}, indent=2))
        return 0
    print(f"{'case':<18} {'c_ru [N/m]':>12} {'+-':>9} {'min..max over carrier':>25} "
          f"{'c_r [N/m]':>11} {'+-':>9} {'DOFs':>8} {'time [s]':>9}")
    for name, r in out.items():
        print(f"{name:<18} {r['c_ru_N_m']:>12.5e} {r['c_ru_error_N_m']:>9.1e} "
              f"{r['c_ru_min_N_m']:>12.4e}..{r['c_ru_max_N_m']:<11.4e} {r['c_r_N_m']:>11.4e} "
              f"{r['c_r_error_N_m']:>9.1e} {r['dofs']:>8} {r['seconds_total']:>9.1f}")
    if len(out) == 2:
        intact, cracked = out.values()
        print(f"crack lowers c_ru by {100 * (1 - cracked['c_ru_N_m'] / intact['c_ru_N_m']):.2f} %")
    print("plane stress, steel E 210 GPa, nu 0.3; supports clamped; c_sp, c_rp, c_p, c_c: "
          "not computed by FE yet (use the preset values)")
    return 0
