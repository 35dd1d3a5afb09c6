"""Path of contact and mesh stiffness over the mesh cycle of a spur pair (SI units).

A contact point is given by its roll length ``s`` on the first gear (distance
along the line of action from that gear's base tangent point).  The pair
stiffness at ``s`` is ``1 / (q_1(r_1) + q_2(r_2) + q_H)`` with the tooth
compliances at the two contact radii; the mesh stiffness sums the pairs in
contact, ``s + k p_b`` on the path (this is the load sharing of a rigid
transmission error: every pair deflects the same).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from hubvib.meshing.gear import GearGeometryError, centre_distance, working_pressure_angle
from hubvib.meshing.ring_gear import ToothedBody

CYCLE_POINTS = 400  # contact positions per base pitch


@dataclass(frozen=True)
class GearPair:
    """Two bodies in mesh; ``first`` external, ``second`` external or internal."""

    first: ToothedBody
    second: ToothedBody

    def __post_init__(self):
        if self.first.gear.internal:
            raise GearGeometryError("GearPair.first must be an external gear")
        if abs(self.first.gear.module - self.second.gear.module) > 1e-12:
            raise GearGeometryError("GearPair: the two gears must have the same module")
        for body, name in ((self.first, "first"), (self.second, "second")):
            form = self.roll_length(body, body.profile.form_radius)
            own = self.path if body is self.first else self.to_second_range()
            inside = form >= max(own) - 1e-12 if body.gear.internal else form <= min(own) + 1e-12
            if not inside:
                raise GearGeometryError(
                    f"GearPair.{name}: the path of contact runs below the form circle "
                    f"(r = {body.profile.form_radius:.6g} m): tip interference")

    @property
    def working_pressure_angle(self) -> float:
        return working_pressure_angle(self.first.gear, self.second.gear)

    @property
    def base_pitch(self) -> float:
        return self.first.gear.base_pitch

    @property
    def _tangent_gap(self) -> float:
        """Distance between the two base tangent points on the line of action [m]."""
        return centre_distance(self.first.gear, self.second.gear) * math.sin(
            self.working_pressure_angle)

    @staticmethod
    def roll_length(body: ToothedBody, radius: float) -> float:
        rb = body.gear.base_diameter / 2
        return math.sqrt(max(radius ** 2 - rb ** 2, 0.0))

    def second_roll(self, s1):
        """Roll length on the second gear for roll length ``s1`` on the first [m]."""
        if self.second.gear.internal:
            return np.asarray(s1) + self._tangent_gap
        return self._tangent_gap - np.asarray(s1)

    @property
    def path(self) -> tuple[float, float]:
        """(start, end) of contact as roll lengths on the first gear [m]."""
        tip1 = self.roll_length(self.first, self.first.profile.tip_radius)
        tip2 = self.roll_length(self.second, self.second.profile.tip_radius)
        start = tip2 - self._tangent_gap if self.second.gear.internal else self._tangent_gap - tip2
        return start, tip1

    def to_second_range(self) -> tuple[float, float]:
        start, end = self.path
        return tuple(sorted(float(v) for v in self.second_roll([start, end])))

    @property
    def contact_ratio(self) -> float:
        start, end = self.path
        return (end - start) / self.base_pitch

    def radii(self, s1) -> tuple[np.ndarray, np.ndarray]:
        """Contact radii on the first and the second gear [m]."""
        rb1, rb2 = self.first.gear.base_diameter / 2, self.second.gear.base_diameter / 2
        return np.hypot(rb1, s1), np.hypot(rb2, self.second_roll(s1))


@dataclass(frozen=True)
class MeshCycle:
    """Mesh stiffness over one base pitch [N/m] at roll lengths ``s`` [m]."""

    s: np.ndarray
    stiffness: np.ndarray
    pairs: np.ndarray

    @property
    def mean(self) -> float:
        return float(np.mean(self.stiffness))

    @property
    def single_pair_max(self) -> float:
        single = self.stiffness[self.pairs == 1]
        return float(single.max()) if single.size else float("nan")


Compliance = Callable[[np.ndarray], np.ndarray]


def pair_stiffness(pair: GearPair, q_first: Compliance, q_second: Compliance, q_contact: float,
                   s1) -> np.ndarray:
    """Stiffness of one tooth pair at roll lengths ``s1`` [N/m]."""
    r1, r2 = pair.radii(s1)
    return 1.0 / (q_first(r1) + q_second(r2) + q_contact)


def mesh_cycle(pair: GearPair, q_first: Compliance, q_second: Compliance, q_contact: float,
               points: int = CYCLE_POINTS, marked_pair_compliance: Compliance | None = None,
               ) -> MeshCycle:
    """Mesh stiffness over one base pitch; the pairs share the load.

    With ``marked_pair_compliance`` (a damaged tooth of the second gear) the
    cycle runs over the whole engagement of that tooth: roll lengths from
    the start to the end of its contact plus one pitch, the marked tooth
    being the pair that enters at the start.
    """
    start, end = pair.path
    pb = pair.base_pitch
    if marked_pair_compliance is None:
        s = start + pb * np.arange(points) / points
    else:
        s = np.linspace(start - pb, end + pb, int(points * (end - start + 2 * pb) / pb))
    total, count = np.zeros_like(s), np.zeros(s.shape, dtype=int)
    reach = int(math.ceil((s.max() - s.min() + end - start) / pb)) + 1
    for k in range(-reach, reach + 1):
        sk = s + k * pb
        inside = (sk >= start) & (sk <= end)
        if not inside.any():
            continue
        q2 = marked_pair_compliance if (marked_pair_compliance is not None and k == 0) else q_second
        total[inside] += pair_stiffness(pair, q_first, q2, q_contact, sk[inside])
        count[inside] += 1
    if np.any(count == 0):
        raise GearGeometryError(f"contact ratio {pair.contact_ratio:.3f} < 1: the mesh loses "
                                "contact during the cycle")
    return MeshCycle(s, total, count)
