"""c_rp over the engagement of a ring tooth cracked in 3D (SI units).

The solid ring gives the cracked tooth's compliance under a line load across
the face (``fem.tooth_solid``) at the flank radii of the plane tooth curve, and
the same for the intact tooth on a mesh of the same level.  Their ratio at
each radius scales the plane model's intact ring-tooth curve; that cracked
curve enters the plane pair and mesh-cycle machinery (``tooth_stiffness.
engaged_mesh``: planet tooth and Hertz in series, load shared over the path of
contact), so the 3D ratio over the engagement is read exactly as the plane one.
Scaling the plane curve (rather than using the 3D compliance itself) keeps the
intact pair identical to the plane study's: what the solid mesh's own error in
the tooth compliance (a few per cent stiff at the default level) shares between
the cracked and the intact tooth cancels in the ratio.
"""
from __future__ import annotations

import numpy as np

from hubvib.meshing.ring_gear import ToothedBody

from .material import Material
from .mesh_cycle import GearPair
from .tooth_stiffness import EngagedMesh, ToothCurve, contact_radii, engaged_mesh, intact_curve


def solid_engaged_mesh(planet: ToothedBody, ring: ToothedBody, radii, cracked, intact,
                       options, material: Material = Material(), tooth: int = 0
                       ) -> EngagedMesh:
    """c_rp over the engagement of ring tooth ``tooth`` whose 3D line-load compliance is
    ``cracked`` [m/N] against ``intact`` [m/N] at the flank ``radii`` [m] (the plane
    curve's Chebyshev radii); ``options`` mesh the plane intact curves."""
    cracked, intact = np.asarray(cracked, dtype=float), np.asarray(intact, dtype=float)
    radii = np.asarray(radii, dtype=float)
    if not (cracked.shape == intact.shape == radii.shape) or not len(radii):
        raise ValueError(f"radii, cracked and intact need one value per radius; got "
                         f"{radii.shape}, {cracked.shape}, {intact.shape}")
    if np.any(~np.isfinite(cracked) | (cracked <= 0) | ~np.isfinite(intact) | (intact <= 0)):
        raise ValueError("the 3D tooth compliances must be finite and > 0 [m/N]")
    plane = intact_curve(ring, contact_radii(ring, [GearPair(planet, ring)]), material,
                         options, tooth)
    if plane.radii.shape != radii.shape or np.abs(plane.radii - radii).max() > 1e-9:
        raise ValueError(f"the 3D radii {radii.tolist()} m are not the plane curve's "
                         f"{plane.radii.tolist()} m")
    curve = ToothCurve(plane.radii, plane.compliance * cracked / intact)
    return engaged_mesh(planet, ring, curve, options, material, tooth)
