"""``hubvib mesh ring``: build, measure and write a ring-gear mesh."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

RING_PRESETS = ("raba118",)


def add_parser(sub) -> None:
    p = sub.add_parser("mesh", help="gmsh mesh of the ring gear (VTU + PNG + counts)")
    p.add_argument("part", choices=["ring"])
    p.add_argument("--preset", default="raba118", choices=RING_PRESETS)
    p.add_argument("--crack-depth", type=float, default=0.0, metavar="D",
                   help="crack length along its path [m]; 0 = intact")
    p.add_argument("--crack-tooth", type=int, default=0)
    p.add_argument("--crack-angle", type=float, default=0.0, metavar="DEG",
                   help="crack direction from the radial [deg]")
    p.add_argument("--crack-start", choices=["root", "rim"], default="root")
    p.add_argument("--order", type=int, choices=[1, 2], default=2)
    p.add_argument("--dim", type=int, choices=[2], default=2,
                   help="2 (plane); 3D extrusion is not available yet")
    p.add_argument("--size", type=float, default=2e-3, help="bulk element size [m]")
    p.add_argument("--tip-size", type=float, default=5e-5, help="element size at the crack tip [m]")
    p.add_argument("--out", type=Path, default=Path("hubvib-out/mesh"))
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def build(args):
    from meshing import raba118
    from meshing.crack import Crack
    from meshing.ring_mesh import MeshOptions, ring_mesh

    ring = raba118.ring_gear()
    crack = Crack(args.crack_tooth, args.crack_depth, math.radians(args.crack_angle),
                  args.crack_start)
    options = MeshOptions(size=args.size, tip_size=args.tip_size, order=args.order)
    return ring, ring_mesh(ring, crack, options)


def summary(ring, mesh) -> dict:
    from meshing import measure

    area, exact = measure.area(mesh), mesh.info["exact_area"]
    return {"nodes": mesh.info["nodes"], "elements": mesh.info["elements"],
            "cell_type": mesh.cell_type, "area_m2": area, "exact_area_m2": exact,
            "area_relative_error": area / exact - 1,
            "mass_kg": measure.mass(mesh, ring.gear.face_width, ring.density),
            "min_quality_sicn": mesh.info["min_quality"],
            "mean_quality_sicn": mesh.info["mean_quality"],
            "seconds": mesh.info["seconds"], "crack_path_m": mesh.info["crack_path"],
            "groups": sorted(mesh.boundaries)}


def run(args) -> int:
    from meshing.export import write_png, write_vtu

    ring, mesh = build(args)
    info = summary(ring, mesh)
    name = "ring" if args.crack_depth == 0 else f"ring_crack_{args.crack_depth:g}m"
    files = [write_vtu(mesh, args.out / f"{name}.vtu")]
    tooth = ring.tooth_angle(args.crack_tooth)
    centre = None if args.crack_depth else ring.load_radius * 1.04 * np.array(
        [math.cos(tooth), math.sin(tooth)])
    files.append(write_png(mesh, args.out / f"{name}.png", centre=centre,
                           half_width=None if args.crack_depth else 0.02))
    info["files"] = [str(f) for f in files]
    if args.json:
        print(json.dumps(info, indent=2))
        return 0
    print(f"{info['nodes']} nodes, {info['elements']} {info['cell_type']} elements, "
          f"meshed in {info['seconds']:.2f} s")
    print(f"area {info['area_m2']:.9e} m^2 (exact {info['exact_area_m2']:.9e}, relative error "
          f"{info['area_relative_error']:.1e}); mass {info['mass_kg']:.4f} kg")
    print(f"element quality (gmsh minSICN): min {info['min_quality_sicn']:.3f}, "
          f"mean {info['mean_quality_sicn']:.3f}")
    print(f"written: {', '.join(info['files'])}")
    return 0
