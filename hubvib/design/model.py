"""The reducer design: one frozen object from which geometry, FE and the lumped model follow (SI).

Every length is in metres, every angle in radians, torque in N m, stiffness
in N/m, mass in kg.  Design files (TOML) use the same units except where a key
says ``_deg``; ``hubvib.design.parse`` converts at that edge.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from hubvib.foundation.errors import InputError


class DesignError(InputError):
    """The design is invalid or cannot assemble; the message names the key and the range."""


@dataclass(frozen=True)
class GearSpec:
    """One gear of the stage.

    Parameters
    ----------
    teeth : int
        Number of teeth z.
    shift : float
        Profile shift coefficient x [-] (ISO 21771; for the ring, positive moves the
        toothing outwards).
    bore : float or None
        Sun or planet: diameter of the shaft or bearing seat [m]; ``None`` = 0.4 x the
        root diameter (ASSUMED, stated by ``hubvib design check``).
    """

    teeth: int
    shift: float = 0.0
    bore: float | None = None


@dataclass(frozen=True)
class RimSpec:
    """The ring's rim: give its thickness below the root circle or the ring's mass.

    Parameters
    ----------
    thickness : float or None
        Radial thickness from the root circle to the outer surface [m].
    mass : float or None
        Mass of the whole ring (teeth and rim) [kg]; sets the outer diameter.
    """

    thickness: float | None = None
    mass: float | None = None


@dataclass(frozen=True)
class SupportSpec:
    """Where the hub holds the ring's outer surface: ``count`` clamped arcs (0 = all of it).

    Parameters
    ----------
    count : int
    arc : float
        Angular width of each arc [rad].
    first : float
        Polar angle of the middle of the first arc [rad].
    """

    count: int = 6
    arc: float = math.radians(20.0)
    first: float = 0.0


@dataclass(frozen=True)
class MaterialSpec:
    """Steel by default: E [Pa], nu [-], density [kg/m^3]."""

    E: float = 210e9
    nu: float = 0.3
    density: float = 7850.0


@dataclass(frozen=True)
class BearingSpec:
    """A radial roller bearing for Palmgren's line-contact stiffness.

    Parameters
    ----------
    rollers : int
        Number of rollers (all rows).
    roller_length : float
        Effective roller length [m].
    load : float or None
        Radial load [N]; ``None`` for the planet bearing = the mesh forces of the
        design's sun torque (equal load sharing).
    """

    rollers: int
    roller_length: float
    load: float | None = None


@dataclass(frozen=True)
class ReducerDesign:
    """A single-stage planetary reducer with a fixed ring (the hub reducer).

    Parameters
    ----------
    name : str
    n_planets : int
    module : float
        [m]
    pressure_angle : float
        Reference pressure angle of the basic rack [rad].
    face_width : float
        [m]
    sun, planet, ring : GearSpec
    rim : RimSpec
    planet_angles : tuple of float or None
        Planet-centre angles [rad]; ``None`` = equally spaced from 0.
    supports : SupportSpec
    material : MaterialSpec
    sun_torque : float
        Operating torque on the sun [N m] (bearing loads, FE load renders).
    planet_bearing, carrier_bearing : BearingSpec or None
        For c_p and c_c; ``None``: the lumped table must give them.
    lumped : tuple of (str, float)
        Lumped-model fields that the geometry does not give (``m_c``, ``c_ru`` ...) or
        that the design fixes by decision (a published table's value), SI; see
        ``hubvib.reducer.stages.lumped_parameters``.
    notes : tuple of str
        Where each ASSUMED value comes from, printed by ``hubvib design check``.
    """

    name: str
    n_planets: int
    module: float
    pressure_angle: float
    face_width: float
    sun: GearSpec
    planet: GearSpec
    ring: GearSpec
    rim: RimSpec
    planet_angles: tuple[float, ...] | None = None
    supports: SupportSpec = SupportSpec()
    material: MaterialSpec = MaterialSpec()
    sun_torque: float = 1000.0
    planet_bearing: BearingSpec | None = None
    carrier_bearing: BearingSpec | None = None
    lumped: tuple[tuple[str, float], ...] = ()
    notes: tuple[str, ...] = ()

    def __post_init__(self):
        if isinstance(self.lumped, dict):
            object.__setattr__(self, "lumped", tuple(sorted(self.lumped.items())))

    @property
    def lumped_fields(self) -> dict[str, float]:
        """The ``lumped`` table as a dict."""
        return dict(self.lumped)

    @property
    def angles(self) -> tuple[float, ...]:
        """Planet-centre angles [rad]."""
        if self.planet_angles is not None:
            return self.planet_angles
        return tuple(2 * math.pi * i / self.n_planets for i in range(self.n_planets))

    @property
    def equally_spaced(self) -> bool:
        step = 2 * math.pi / self.n_planets
        return all(abs(math.remainder(a - i * step - self.angles[0], 2 * math.pi)) < 1e-9
                   for i, a in enumerate(self.angles))

    def fingerprint(self) -> dict:
        """Every field that decides an FE value, as plain data (for cache keys)."""
        data = asdict(self)
        data.pop("notes")
        data["lumped"] = self.lumped_fields
        return data
