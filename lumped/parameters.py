"""Parameters of the lumped planetary model, SI units throughout."""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from hubvib.design.fields import DIAMETER_FIELDS, MASS_FIELDS, STIFFNESS_FIELDS
from hubvib.foundation.errors import InputError

ANGLE_TOLERANCE = 1e-9  # [rad] two planets closer than this are the same planet
#: most planets a stage may have: real stages have 3..12; the eigensolver's cost grows as
#: N^3 (one shift sweep stays well under a second at N = 32)
MAX_PLANETS = 32
#: largest |planet angle| [rad]: one turn either way (a float far beyond it no longer
#: resolves ANGLE_TOLERANCE, e.g. 1e300 rad)
MAX_ANGLE = 2 * math.pi


class ParameterError(InputError):
    """A parameter is outside its allowed range; the message names it."""


@dataclass(frozen=True)
class PlanetaryParameters:
    """One planetary stage: sun ``s``, carrier ``c``, ring ``r``, planets ``p``.

    Parameters
    ----------
    m_s, m_c, m_r, m_p : float
        Masses of sun, carrier, ring and of each planet [kg].
    mu_s, mu_c, mu_r, mu_p : float
        Reduced masses ``J / r_b**2`` of the rotations, taken along the base
        circle of each member [kg].
    d_s, d_c, d_r, d_p : float
        Base-circle diameters [m] (the carrier's is the planet-centre circle
        scaled as in the paper).  Only used to convert rotations and torques.
    c_sp, c_rp : float
        Sun-planet and ring-planet mesh stiffness along the line of action [N/m].
    c_p, c_c, c_r : float
        Planet, carrier and ring bearing (support) stiffness [N/m].
    c_s : float
        Sun bearing stiffness [N/m]; 0 is a floating sun (the paper's case).
    c_su, c_cu, c_ru : float
        Reduced torsional stiffness of sun, carrier and ring [N/m]:
        torsional stiffness [N m/rad] divided by the base radius squared.
    alpha_s, alpha_r : float
        Working pressure angle of the sun-planet and ring-planet mesh [rad].
    theta : tuple of float
        Angular position of each planet centre from the x axis [rad], within
        one turn either way (``|theta| <= 2 pi``); its length is the number
        of planets, 1 <= N <= ``MAX_PLANETS``.
    c_rp_factors : tuple of float
        Factor on ``c_rp`` for each planet's ring mesh (one per planet, > 0),
        e.g. below 1 for the planet in mesh with a cracked ring tooth; empty
        (the default) means 1 for every planet.
    """

    m_s: float
    m_c: float
    m_r: float
    m_p: float
    mu_s: float
    mu_c: float
    mu_r: float
    mu_p: float
    d_s: float
    d_c: float
    d_r: float
    d_p: float
    c_sp: float
    c_rp: float
    c_p: float
    c_c: float
    c_r: float
    c_su: float
    c_cu: float
    c_ru: float
    alpha_s: float
    alpha_r: float
    theta: tuple[float, ...]
    c_s: float = 0.0
    c_rp_factors: tuple[float, ...] = ()

    def __post_init__(self):
        for name in STIFFNESS_FIELDS:
            _check_number(name, getattr(self, name), lower=0.0, closed=True)
        for name in MASS_FIELDS + DIAMETER_FIELDS:
            _check_number(name, getattr(self, name), lower=0.0, closed=False)
        for name in ("alpha_s", "alpha_r"):
            value = getattr(self, name)
            _check_number(name, value, lower=0.0, closed=False)
            if value >= math.pi / 2:
                raise ParameterError(f"{name} = {value!r} rad, but it must lie in (0, pi/2)")
        _check_planet_angles(self.theta)
        object.__setattr__(self, "theta", tuple(float(t) for t in self.theta))
        _check_factors(self.c_rp_factors, len(self.theta))
        object.__setattr__(self, "c_rp_factors", tuple(float(f) for f in self.c_rp_factors))

    @property
    def n_planets(self) -> int:
        """Number of planets N."""
        return len(self.theta)

    @property
    def n_dof(self) -> int:
        """Degrees of freedom, 9 + 3 N."""
        return 9 + 3 * self.n_planets

    def replace(self, **changes) -> "PlanetaryParameters":
        """Copy with some fields changed (validated like the original)."""
        unknown = set(changes) - {f.name for f in dataclasses.fields(self)}
        if unknown:
            raise ParameterError(
                f"unknown parameter(s) {sorted(unknown)}; known: {sorted(field_names())}"
            )
        return dataclasses.replace(self, **changes)

    def equally_spaced(self, tolerance: float = 1e-12) -> bool:
        """True when the planets are at theta_1 + 2 pi (i - 1) / N."""
        n = self.n_planets
        ideal = [self.theta[0] + 2 * math.pi * i / n for i in range(n)]
        return all(abs(_wrap(a - b)) <= tolerance for a, b in zip(self.theta, ideal))

    def to_dict(self) -> dict:
        """Plain dict (tuples as lists) for JSON/TOML output."""
        data = dataclasses.asdict(self)
        data["theta"] = list(self.theta)
        data["c_rp_factors"] = list(self.c_rp_factors)
        return data


