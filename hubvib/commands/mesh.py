"""``hubvib mesh ring``: build, measure and write a ring-gear mesh."""
from __future__ import annotations

import math
import time
from pathlib import Path

from hubvib.foundation.output import json_text, written_line
from hubvib.meshing.crack import FRONT_SHAPES, STARTS
from hubvib.studies.part_mesh import MAX_ELEMENTS, PartMesh, write_part_mesh

from ._reducer import add_reducer_options, reducer_name


def add_parser(sub) -> None:
    p = sub.add_parser("mesh", help="gmsh mesh of a gear body (VTU + PNG + counts)")
    p.add_argument("part", choices=["ring", "sun", "planet"],
                   help="the ring (may be cracked), or the sun or planet on its bore")
    add_reducer_options(p)
    p.add_argument("--crack-depth", type=float, default=0.0, metavar="D",
                   help="ring crack length along its path [m] (metres: 0.005 = 5 mm); 0 = intact")
    p.add_argument("--crack-tooth", type=int, default=None, metavar="K",
                   help="cracked ring tooth, with --crack-depth; default 0")
    p.add_argument("--crack-angle", type=float, default=None, metavar="DEG",
                   help="crack direction from the radial [deg], with --crack-depth; default 0")
    p.add_argument("--crack-start", choices=STARTS, default=None,
                   help="where the crack starts, with --crack-depth; default root")
    p.add_argument("--order", type=int, choices=[1, 2], default=2,
                   help="element order: 1 linear, 2 quadratic (default)")
    p.add_argument("--dim", type=int, choices=[2, 3], default=2,
                   help="2 (plane section) or 3 (solid, ring only; coarser default sizes)")
    p.add_argument("--crack-front", choices=FRONT_SHAPES, default=None,
                   help="--dim 3 with --crack-depth: crack through the face width (default), or "
                   "a semi-elliptic surface crack")
    p.add_argument("--crack-half-length", type=float, default=None, metavar="C",
                   help="--crack-front semi_elliptic: half its length along the width [m]; "
                   "default 5e-3")
    p.add_argument("--size", type=float, default=None,
                   help="bulk element size [m] (default 2e-3 in 2D, 6e-3 in 3D); at most "
                   f"{MAX_ELEMENTS[2]:.0e} triangles or {MAX_ELEMENTS[3]:.0e} tetrahedra "
                   "(ring: >= 3.2e-4 m in 2D, >= 3.4e-3 m in 3D)")
    p.add_argument("--tip-size", type=float, default=None,
                   help="element size at the crack tip [m] (default 5e-5 in 2D, 5e-4 in 3D)")
    p.add_argument("--out", type=Path, default=Path("hubvib-out/mesh"), metavar="DIR",
                   help="output folder for the VTU and PNG (default hubvib-out/mesh)")
    p.add_argument("--json", action="store_true", help="machine-readable output (JSON)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.runtime.progress import stage, working

    from ._applies import refuse_ignored, value
    from .design import design_from_argument

    cracked = args.part == "ring" and args.crack_depth != 0
    crack = "to a ring crack (mesh ring --crack-depth D, D > 0 [m])"
    refuse_ignored(args, (
        ("--crack-tooth", cracked, crack), ("--crack-angle", cracked, crack),
        ("--crack-start", cracked, crack),
        ("--crack-front", cracked and args.dim == 3, "to a crack in the solid ring "
         "(--dim 3 --crack-depth D)"),
        ("--crack-half-length", cracked and args.dim == 3 and args.crack_front ==
         "semi_elliptic", "to a semi-elliptic crack (--dim 3 --crack-depth D --crack-front "
         "semi_elliptic)")))
    angle = args.crack_angle
    request = PartMesh(args.part, args.crack_depth,
                       value(args, "--crack-tooth", PartMesh.crack_tooth),
                       PartMesh.crack_angle if angle is None else math.radians(angle),
                       value(args, "--crack-start", PartMesh.crack_start), args.order, args.dim,
                       value(args, "--crack-front", PartMesh.crack_front),
                       value(args, "--crack-half-length", PartMesh.crack_half_length),
                       args.size, args.tip_size)
    design = design_from_argument(reducer_name(args))
    started = time.perf_counter()
    what = f"{args.dim}D mesh of the {args.part}"
    with working(what):
        info, mesh = write_part_mesh(design, request, args.out)
    stage(what, started)
    if args.json:
        print(json_text(info))
        return 0
    print(f"{info['nodes']} nodes, {info['elements']} {info['cell_type']} elements, "
          f"meshed in {info['seconds']:.2f} s")
    what, unit = ("volume", "m^3") if mesh.dim == 3 else ("area", "m^2")
    print(f"{what} {info[f'{what}_{unit[0]}{unit[-1]}']:.9e} {unit} (exact "
          f"{info[f'exact_{what}_{unit[0]}{unit[-1]}']:.9e}, relative error "
          f"{info['relative_error']:.1e}); mass {info['mass_kg']:.4f} kg")
    if mesh.info.get("straightened"):
        print(f"{mesh.info['straightened']} curved tetrahedra had their surface edges straightened "
              "(they would have been inverted)")
    print(f"element quality (gmsh minSICN): min {info['min_quality_sicn']:.3f}, "
          f"mean {info['mean_quality_sicn']:.3f}")
    print(written_line(info["files"]))
    return 0
