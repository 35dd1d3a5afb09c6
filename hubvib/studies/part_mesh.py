"""A Gmsh mesh of one part of a design: the ring (plane or solid, intact or cracked) or the
sun or planet on its bore, measured against its exact area or volume and mass, written
as VTU and PNG (what ``hubvib mesh`` prints).  SI units: m, m^2, m^3, kg, s."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from hubvib.reducer import gear_body, ring_gear
from hubvib.foundation.bounds import lower_bound
from hubvib.foundation.output import output_set
from hubvib.meshing import measure
from hubvib.meshing.crack import Crack, CrackFront
from hubvib.meshing.export import write_png, write_vtu
from hubvib.meshing.gear import GearGeometryError
from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh
from hubvib.meshing.ring_mesh_3d import SOLID_OPTIONS, ring_mesh_3d

#: most bulk elements ``size`` may ask for (estimated from the exact area or volume before
#: meshing): 5e5 triangles take minutes to mesh on 2 cores
MAX_ELEMENTS = {2: 5e5, 3: 2e5}


@dataclass(frozen=True)
class PartMesh:
    """What to mesh: ``part`` ("ring", "sun", "planet"); the crack (``crack_depth`` [m] along
    its path, 0 = intact; ``crack_tooth``; ``crack_angle`` [rad] from the radial;
    ``crack_start``; in 3D ``crack_front`` and ``crack_half_length`` [m]); ``order`` 1 or 2;
    ``dim`` 2 (plane section) or 3 (solid, ring only); ``size`` and ``tip_size`` [m]
    (None: the defaults of the plane or solid mesher)."""

    part: str
    crack_depth: float = 0.0
    crack_tooth: int = 0
    crack_angle: float = 0.0
    crack_start: str = "root"
    order: int = 2
    dim: int = 2
    crack_front: str = "through"
    crack_half_length: float = 5e-3
    size: float | None = None
    tip_size: float | None = None

    @property
    def name(self) -> str:
        """File stem of the mesh."""
        return self.part + ("" if self.crack_depth == 0 else f"_crack_{self.crack_depth:g}m") + (
            "_3d" if self.dim == 3 else "")


def part_body(design, request: PartMesh):
    """The ring (``meshing.RingGear``) or the named gear body of the design."""
    return ring_gear(design) if request.part == "ring" else gear_body(design, request.part)


def check_size(request: PartMesh, body) -> None:
    """Refuse a ``size`` whose mesh would be too large, before any meshing.

    Elements ~ area / (sqrt(3)/4 h^2) (equilateral triangles) or volume /
    (h^3 / (6 sqrt(2))) (regular tetrahedra); refinement at the teeth adds to it.
    """
    size = request.size
    if size is None or (request.dim == 3 and request.part != "ring"):
        return  # mesh_part refuses a solid sun or planet
    if not (math.isfinite(size) and size > 0):
        raise ValueError(f"--size = {size!r} m, but it must be a finite size > 0")
    if request.dim == 3:
        extent, cell = body.area() * body.gear.face_width, 1 / (6 * math.sqrt(2))
    else:
        extent, cell = body.area(), math.sqrt(3) / 4
    estimate = extent / (cell * size ** request.dim)
    limit = MAX_ELEMENTS[request.dim]
    if estimate > limit:
        smallest = (extent / (cell * limit)) ** (1 / request.dim)
        raise ValueError(f"--size = {size:g} m would give ~{estimate:.1e} elements of the "
                         f"{request.part}; allowed >= {float(lower_bound(smallest, 2)):.1e} m "
                         f"(at most {limit:.0e} "
                         f"{'tetrahedra' if request.dim == 3 else 'triangles'})")


def mesh_part(body, request: PartMesh):
    """The mesh (``meshing.FEMesh``) of ``body`` as the request asks."""
    crack = Crack(request.crack_tooth, request.crack_depth, request.crack_angle,
                  request.crack_start)
    if request.part != "ring":
        if request.crack_depth or request.dim == 3:
            raise GearGeometryError(f"{request.part}: cracks and --dim 3 are for the ring only")
        return ring_mesh(body, None, _options(MeshOptions(), request))
    if request.dim == 3:
        front = CrackFront(request.crack_front, half_length=request.crack_half_length)
        return ring_mesh_3d(body, crack, front, _options(SOLID_OPTIONS, request))
    return ring_mesh(body, crack, _options(MeshOptions(), request))


def summary(body, mesh) -> dict:
    """Counts, size against the exact value, mass [kg], quality and groups of a mesh."""
    if mesh.dim == 3:
        size = {"volume_m3": measure.volume(mesh), "exact_volume_m3": mesh.info["exact_volume"]}
    else:
        size = {"area_m2": measure.area(mesh), "exact_area_m2": mesh.info["exact_area"]}
    measured, exact = size.values()
    return {"nodes": mesh.info["nodes"], "elements": mesh.info["elements"],
            "cell_type": mesh.cell_type, **size, "relative_error": measured / exact - 1,
            "mass_kg": measure.mass(mesh, body.gear.face_width, body.density),
            "min_quality_sicn": mesh.info["min_quality"],
            "mean_quality_sicn": mesh.info["mean_quality"],
            "seconds": mesh.info["seconds"], "crack_path_m": mesh.info["crack_path"],
            "groups": sorted(mesh.boundaries)}


def write_part_mesh(design, request: PartMesh, out: Path) -> tuple[dict, object]:
    """Mesh the part into ``out`` (``NAME.vtu`` and ``NAME.png``, one output set); returns
    the summary with the ``files`` and the mesh."""
    body = part_body(design, request)
    check_size(request, body)
    with output_set(out) as staged:  # checked and locked before the meshing
        mesh = mesh_part(body, request)
        info = summary(body, mesh)
        write_vtu(mesh, staged / f"{request.name}.vtu")
        tooth = body.tooth_angle(request.crack_tooth)
        centre = None if request.crack_depth else body.load_radius * np.array(
            [math.cos(tooth), math.sin(tooth)])
        write_png(mesh, staged / f"{request.name}.png", centre=centre,
                  half_width=None if request.crack_depth else 0.02)
    info["files"] = [str(out / f"{request.name}.{ext}") for ext in ("vtu", "png")]
    return info, mesh


def _options(defaults, request: PartMesh):
    changes = {"order": request.order}
    if request.size is not None:
        changes["size"] = request.size
    if request.tip_size is not None:
        changes["tip_size"] = request.tip_size
    return replace(defaults, **changes)
