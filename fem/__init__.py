"""scikit-fem stiffnesses of the ring, the tooth pairs and the bearings (stage 2 of the chain).

The face below is what a user of the FE stage imports: the material, the plane and solid
models and their solve, the ring's torsional stiffness and the cracked-tooth level, the
mesh-cycle stiffness of a gear pair, the cost estimates, modes, fracture mechanics and
crack growth.  Every name is imported on first use (PEP 562), so ``import hubvib.fem``
loads neither scikit-fem nor gmsh nor any submodule; the functions named like their
module (``ring_stiffness``, ``crack_level``, ``mesh_cycle``) are imported from it
(``from hubvib.fem.ring_stiffness import ring_stiffness``).  SI units throughout.
"""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .annulus import exact_k_theta, fe_k_theta
    from .bearing import BearingError, RollerBearing
    from .crack_level import CrackLevel
    from .crack_propagation import CrackGrowth, GrowthError, GrowthOptions, grow_crack
    from .edge_crack import fe_rotation_compliance, handbook_added_compliance
    from .elasticity import PlaneModel, Solution, plane_model, rigid_body_modes, solve, supported
    from .estimate import (CrackCaseEstimate, MeshEstimate, RingEstimate, estimate_crack_case,
                           estimate_mesh, estimate_ring)
    from .fracture import FractureError, StressIntensity, mts_angle, mts_driving_force
    from .iso6336 import IsoStiffness, iso_stiffness
    from .material import Material, MaterialError
    from .mesh_cycle import GearPair, MeshCycle, pair_stiffness
    from .modal import Modes, lowest_modes
    from .ring_stiffness import RingStiffness
    from .solid import SolidModel, solid_model
    from .solvers import SingularSystemError
    from .stress import von_mises
    from .tooth_fe import FEToothCompliance, fe_tooth_compliance
    from .tooth_stiffness import PairStiffness, reducer_mesh_stiffness

__all__ = [
    "Material", "MaterialError",
    "PlaneModel", "plane_model", "Solution", "solve", "supported", "rigid_body_modes",
    "SingularSystemError", "SolidModel", "solid_model",
    "RingStiffness", "CrackLevel",
    "GearPair", "MeshCycle", "pair_stiffness", "PairStiffness", "reducer_mesh_stiffness",
    "IsoStiffness", "iso_stiffness", "FEToothCompliance", "fe_tooth_compliance",
    "BearingError", "RollerBearing",
    "RingEstimate", "estimate_ring", "CrackCaseEstimate", "estimate_crack_case",
    "MeshEstimate", "estimate_mesh",
    "Modes", "lowest_modes", "von_mises",
    "FractureError", "StressIntensity", "mts_angle", "mts_driving_force",
    "CrackGrowth", "GrowthError", "GrowthOptions", "grow_crack",
    "exact_k_theta", "fe_k_theta", "fe_rotation_compliance", "handbook_added_compliance",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
