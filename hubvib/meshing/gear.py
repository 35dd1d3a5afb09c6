"""Involute spur gear geometry, external and internal (SI units).

Sign convention (ISO 21771, DIN 3960): tooth counts and diameters are
positive numbers here and ``internal`` says which side the material is on.
A positive profile shift ``x`` moves the tool datum line away from the gear
axis for both kinds, so for an internal gear it makes the teeth thinner and
moves its tip circle outwards: ``d_a = d - 2 m (h_a* - x)``.  This is ISO
21771's convention, whose signed formulas (z < 0) give the same circles.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.design.involute import involute, inverse_involute

MIN_TIP_THICKNESS = 0.2  # [module] below this a tooth counts as pointed


class GearGeometryError(ValueError):
    """Gear parameters that give no valid tooth; the message names the parameter."""


def rotation(angle: float) -> np.ndarray:
    """2x2 matrix turning plane vectors counter-clockwise by ``angle`` [rad]."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


@dataclass(frozen=True)
class SpurGear:
    """One spur gear.

    Parameters
    ----------
    teeth : int
        Number of teeth z (>= 6 external, >= 12 internal).
    module : float
        Normal module m [m].
    pressure_angle : float
        Reference pressure angle alpha [rad].
    profile_shift : float
        Profile shift coefficient x [-] (convention above).
    addendum_coefficient, dedendum_coefficient : float
        h_a*, h_f* of the basic rack [-] (ISO 53: 1.0 and 1.25).
    tool_tip_radius_coefficient : float
        rho_fP* of the cutter tip [-] (ISO 53 profile A: 0.38); sets the root fillet.
    face_width : float
        b [m].
    internal : bool
        True for a ring (internal) gear.
    """

    teeth: int
    module: float
    pressure_angle: float = math.radians(20.0)
    profile_shift: float = 0.0
    addendum_coefficient: float = 1.0
    dedendum_coefficient: float = 1.25
    tool_tip_radius_coefficient: float = 0.38
    face_width: float = 0.03
    internal: bool = False

    def __post_init__(self):
        minimum = 12 if self.internal else 6
        if isinstance(self.teeth, bool) or not isinstance(self.teeth, int) or self.teeth < minimum:
            raise GearGeometryError(
                f"teeth = {self.teeth!r}, but it must be an integer >= {minimum} "
                f"for an {'internal' if self.internal else 'external'} gear")
        for name, low, high in (("module", 0.0, math.inf), ("face_width", 0.0, math.inf),
                                ("pressure_angle", math.radians(10), math.radians(35)),
                                ("addendum_coefficient", 0.0, 2.0),
                                ("dedendum_coefficient", 0.0, 2.5),
                                ("tool_tip_radius_coefficient", 0.0, 1.0),
                                ("profile_shift", -2.0, 2.0)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                math.isfinite(value) and low <= value <= high) or (name in ("module", "face_width")
                                                                   and value == 0):
                raise GearGeometryError(f"{name} = {value!r}, but it must lie in [{low}, {high}]"
                                        + (" and be > 0" if name in ("module", "face_width") else ""))
        if self.dedendum_coefficient <= self.addendum_coefficient:
            raise GearGeometryError(
                f"dedendum_coefficient = {self.dedendum_coefficient} must exceed "
                f"addendum_coefficient = {self.addendum_coefficient} (tip clearance)")
        self._check_tooth()

    # circles [m]
    @property
    def reference_diameter(self) -> float:
        return self.teeth * self.module

    @property
    def base_diameter(self) -> float:
        return self.reference_diameter * math.cos(self.pressure_angle)

    @property
    def base_pitch(self) -> float:
        return math.pi * self.module * math.cos(self.pressure_angle)

    @property
    def tip_diameter(self) -> float:
        m, x, ha = self.module, self.profile_shift, self.addendum_coefficient
        if self.internal:
            return self.reference_diameter - 2 * m * (ha - x)
        return self.reference_diameter + 2 * m * (ha + x)

    @property
    def root_diameter(self) -> float:
        m, x, hf = self.module, self.profile_shift, self.dedendum_coefficient
        if self.internal:
            return self.reference_diameter + 2 * m * (hf + x)
        return self.reference_diameter - 2 * m * (hf - x)

    @property
    def reference_tooth_thickness(self) -> float:
        """Circular tooth thickness on the reference circle [m]."""
        sign = -1.0 if self.internal else 1.0
        return self.module * (math.pi / 2 + sign * 2 * self.profile_shift * math.tan(self.pressure_angle))

    def tooth_thickness(self, diameter) -> np.ndarray:
        """Circular tooth thickness on a circle of ``diameter`` >= base diameter [m]."""
        d = np.asarray(diameter, dtype=float)
        if np.any(d < self.base_diameter * (1 - 1e-12)):
            raise GearGeometryError(
                f"diameter {d.min()!r} m is inside the base circle {self.base_diameter!r} m")
        alpha_y = np.arccos(np.minimum(self.base_diameter / d, 1.0))
        sign = -1.0 if self.internal else 1.0
        half = self.reference_tooth_thickness / self.reference_diameter
        return d * (half + sign * (involute(self.pressure_angle) - involute(alpha_y)))

    def half_tooth_angle(self, radius) -> np.ndarray:
        """Angle from the tooth centre line to the flank at ``radius`` [rad]."""
        return self.tooth_thickness(2 * np.asarray(radius)) / (2 * np.asarray(radius))

    def flank(self, radii) -> np.ndarray:
        """Points (x, y) [m] of the flank at angle +psi of the tooth centred on +x."""
        r = np.asarray(radii, dtype=float)
        psi = self.half_tooth_angle(r)
        return np.column_stack([r * np.cos(psi), r * np.sin(psi)])

    def flank_normal(self, radius: float) -> np.ndarray:
        """Unit normal of the ``flank`` at ``radius`` pointing into the space [-].

        The normal is tangent to the base circle (line of action); the base
        tangent point lies at polar angle psi - a_r (external) or psi + a_r (internal).
        """
        p = self.flank([radius])[0]
        a_r = math.acos(min(self.base_diameter / (2 * radius), 1.0))
        theta = math.atan2(p[1], p[0]) + (a_r if self.internal else -a_r)
        return np.array([-math.sin(theta), math.cos(theta)])

    def span_measurement(self, k: int) -> float:
        """Base tangent length W_k over k teeth (external) or k spaces (internal) [m].

        The same expression serves both: a positive shift thickens an external
        tooth and widens an internal gear's space.
        """
        m, a = self.module, self.pressure_angle
        return m * math.cos(a) * (math.pi * (k - 0.5) + self.teeth * float(involute(a))) \
            + 2 * self.profile_shift * m * math.sin(a)

    def _check_tooth(self):
        tip = self.tip_diameter
        if tip <= self.base_diameter * (1 + 1e-9):
            raise GearGeometryError(
                f"profile_shift = {self.profile_shift} gives a tip circle {tip:.6g} m inside the "
                f"base circle {self.base_diameter:.6g} m: no involute flank")
        tip_thickness = float(self.tooth_thickness(tip))
        if tip_thickness < MIN_TIP_THICKNESS * self.module:
            raise GearGeometryError(
                f"profile_shift = {self.profile_shift} gives a pointed tooth: tip thickness "
                f"{tip_thickness / self.module:.3f} m, allowed >= {MIN_TIP_THICKNESS} m")
        if not self.internal:
            h_tool = self.dedendum_coefficient - self.tool_tip_radius_coefficient * (
                1 - math.sin(self.pressure_angle))
            x_min = h_tool - self.teeth * math.sin(self.pressure_angle) ** 2 / 2
            if self.profile_shift < x_min - 1e-12:
                raise GearGeometryError(
                    f"profile_shift = {self.profile_shift} undercuts the {self.teeth}-tooth gear; "
                    f"allowed >= {x_min:.4f} (ISO 21771 undercut limit)")


def working_pressure_angle(pinion: SpurGear, gear: SpurGear) -> float:
    """Working pressure angle of a zero-backlash pair [rad] (ISO 21771).

    External pair: inv a_w = 2 tan a (x1 + x2) / (z1 + z2) + inv a;
    internal pair (``gear.internal``): inv a_w = 2 tan a (x2 - x1) / (z2 - z1) + inv a.
    """
    a = pinion.pressure_angle
    if gear.internal:
        ratio = (gear.profile_shift - pinion.profile_shift) / (gear.teeth - pinion.teeth)
    else:
        ratio = (pinion.profile_shift + gear.profile_shift) / (pinion.teeth + gear.teeth)
    return inverse_involute(2 * math.tan(a) * ratio + float(involute(a)))


def centre_distance(pinion: SpurGear, gear: SpurGear) -> float:
    """Working centre distance of a zero-backlash pair [m]."""
    a_w = working_pressure_angle(pinion, gear)
    z = gear.teeth - pinion.teeth if gear.internal else gear.teeth + pinion.teeth
    return z * pinion.module / 2 * math.cos(pinion.pressure_angle) / math.cos(a_w)
