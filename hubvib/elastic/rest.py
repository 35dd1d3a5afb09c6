"""The ring-planet spring without the ring body [N/m]: the planet tooth and the contact.

The FE ring holds the ring tooth and rim, so the spring between a planet and its ring
patch carries only the rest of the pair: the planet tooth's compliance (FE, or the
analytical potential-energy method) and the Hertzian contact, in series, the pairs in
contact sharing the load, mean over one mesh cycle (``fem.mesh_cycle``) -- the FE pair
stiffness ``c_rp`` with the ring tooth's compliance set to zero.

The FE planet tooth is the intact curve the crack study's FE stage computes as well: it
comes from the same on-disk store (``runtime.tooth_curves``), computed by whichever
process needs it first (same floats either way).
"""
from __future__ import annotations

import numpy as np

from hubvib.reducer.stages import gear_body, material, ring_gear
from hubvib.fem.mesh_cycle import GearPair, mesh_cycle
from hubvib.fem.tooth_beam import hertz_compliance
from hubvib.fem.tooth_stiffness import beam_curve, contact_radii, intact_curve, set_intact_store
from hubvib.meshing.ring_mesh import MeshOptions
from hubvib.runtime.tooth_curves import shared_intact_curve


def rest_stiffness(design, method: str = "fe") -> float:
    """Mean over the mesh cycle of the ring-planet pair without the ring tooth [N/m]."""
    ring, planet, mat = ring_gear(design), gear_body(design, "planet"), material(design)
    pair = GearPair(planet, ring)
    span = contact_radii(planet, [pair])
    if method == "fe":
        set_intact_store(shared_intact_curve)
        try:
            curve = intact_curve(planet, span, mat, MeshOptions())
        finally:
            set_intact_store(None)
    else:
        curve = beam_curve(planet, span, mat)
    q_h = hertz_compliance(min(planet.gear.face_width, ring.gear.face_width), mat)
    return mesh_cycle(pair, curve, lambda r: np.zeros_like(np.asarray(r, dtype=float)),
                      q_h).mean
