"""``hubvib crack-path``: the path a root crack takes (LEFM growth) and what it severs."""
from __future__ import annotations

from pathlib import Path

from hubvib.foundation.output import json_text, written_line

from ._reducer import add_reducer_options, reducer_name

#: most growth steps the command accepts
MAX_STEPS = 200


def add_parser(sub) -> None:
    p = sub.add_parser("crack-path", help="grow the ring's root crack by LEFM (K_I, K_II, "
                       "maximum tangential stress) until it severs the tooth or the rim")
    add_reducer_options(p)
    p.add_argument("--steps", type=int, default=40, metavar="N",
                   help=f"most growth steps (FE solutions), 1..{MAX_STEPS}; default 40")
    p.add_argument("--step", type=float, default=0.5e-3, metavar="DA",
                   help="crack extension per step [m], 1e-5..1e-2; default 5e-4")
    p.add_argument("--tooth", type=int, default=None, metavar="K",
                   help="cracked ring tooth; default the one midway between two support pads")
    p.add_argument("--out", type=Path, default=Path("hubvib-out/crack-path"),
                   help="folder for crack_path.png, crack_step_NN.vtu and crack_path.json")
    p.add_argument("--load", choices=("worst", "envelope"), default="worst",
                   help="worst: the mesh force at the highest point of single tooth contact "
                   "(default); envelope: at each step the position of the mesh cycle that "
                   "drives the crack hardest (largest MTS driving force)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.fem.crack_propagation import GrowthOptions
    from hubvib.runtime.progress import progress
    from hubvib.studies.lefm_path import crack_path

    from .design import design_from_argument

    if not 1 <= args.steps <= MAX_STEPS:
        raise ValueError(f"--steps = {args.steps}, allowed 1..{MAX_STEPS}")
    if not 1e-5 <= args.step <= 1e-2:  # NaN fails too
        raise ValueError(f"--step = {args.step!r} m, allowed 1e-5..1e-2 m")
    design = design_from_argument(reducer_name(args))
    options = GrowthOptions(step=args.step, initial_depth=args.step, max_steps=args.steps)
    with progress(args.steps, "crack growth", "step") as bar:
        result = crack_path(design, options, args.out, args.tooth, args.load,
                            on_step=lambda index, step: bar.update(
                                1, f"depth {1e3 * step.depth:.3g} mm, K_I "
                                   f"{step.k_i / 1e6:.3g} MPa m^0.5"))
    info = result.to_dict()
    if args.json:
        print(json_text(info))
        return 0
    print(f"design {info['design']!r}: backup ratio {info['backup_ratio']:.3f} (rim "
          f"{1e3 * info['rim_thickness_m']:.3f} mm / tooth height "
          f"{1e3 * info['tooth_height_m']:.3f} mm); root crack at tooth {info['tooth']}, "
          f"mesh force {info['force_N']:.1f} N at r = {1e3 * info['load_radius_m']:.3f} mm")
    print(f"{'step':>4} {'depth mm':>9} {'tip x mm':>9} {'tip y mm':>9} {'K_I MPa m^0.5':>14} "
          f"{'K_II MPa m^0.5':>15} {'kink deg':>9}")
    tips = info["path_m"][1:]
    for i, (depth, k1, k2, kink) in enumerate(zip(info["depth_m"], info["k_i_mpa_sqrt_m"],
                                                  info["k_ii_mpa_sqrt_m"],
                                                  info["kink_angle_deg"])):
        x, y = tips[i]
        print(f"{i:>4} {1e3 * depth:>9.3f} {1e3 * x:>9.3f} {1e3 * y:>9.3f} {k1:>14.3f} "
              f"{k2:>15.3f} {kink:>9.2f}")
    x, y = info["exit_m"]
    if info["severed"]:
        print(f"fracture: {info['fracture']} (the crack reaches the "
              f"{'toothed surface' if info['fracture'] == 'tooth' else 'outer surface'} at "
              f"({1e3 * x:.3f}, {1e3 * y:.3f}) mm)")
    else:
        print(f"fracture: {info['fracture']} (not severed after {info['steps']} steps; its "
              f"direction leads to ({1e3 * x:.3f}, {1e3 * y:.3f}) mm)")
    print(written_line(info["files"]))
    return 0
