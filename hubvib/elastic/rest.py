"""The ring-planet spring without the ring body [N/m]: the planet tooth and the contact.

The FE ring holds the ring tooth and rim, so the spring between a planet and its ring
patch carries only the rest of the pair: the planet tooth's compliance (FE, or the
analytical potential-energy method) and the Hertzian contact, in series, the pairs in
contact sharing the load, mean over one mesh cycle (``fem.mesh_cycle``) -- the FE pair
stiffness ``c_rp`` with the ring tooth's compliance set to zero.
"""
from __future__ import annotations

import numpy as np

from hubvib.build.stages import gear_body, material, ring_gear
from hubvib.fem.mesh_cycle import GearPair, mesh_cycle
from hubvib.fem.tooth_beam import hertz_compliance
from hubvib.fem.tooth_stiffness import beam_curve, contact_radii, intact_curve
from hubvib.meshing.ring_mesh import MeshOptions


def rest_stiffness(design, method: str = "fe") -> float:
    """Mean over the mesh cycle of the ring-planet pair without the ring tooth [N/m]."""
    ring, planet, mat = ring_gear(design), gear_body(design, "planet"), material(design)
    pair = GearPair(planet, ring)
    span = contact_radii(planet, [pair])
    curve = (intact_curve(planet, span, mat, MeshOptions()) if method == "fe"
             else beam_curve(planet, span, mat))
    q_h = hertz_compliance(min(planet.gear.face_width, ring.gear.face_width), mat)
    return mesh_cycle(pair, curve, lambda r: np.zeros_like(np.asarray(r, dtype=float)),
                      q_h).mean