def field_names() -> tuple[str, ...]:
    """Names of all parameters, as accepted by ``replace`` and ``--set``."""
    return tuple(f.name for f in dataclasses.fields(PlanetaryParameters))


def scalar_field_names() -> tuple[str, ...]:
    """Parameters that are one number each (``theta``, ``c_rp_factors`` are per planet)."""
    return tuple(n for n in field_names() if n not in ("theta", "c_rp_factors"))


def equally_spaced_angles(n_planets: int, theta_1: float = 0.0) -> tuple[float, ...]:
    """Planet angles theta_i = theta_1 + 2 pi (i - 1) / N [rad], 1 <= N <= MAX_PLANETS."""
    if isinstance(n_planets, bool) or not isinstance(n_planets, int) or not (
            1 <= n_planets <= MAX_PLANETS):
        raise ParameterError(f"n_planets = {n_planets!r}, but it must be an integer "
                             f"1..{MAX_PLANETS}")
    return tuple(theta_1 + 2 * math.pi * i / n_planets for i in range(n_planets))


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def _check_number(name, value, lower, closed):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(f"{name} = {value!r}, but it must be a real number")
    if not math.isfinite(value):
        raise ParameterError(f"{name} = {value!r}, but it must be finite")
    if value < lower or (value == lower and not closed):
        bound = f">= {lower}" if closed else f"> {lower}"
        raise ParameterError(f"{name} = {value!r}, but it must be {bound}")


def _check_factors(factors, n_planets):
    if not isinstance(factors, (tuple, list)) or len(factors) not in (0, n_planets):
        raise ParameterError(f"c_rp_factors = {factors!r}, but it must be empty or hold one "
                             f"factor per planet ({n_planets})")
    for i, f in enumerate(factors):
        _check_number(f"c_rp_factors[{i}]", f, lower=0.0, closed=False)


def _check_planet_angles(theta):
    if not isinstance(theta, (tuple, list)):
        raise ParameterError(
            f"theta = {theta!r}, but it must be a sequence of planet angles [rad], one per planet"
        )
    if len(theta) < 1:
        raise ParameterError("theta has 0 planet angles, but N >= 1 planets are required")
    if len(theta) > MAX_PLANETS:
        raise ParameterError(f"theta has {len(theta)} planet angles, but at most "
                             f"N = {MAX_PLANETS} planets are allowed")
    for i, t in enumerate(theta):
        _check_number(f"theta[{i}]", t, lower=-math.inf, closed=True)
        if abs(t) > MAX_ANGLE:
            raise ParameterError(f"theta[{i}] = {t!r} rad, but planet angles must lie in "
                                 "[-2 pi, 2 pi] (one turn either way)")
    # the closest two planets are neighbours in angular order: N log N, not N^2 pairs
    order = sorted(range(len(theta)), key=lambda k: theta[k] % (2 * math.pi))
    for a, b in zip(order, order[1:] + order[:1]):
        if a != b and abs(_wrap(theta[a] - theta[b])) <= ANGLE_TOLERANCE:
            j, i = sorted((a, b))
            raise ParameterError(
                f"theta[{j}] = {theta[j]!r} and theta[{i}] = {theta[i]!r} rad put two planets "
                f"at the same place; planet angles must differ by more than {ANGLE_TOLERANCE} rad"
            )
