"""Gmsh meshes of the ring gear and external gears (stage 1 of the chain).

The face below is what a user of the meshing stage imports: the gear geometry (ring
gear, spur gear, shaper cutter, gear body), the crack and its front and start kinds
with their registries, the mesh container ``FEMesh`` and the meshing options, the
benchmark meshes (annulus, edge-crack strip, centre-crack plate) and the VTU export.
Every name is imported on first use (PEP 562): ``import hubvib.meshing`` loads no gmsh
and no submodule; the mesh builders named like their module are imported from it
(``from hubvib.meshing.ring_mesh import ring_mesh``, ``...ring_mesh_3d import
ring_mesh_3d``, ``...to_skfem import to_skfem``).  Lengths in [m].
"""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .annulus import annulus_mesh
    from .crack import Crack, CrackFront
    from .crack_kinds import (CrackStart, FrontShape, front_shape, register_front,
                              register_start, start_kind)
    from .crack_plate import centre_crack_plate
    from .export import write_vtu
    from .fe_mesh import FEMesh
    from .gear import GearGeometryError, SpurGear
    from .gear_body import GearBody
    from .profile import ShaperCutter, ToothProfile
    from .ring_gear import RingGear, Supports, ToothedBody
    from .ring_mesh import MeshOptions
    from .session import MeshingError
    from .strip import edge_crack_strip

__all__ = [
    "RingGear", "SpurGear", "ToothedBody", "Supports", "GearBody", "ShaperCutter",
    "ToothProfile", "GearGeometryError",
    "Crack", "CrackFront", "CrackStart", "FrontShape", "register_start", "start_kind",
    "register_front", "front_shape",
    "FEMesh", "MeshOptions", "MeshingError",
    "annulus_mesh", "edge_crack_strip", "centre_crack_plate", "write_vtu",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
