"""Track geometry of a ball/roller planetary gear from its lift angle (seed 001, eqs. 11-13).

The fixed link's multi-period track is a circle of mean radius ``R`` offset by the amplitude
``A`` in the angle ``z2 phi`` (Kapitonov 2024, "Improving the efficiency of ball and roller gears
by optimizing geometrics of engagement parts", Transport Engineering 3:20-30).

* eq. (11): ``alpha2 = arctan(z2 tan alpha1)``
* eq. (12), read so that it is dimensionally right and reproduces the paper's table (the print
  puts the ``- 1`` outside the root's factor): ``R = d_c z2 (sqrt(1 + tan^2 alpha2) - 1) /
  (pi tan alpha2 - 2 z2 sin alpha1)``
* eq. (13): ``A = R sin alpha1``
"""
from __future__ import annotations

import math
from dataclasses import dataclass

#: Satellite diameters of the paper's table [m]: 15 mm balls, 10 mm rollers.
SATELLITE_DIAMETER_M = {"ball": 0.015, "roller": 0.010}


@dataclass(frozen=True)
class TrackGeometry:
    """Mean radius and amplitude of the tracks for one satellite size.

    Attributes
    ----------
    satellite : str
        ``"ball"`` or ``"roller"`` (a label; only the diameter enters).
    satellite_diameter_m : float
        Satellite diameter d_c [m].
    mean_radius_m : float
        Mean track radius R, eq. (12) [m].
    amplitude_m : float
        Track amplitude A, eq. (13) [m].
    """

    satellite: str
    satellite_diameter_m: float
    mean_radius_m: float
    amplitude_m: float

    def to_dict(self) -> dict:
        return {"satellite": self.satellite, "satellite_diameter_m": self.satellite_diameter_m,
                "mean_radius_m": self.mean_radius_m, "amplitude_m": self.amplitude_m}


def check_alpha1(alpha1_rad: float) -> float:
    """Return ``alpha1_rad`` if it lies in (0, 90) deg, else raise ValueError."""
    if not (math.isfinite(alpha1_rad) and 0.0 < alpha1_rad < math.pi / 2):
        raise ValueError(f"alpha1 (--alpha1-deg) must be in (0, 90) deg, "
                         f"got {math.degrees(alpha1_rad):g} deg")
    return float(alpha1_rad)


def check_diameter(satellite: str, diameter_m: float) -> float:
    """Return the satellite diameter [m] if finite and > 0, else raise ValueError."""
    if not (math.isfinite(diameter_m) and diameter_m > 0.0):
        raise ValueError(f"{satellite} satellite diameter d_c (--{satellite}-diameter-mm) must "
                         f"be > 0 mm, got {diameter_m * 1e3:g} mm")
    return float(diameter_m)


def fixed_track_lift_angle(alpha1_rad: float, z2: int) -> float:
    """Lift angle of the fixed multi-period track, eq. (11) [rad].

    Parameters
    ----------
    alpha1_rad : float
        Lift angle of the driving single-period track [rad], in (0, pi/2).
    z2 : int
        Number of periods of the fixed track (``z2 = i - 1``).
    """
    return math.atan(z2 * math.tan(check_alpha1(alpha1_rad)))


def track_geometry(alpha1_rad: float, z2: int, satellite_diameter_m: float,
                   satellite: str = "ball") -> TrackGeometry:
    """Mean radius R (eq. 12) and amplitude A (eq. 13) for a satellite of diameter d_c.

    The denominator ``pi tan alpha2 - 2 z2 sin alpha1 = z2 (pi tan alpha1 - 2 sin alpha1)`` is
    positive for every alpha1 in (0, 90) deg, so R > 0 whenever d_c > 0.

    Examples
    --------
    >>> g = track_geometry(math.radians(9), 4, 0.015)
    >>> round(g.mean_radius_m * 1e3, 5), round(g.amplitude_m * 1e3, 5)   # paper: 14.92564, 2.334885
    (14.92564, 2.33488)
    """
    d_c = check_diameter(satellite, satellite_diameter_m)
    alpha2 = fixed_track_lift_angle(alpha1_rad, z2)
    tan2 = math.tan(alpha2)
    radius = d_c * z2 * (math.sqrt(1.0 + tan2 * tan2) - 1.0) / (
        math.pi * tan2 - 2.0 * z2 * math.sin(alpha1_rad))
    return TrackGeometry(satellite, d_c, radius, radius * math.sin(alpha1_rad))
