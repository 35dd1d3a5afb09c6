"""Where each planet's sun and ring mesh stand in their mesh cycle, from the gear geometry.

The position in the cycle is the roll length ``s`` of the contact on the planet
(distance along the line of action from the planet's base tangent point), as in
:class:`hubvib.fem.mesh_cycle.GearPair` with the planet as the first gear.

Geometry (planet ``i`` at polar angle ``theta_i`` about the sun/ring centre, the
ring fixed, tooth ``k`` of the ring centred on ``2 pi k / z_r`` with its ``+psi``
flank loaded, as in the FE tooth model): the ring-mesh line of action touches
the planet's base circle at ``theta_i + alpha_r`` (the row of
:func:`hubvib.lumped.network.spring_network`), and the loaded ``+psi`` involute
of ring tooth ``k`` starts on the ring's base circle at ``2 pi k / z_r + psi_b``
(``psi_b``: half tooth angle on the base circle).  Unwinding it gives the
contact's roll length on the planet

    s_r(theta_i, k) = r_br (theta_i + alpha_r - 2 pi k / z_r - psi_b,r) - a sin(alpha_r),

and on the planet the sun mesh loads the opposite flank, so the two roll lengths
of one planet always add up to the same number (its teeth are rigid):

    s_s + s_r = r_bp (2 psi_b,p + alpha_s + alpha_r - pi)   (mod p_b).

Consequences (Parker & Lin 2004, "Mesh phasing relationships in planetary and
epicyclic gears", J. Mech. Des. 126): planet ``i``'s ring mesh runs
``z_r psi_i / 2 pi`` mesh cycles ahead of planet 1's, its sun mesh
``-z_s psi_i / 2 pi``; both are the same fraction of a cycle when
``(z_s + z_r) psi_i / 2 pi`` is an integer (the assembly condition).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.reducer.stages import spur_gears
from hubvib.meshing.gear import centre_distance, working_pressure_angle


@dataclass(frozen=True)
class MeshPhasing:
    """Geometry that places the meshes in their cycle.

    Attributes
    ----------
    base_pitch : float
        p_b [m] (the same on all three gears).
    ring_base_radius, planet_base_radius : float
        r_br, r_bp [m].
    tangent_gap : float
        a sin(alpha_r): distance between the two base tangent points of the ring mesh [m].
    alpha_s, alpha_r : float
        Working pressure angles [rad].
    ring_base_half_angle, planet_base_half_angle : float
        Half tooth angle on the base circle, psi_b [rad].
    ring_teeth : int
        z_r.
    """

    base_pitch: float
    ring_base_radius: float
    planet_base_radius: float
    tangent_gap: float
    alpha_s: float
    alpha_r: float
    ring_base_half_angle: float
    planet_base_half_angle: float
    ring_teeth: int

    @property
    def roll_sum(self) -> float:
        """s_s + s_r of one planet (mod p_b) [m]."""
        return self.planet_base_radius * (2 * self.planet_base_half_angle + self.alpha_s
                                          + self.alpha_r - math.pi)

    @property
    def centre_distance(self) -> float:
        """Planet-ring (and sun-planet) centre distance a [m]."""
        return self.tangent_gap / math.sin(self.alpha_r)

    def tooth_angle(self, tooth: int) -> float:
        """Polar angle of ring tooth ``tooth``'s centre line [rad]."""
        return 2 * math.pi * tooth / self.ring_teeth

    def ring_roll(self, theta, tooth: int = 0) -> np.ndarray:
        """Roll length on the planet of the contact with ring tooth ``tooth`` [m].

        ``theta`` is the planet's polar angle [rad]; the angle to the tooth is wrapped
        to [-pi, pi), so the result is the tooth's own contact (not reduced mod p_b).
        """
        relative = np.asarray(theta, dtype=float) - self.tooth_angle(tooth)
        relative = (relative + math.pi) % (2 * math.pi) - math.pi
        return self.ring_base_radius * (relative + self.alpha_r - self.ring_base_half_angle) \
            - self.tangent_gap

    def sun_roll(self, theta) -> np.ndarray:
        """Roll length on the planet of a sun-mesh contact (mod p_b) [m]."""
        return self.roll_sum - self.ring_roll(theta)


def design_teeth(design) -> dict[str, int]:
    """Tooth counts of the sun, planet and ring of a ``ReducerDesign``."""
    return {"sun": design.sun.teeth, "planet": design.planet.teeth, "ring": design.ring.teeth}


def design_phasing(design) -> MeshPhasing:
    """Mesh phasing of a ``ReducerDesign``'s gears."""
    return gear_phasing(*spur_gears(design))


def gear_phasing(sun, planet, ring) -> MeshPhasing:
    """Mesh phasing of three :class:`hubvib.meshing.gear.SpurGear` (ring internal)."""
    alpha_s = working_pressure_angle(planet, sun)
    alpha_r = working_pressure_angle(planet, ring)
    gap = centre_distance(planet, ring) * math.sin(alpha_r)
    return MeshPhasing(
        base_pitch=planet.base_pitch, ring_base_radius=ring.base_diameter / 2,
        planet_base_radius=planet.base_diameter / 2, tangent_gap=gap,
        alpha_s=alpha_s, alpha_r=alpha_r,
        ring_base_half_angle=float(ring.half_tooth_angle(ring.base_diameter / 2)),
        planet_base_half_angle=float(planet.half_tooth_angle(planet.base_diameter / 2)),
        ring_teeth=ring.teeth)
