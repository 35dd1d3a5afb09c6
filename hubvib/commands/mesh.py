"""``hubvib mesh ring``: build, measure and write a ring-gear mesh."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from hubvib.design import preset_names
from hubvib.foundation.output import json_text, output_set
from hubvib.meshing.crack import STARTS

#: most bulk elements ``--size`` may ask for (estimated from the exact area or volume
#: before meshing): 5e5 triangles take ~2 min to mesh on 2 cores (2.1e5 at 5e-4 m: 41 s)
MAX_ELEMENTS = {2: 5e5, 3: 2e5}


def add_parser(sub) -> None:
    p = sub.add_parser("mesh", help="gmsh mesh of a gear body (VTU + PNG + counts)")
    p.add_argument("part", choices=["ring", "sun", "planet"],
                   help="the ring (may be cracked), or the sun or planet on its bore")
    p.add_argument("--preset", default="raba118", choices=preset_names(),
                   help="a registered design preset (hubvib.design.PRESETS)")
    p.add_argument("--design", metavar="FILE.toml", help="a reducer design file (replaces "
                   "--preset)")
    p.add_argument("--crack-depth", type=float, default=0.0, metavar="D",
                   help="crack length along its path [m]; 0 = intact")
    p.add_argument("--crack-tooth", type=int, default=0)
    p.add_argument("--crack-angle", type=float, default=0.0, metavar="DEG",
                   help="crack direction from the radial [deg]")
    p.add_argument("--crack-start", choices=STARTS, default="root")
    p.add_argument("--order", type=int, choices=[1, 2], default=2)
    p.add_argument("--dim", type=int, choices=[2, 3], default=2,
                   help="2 (plane section) or 3 (solid, ring only; coarser default sizes)")
    p.add_argument("--crack-front", choices=["through", "semi_elliptic"], default="through",
                   help="3D: crack through the face width, or a semi-elliptic surface crack")
    p.add_argument("--crack-half-length", type=float, default=5e-3, metavar="C",
                   help="3D semi-elliptic crack: half its length along the width [m]")
    p.add_argument("--size", type=float, default=None,
                   help="bulk element size [m] (default 2e-3 in 2D, 6e-3 in 3D); at most "
                   f"{MAX_ELEMENTS[2]:.0e} triangles or {MAX_ELEMENTS[3]:.0e} tetrahedra "
                   "(ring: >= 3.2e-4 m in 2D, >= 3.3e-3 m in 3D)")
    p.add_argument("--tip-size", type=float, default=None,
                   help="element size at the crack tip [m] (default 5e-5 in 2D, 5e-4 in 3D)")
    p.add_argument("--out", type=Path, default=Path("hubvib-out/mesh"))
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def bodies(args):
    """The ring and the named body (ring, sun or planet) of the design the options give."""
    from hubvib.build.stages import gear_body, ring_gear

    from .design import design_from_argument

    design = design_from_argument(args.design or args.preset)
    return ring_gear(design) if args.part == "ring" else gear_body(design, args.part)


def build(args):
    from hubvib.meshing.crack import Crack, CrackFront
    from hubvib.meshing.gear import GearGeometryError
    from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh

    crack = Crack(args.crack_tooth, args.crack_depth, math.radians(args.crack_angle),
                  args.crack_start)
    if args.part != "ring":
        if args.crack_depth or args.dim == 3:
            raise GearGeometryError(f"{args.part}: cracks and --dim 3 are for the ring only")
        body = bodies(args)
        return body, ring_mesh(body, None, _options(MeshOptions(), args))
    ring = bodies(args)
    if args.dim == 3:
        from hubvib.meshing.ring_mesh_3d import SOLID_OPTIONS, ring_mesh_3d

        front = CrackFront(args.crack_front, half_length=args.crack_half_length)
        return ring, ring_mesh_3d(ring, crack, front, _options(SOLID_OPTIONS, args))
    return ring, ring_mesh(ring, crack, _options(MeshOptions(), args))


def check_size(args, body) -> None:
    """Refuse a ``--size`` whose mesh would be too large, before any meshing.

    Elements ~ area / (sqrt(3)/4 h^2) (equilateral triangles) or volume /
    (h^3 / (6 sqrt(2))) (regular tetrahedra); refinement at the teeth adds to it.
    """
    if args.size is None or (args.dim == 3 and args.part != "ring"):
        return  # build() refuses a solid sun or planet
    if not (math.isfinite(args.size) and args.size > 0):
        raise ValueError(f"--size = {args.size!r} m, but it must be a finite size > 0")
    if args.dim == 3:
        extent, cell = body.area() * body.gear.face_width, 1 / (6 * math.sqrt(2))
    else:
        extent, cell = body.area(), math.sqrt(3) / 4
    estimate = extent / (cell * args.size ** args.dim)
    limit = MAX_ELEMENTS[args.dim]
    if estimate > limit:
        smallest = (extent / (cell * limit)) ** (1 / args.dim)
        raise ValueError(f"--size = {args.size:g} m would give ~{estimate:.1e} elements of the "
                         f"{args.part}; allowed >= {smallest:.1e} m (at most {limit:.0e} "
                         f"{'tetrahedra' if args.dim == 3 else 'triangles'})")


def _options(defaults, args):
    from dataclasses import replace

    changes = {"order": args.order}
    if args.size is not None:
        changes["size"] = args.size
    if args.tip_size is not None:
        changes["tip_size"] = args.tip_size
    return replace(defaults, **changes)


def summary(ring, mesh) -> dict:
    from hubvib.meshing import measure

    if mesh.dim == 3:
        size = {"volume_m3": measure.volume(mesh), "exact_volume_m3": mesh.info["exact_volume"]}
    else:
        size = {"area_m2": measure.area(mesh), "exact_area_m2": mesh.info["exact_area"]}
    measured, exact = size.values()
    return {"nodes": mesh.info["nodes"], "elements": mesh.info["elements"],
            "cell_type": mesh.cell_type, **size, "relative_error": measured / exact - 1,
            "mass_kg": measure.mass(mesh, ring.gear.face_width, ring.density),
            "min_quality_sicn": mesh.info["min_quality"],
            "mean_quality_sicn": mesh.info["mean_quality"],
            "seconds": mesh.info["seconds"], "crack_path_m": mesh.info["crack_path"],
            "groups": sorted(mesh.boundaries)}


def run(args) -> int:
    from hubvib.meshing.export import write_png, write_vtu

    check_size(args, bodies(args))
    name = args.part + ("" if args.crack_depth == 0 else f"_crack_{args.crack_depth:g}m") + (
        "_3d" if args.dim == 3 else "")
    with output_set(args.out) as staged:  # checked and locked before the meshing
        ring, mesh = build(args)
        info = summary(ring, mesh)
        write_vtu(mesh, staged / f"{name}.vtu")
        tooth = ring.tooth_angle(args.crack_tooth)
        centre = None if args.crack_depth else ring.load_radius * np.array(
            [math.cos(tooth), math.sin(tooth)])
        write_png(mesh, staged / f"{name}.png", centre=centre,
                  half_width=None if args.crack_depth else 0.02)
    info["files"] = [str(args.out / f"{name}.{ext}") for ext in ("vtu", "png")]
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
    print(f"written: {', '.join(info['files'])}")
    return 0
