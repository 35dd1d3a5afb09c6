"""Mesh levels: the default options scaled, a family tuned for the ring's c_ru, and the
solid levels of the 3D estimate (SI)."""
from __future__ import annotations

import math
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


def ring_options(scale: float) -> MeshOptions:
    """Plane ring mesh for c_ru with the sizes where c_ru needs them (``scale`` [-]).

    Halving one size of the default mesh at a time (scale 1) moves c_ru by +3e-4 for the
    toothed boundary, -1.1e-4 for the support ends (``tip_size``, 4x), 4e-5 for the
    grading and 2e-6 or less for the rim and the load patches.  So here the toothed
    boundary is a level finer than in ``scaled_options(scale)``, the rim 2 sqrt 2 times
    coarser, the load patches as coarse (at most the patch itself) and the grading twice
    as fast.  At scale sqrt 2 (measured, intact ring, plane stress): 6.6e4 DOFs and c_ru
    within 6e-4 of the finest uniform level (scale 0.354, 6.0e5 DOFs), against 1.05e5
    DOFs and 7.9e-4 for ``scaled_options(sqrt 2)``.
    """
    default = MeshOptions()
    coarse = 2 * math.sqrt(2) * scale
    return replace(default, size=coarse * default.size,
                   load_size=min(default.load_patch, coarse * default.load_size),
                   grading=min(1.0, 2 * default.grading),
                   tooth_size=scale / math.sqrt(2) * default.tooth_size,
                   tip_size=scale * default.tip_size)


def solid_options(rim: float, tooth: float, load: float) -> MeshOptions:
    """Solid-mesh options with these rim, tooth and load-patch element sizes [m]."""
    return replace(SOLID_OPTIONS, size=rim, tooth_size=tooth, load_size=load,
                   tip_size=min(load, SOLID_OPTIONS.tip_size))
