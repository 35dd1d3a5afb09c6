"""Analytical tooth compliance by the potential-energy method (SI units).

The tooth is a cantilever along its centre line with the exact cross-section
of the meshed profile (involute and fillet, ``ToothProfile``), clamped at the
chord through the fillet ends on the root circle.  For a unit force along the
line of action at a flank point the compliance [m/N] is ``2 U / F^2``, with

- bending ``int M^2 / (E I)``, shear ``int 1.2 V^2 / (G A)`` and axial
  ``int N^2 / (E A)`` along the centre line (Yang & Lin 1987; Tian 2004;
  Chen & Shao 2011, with the actual section instead of the straight-line
  approximation below the base circle);
- fillet foundation (body) ``cos^2 a_m / (E b) [L* (u_f/S_f)^2 + M* (u_f/S_f)
  + P* (1 + Q* tan^2 a_m)]`` with the polynomial coefficients of Sainsot,
  Velex & Duverger, J. Mech. Des. 126 (2004) 748, Table 1;
- Hertzian contact of the pair ``1 / k_h``, ``k_h = pi E b / (4 (1 - nu^2))``
  (Yang & Lin 1987: load-independent, both gears of the same material).

Plane stress (E, not E / (1 - nu^2)), as the FE model of the face width.
The tooth frame: tooth 0 centred on +x, the loaded flank on the +psi side.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.meshing.ring_gear import RingGear, ToothedBody

from .material import Material

#: Sainsot et al. (2004) Table 1: rows L*, M*, P*, Q*; columns A..F of
#: X* = A / theta_f^2 + B h_fi^2 + C h_fi / theta_f + D / theta_f + E h_fi + F.
SAINSOT = np.array([
    [-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045],
    [60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086],
    [-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236],
    [-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904],
])
SHEAR_FACTOR = 1.2  # rectangular section
PROFILE_POINTS = 600
BEAM_POINTS = 2001


@dataclass(frozen=True)
class ToothCompliance:
    """Compliance parts [m/N] of one tooth at one load point."""

    bending: float
    shear: float
    axial: float
    foundation: float

    @property
    def total(self) -> float:
        return self.bending + self.shear + self.axial + self.foundation


def hertz_compliance(face_width: float, material: Material = Material()) -> float:
    """1 / k_h, k_h = pi E b / (4 (1 - nu^2)) [m/N] (Yang & Lin 1987)."""
    return 4 * (1 - material.nu ** 2) / (math.pi * material.E * face_width)


def load_point(body: ToothedBody, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """Flank point [m] of tooth 0 at ``radius`` and the unit force into the tooth there."""
    gear = body.gear
    return gear.flank([radius])[0], -gear.flank_normal(radius)


def _half_section(body: ToothedBody) -> tuple[np.ndarray, np.ndarray, float]:
    """Distance from the clamped chord along the axis, half thickness there [m], and the
    axis sign (+1 external: teeth point outwards)."""
    prof, gear = body.profile, body.gear
    involute = gear.flank(np.linspace(prof.tip_radius, prof.form_radius, PROFILE_POINTS))
    fillet = prof.fillet_points(np.linspace(1.0, 0.0, PROFILE_POINTS))
    points = np.vstack([involute, fillet[1:]])
    sign = -1.0 if gear.internal else 1.0
    xi = sign * (points[:, 0] - points[-1, 0])
    order = np.argsort(xi)
    xi, half = xi[order], points[order, 1]
    if np.any(np.diff(xi) <= 0):
        keep = np.concatenate([[True], np.diff(xi) > 0])
        xi, half = xi[keep], half[keep]
    return xi, half, sign


def beam_compliance(body: ToothedBody, radius: float, material: Material = Material(),
                    foundation_ratio: float | None = None) -> ToothCompliance:
    """Potential-energy compliance of tooth 0 loaded at the flank ``radius`` [m/N].

    ``foundation_ratio`` is Sainsot's h_fi = r_f / r_int; default the root
    radius over the held radius (bore of a gear body; for a ring the outer
    radius over the root radius, an extrapolation of the fitted range).
    """
    from scipy.integrate import simpson

    prof, gear = body.profile, body.gear
    b, E, G = gear.face_width, material.E, material.shear_modulus
    p, d = load_point(body, radius)
    xi_table, half_table, sign = _half_section(body)
    x0 = prof.fillet_points(0.0)[0][0]
    xi_load = sign * (p[0] - x0)
    xi = np.linspace(0.0, xi_load, BEAM_POINTS)
    half = np.interp(xi, xi_table, half_table)
    area, inertia = 2 * half * b, b * (2 * half) ** 3 / 12
    axis = np.array([sign, 0.0])
    centre_x = x0 + sign * xi
    moment = (p[0] - centre_x) * d[1] - p[1] * d[0]
    shear = d[1]
    normal = d @ axis
    bending = simpson(moment ** 2 / (E * inertia), x=xi)
    shear_part = simpson(SHEAR_FACTOR * shear ** 2 / (G * area), x=xi)
    axial = simpson(normal ** 2 / (E * area), x=xi)

    r_f = prof.root_radius
    theta_f = prof.root_land_angle
    if foundation_ratio is None:
        foundation_ratio = (body.outer_radius / r_f if isinstance(body, RingGear)
                            else r_f / body.held_radius)
    coeff = SAINSOT @ np.array([1 / theta_f ** 2, foundation_ratio ** 2,
                                foundation_ratio / theta_f, 1 / theta_f, foundation_ratio, 1.0])
    l_star, m_star, p_star, q_star = coeff
    x_cross = p[0] - p[1] * d[0] / d[1]  # load line meets the centre line
    u_f = sign * (x_cross - r_f)
    s_f = 2 * r_f * theta_f
    cos_m, tan_m = abs(d[1]), abs(d[0] / d[1])
    foundation = cos_m ** 2 / (E * b) * (l_star * (u_f / s_f) ** 2 + m_star * (u_f / s_f)
                                          + p_star * (1 + q_star * tan_m ** 2))
    return ToothCompliance(float(bending), float(shear_part), float(axial), float(foundation))
