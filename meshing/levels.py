"""Mesh levels: the default options scaled, and the solid levels of the 3D estimate (SI)."""
from __future__ import annotations

from dataclasses import replace

from .ring_mesh import MeshOptions
from .ring_mesh_3d import SOLID_OPTIONS

#: solid mesh levels for c_ru in 3D: rim, tooth and load-patch element sizes [m]; the
#: last is the default, the one before it gives the error estimate
SOLID_LEVELS = ((10e-3, 5e-3, 4e-3), (7e-3, 4e-3, 3e-3), (5e-3, 3e-3, 2e-3))
#: the benchmark's reference level (~1e6 DOFs) [m]
SOLID_REFERENCE = (4e-3, 2.2e-3, 1.5e-3)


def scaled_options(scale: float) -> MeshOptions:
    """The default plane mesh with every element size times ``scale`` [-]."""
    default = MeshOptions()
    return MeshOptions(size=scale * default.size, tooth_size=scale * default.tooth_size,
                       tip_size=scale * default.tip_size, load_size=scale * default.load_size)


def solid_options(rim: float, tooth: float, load: float) -> MeshOptions:
    """Solid-mesh options with these rim, tooth and load-patch element sizes [m]."""
    return replace(SOLID_OPTIONS, size=rim, tooth_size=tooth, load_size=load,
                   tip_size=min(load, SOLID_OPTIONS.tip_size))
