"""Tooth stiffness by ISO 6336-1:2019 method B, clause 9 (spur gears, SI units).

``q' = C1 + C2/z_n1 + C3/z_n2 + C4 x1 + C5 x1/z_n1 + C6 x2 + C7 x2/z_n2 + C8 x1^2
+ C9 x2^2`` [mm um/N]; ``c'_th = 1/q'``; ``c' = c'_th C_M C_R C_B cos(beta)``
with C_M = 0.8 (theoretical to measured) and C_R = 1 (solid wheel bodies);
``C_B = [1 + 0.5 (1.2 - h_fP/m)] [1 - 0.02 (20 deg - alpha_n)]``;
``c_gamma_alpha = c' (0.75 eps_alpha + 0.25)``.  For an internal gear
``z_n2 = infinity``.  The standard states the fit for x1 >= x2 and
-0.5 <= x1 + x2 <= 2; ``in_range`` says whether the pair is inside.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from hubvib.meshing.gear import SpurGear

C = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
C_M = 0.8
C_R = 1.0
PER_MM_UM = 1e9  # 1 N/(mm um) in N/m^2


@dataclass(frozen=True)
class IsoStiffness:
    """Single stiffness c' and mesh stiffness c_gamma_alpha per face width [N/m^2]."""

    single: float
    mesh: float
    in_range: bool

    def per_face_width(self, b: float) -> tuple[float, float]:
        """(c' b, c_gamma b) [N/m]."""
        return self.single * b, self.mesh * b


def iso_stiffness(pinion: SpurGear, wheel: SpurGear, contact_ratio: float) -> IsoStiffness:
    """ISO 6336-1 c' and c_gamma_alpha of a spur pair (``pinion`` has fewer teeth)."""
    x1, x2 = pinion.profile_shift, wheel.profile_shift
    z1 = pinion.teeth
    inv_z2 = 0.0 if wheel.internal else 1.0 / wheel.teeth
    c1, c2, c3, c4, c5, c6, c7, c8, c9 = C
    q = (c1 + c2 / z1 + c3 * inv_z2 + c4 * x1 + c5 * x1 / z1 + c6 * x2 + c7 * x2 * inv_z2
         + c8 * x1 ** 2 + c9 * x2 ** 2)
    h_fp = pinion.dedendum_coefficient
    c_b = (1 + 0.5 * (1.2 - h_fp)) * (1 - 0.02 * (20.0 - math.degrees(pinion.pressure_angle)))
    single = C_M * C_R * c_b / q * PER_MM_UM
    mesh = single * (0.75 * contact_ratio + 0.25)
    return IsoStiffness(single, mesh, x1 >= x2 and -0.5 <= x1 + x2 <= 2.0)
