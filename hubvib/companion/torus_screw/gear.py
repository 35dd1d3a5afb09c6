"""Forces on a composite roller and efficiency of a planetary torus screw gear (seed 002).

Prudnikov & Bodunova 2021, "Distribution of forces between units of planetary torus screw gear"
(Belarusian-Russian University). One composite roller carries the load between the driving
link's spiral track (reaction N1, lift angle alpha1), the fixed link's grooves (N3, alpha3) and
the output shaft (S2', S2'', M42). Eqs. (14)-(18) are linear in ``X = [N1, N3, S2', S2'', M42]``;
eq. (19) ``X = A^-1 B`` with ``B = [0, -N2, -Phi4, 0, -M_U]``, ``N2 = M2 / (n_p R2)``; eq. (20)
``M1 = n_p N1 cos(gamma) sin(alpha1) R2`` and ``eta = M2 / (M1 u)``.

The print has two sign slips that contradict its own eqs. (9) and (11): the N3 term of (14)
reads ``+cos(gamma) cos(alpha3)`` and the N3 term of (16) reads ``-sin(gamma) sin(phi2)``. The
consistent forms ``-cos(gamma) cos(alpha3)`` and ``+sin(gamma) sin(phi2)`` are used here
(``printed_signs=True`` rebuilds the printed system, to show that the fix matters). S2', S2''
are signed here; the paper prints magnitudes.

The finger's reaction leans by ``gamma = 0`` for cylindrical fingers and
``gamma = arctan(S4 / (2 r4))`` for spherical ones (S4 the height of the finger's contact part).
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

#: Finger shapes of the paper.
FINGER_KINDS = ("cylindrical", "spherical")

#: Lift angles at phi2 = 54 deg back-solved from the paper's cylindrical N1, N3 [deg]; the
#: paper does not print them (the spiral radii r, R of its eqs. 1-5 are missing).
PAPER_ALPHA1_DEG = 6.804
PAPER_ALPHA3_DEG = 81.945
#: Roller rotation angle of the paper's worked example [deg].
PAPER_PHI2_DEG = 54.0
#: Height S4 of the spherical finger's contact part [m]: not printed; S4 = 2 r4 (gamma = 45
#: deg) reproduces the paper's spherical N3 (a fit gives gamma = 45.006 deg).
PAPER_FINGER_SPACING_M = 0.010

#: Largest row-scaled condition number of A accepted before the system counts as singular.
MAX_CONDITION = 1e12
#: Highest input speed [min^-1] (a physical bound: 1e300 overflowed Phi4 = m4 omega2^2 R2)
MAX_INPUT_RPM = 1e6


@dataclass(frozen=True)
class TorusScrewGear:
    """Gear data; defaults are the paper's example. SI units.

    Attributes
    ----------
    output_torque_n_m : float
        Torque on the output shaft M2 [N m] (150).
    rollers : int
        Number of composite rollers n_p (7).
    ratio : float
        Gear ratio u (48 = Z1 Z3 = 4 x 12).
    carrier_radius_m : float
        R2, gear axis to the centre of the torus generating circle [m] (0.025).
    roller_length_m : float
        Composite roller length l4 [m] (0.028).
    finger_radius_m : float
        r4, finger radius at the middle of the contact line [m] (0.005).
    finger_journal_radius_m : float
        r0, radius of the finger's journal in the roller [m] (0.0035).
    roller_journal_radius_m : float
        r42, radius of the roller's journals on the output shaft [m] (0.005).
    roller_mass_kg : float
        m4 [kg] (0.075), for the centrifugal force Phi4.
    rolling_friction : float
        delta_r, finger rolling on the tracks [-] (0.002).
    sliding_friction : float
        delta_c, finger and roller journals [-] (0.05).
    """

    output_torque_n_m: float = 150.0
    rollers: int = 7
    ratio: float = 48.0
    carrier_radius_m: float = 0.025
    roller_length_m: float = 0.028
    finger_radius_m: float = 0.005
    finger_journal_radius_m: float = 0.0035
    roller_journal_radius_m: float = 0.005
    roller_mass_kg: float = 0.075
    rolling_friction: float = 0.002
    sliding_friction: float = 0.05

    def __post_init__(self):
        _positive("output torque M2 (--torque)", self.output_torque_n_m, "N m")
        if not (math.isfinite(self.rollers) and self.rollers >= 1
                and float(self.rollers).is_integer()):
            raise ValueError(f"roller count n_p (--rollers) must be a whole number >= 1, "
                             f"got {self.rollers:g}")
        object.__setattr__(self, "rollers", int(self.rollers))
        _positive("gear ratio u (--ratio)", self.ratio, "")
        for name, flag in (("carrier_radius_m", "carrier-radius"),
                           ("roller_length_m", "roller-length"),
                           ("finger_radius_m", "finger-radius"),
                           ("finger_journal_radius_m", "finger-journal-radius"),
                           ("roller_journal_radius_m", "roller-journal-radius")):
            _positive(f"{name[:-2].replace('_', ' ')} (--{flag})", getattr(self, name), "m")
        if not (math.isfinite(self.roller_mass_kg) and self.roller_mass_kg >= 0.0):
            raise ValueError(f"roller mass m4 (--roller-mass) must be >= 0 kg, "
                             f"got {self.roller_mass_kg:g}")
        for name, flag in (("rolling_friction", "rolling-friction"),
                           ("sliding_friction", "sliding-friction")):
            value = getattr(self, name)
            if not (math.isfinite(value) and 0.0 <= value < 1.0):
                raise ValueError(f"{name.replace('_', ' ')} (--{flag}) must be in [0, 1), "
                                 f"got {value:g}")

    @property
    def roller_load_n(self) -> float:
        """N2 = M2 / (n_p R2), the output shaft's load on one roller [N] (857.14 N)."""
        return self.output_torque_n_m / (self.rollers * self.carrier_radius_m)

    def centrifugal_force_n(self, input_speed_rpm: float) -> float:
        """Phi4 = m4 omega2^2 R2 at the input speed n1 [min^-1] [N]; omega2 = omega1 / u."""
        if not (math.isfinite(input_speed_rpm) and 0.0 <= input_speed_rpm <= MAX_INPUT_RPM):
            raise ValueError(f"input speed (--input-speed-rpm) must be in 0..{MAX_INPUT_RPM:g} "
                             f"min^-1, got {input_speed_rpm:g}")
        omega2 = 2.0 * math.pi * input_speed_rpm / 60.0 / self.ratio
        return self.roller_mass_kg * omega2 ** 2 * self.carrier_radius_m

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class OperatingPoint:
    """Lift angles and roller angle at which the force system is solved.

    Attributes
    ----------
    alpha1_rad, alpha3_rad : float
        Lift angles of the driving spiral and of the fixed link's grooves [rad], in (0, pi/2).
    phi2_rad : float
        Rotation angle of the composite roller about its own axis [rad].
    centrifugal_force_n : float
        Phi4 [N] (0: quasi-static; 0.02 N at 1500 min^-1).
    inertia_moment_n_m : float
        M_U, the roller's inertia moment eq. (6) [N m] (0: quasi-static).
    """

    alpha1_rad: float = math.radians(PAPER_ALPHA1_DEG)
    alpha3_rad: float = math.radians(PAPER_ALPHA3_DEG)
    phi2_rad: float = math.radians(PAPER_PHI2_DEG)
    centrifugal_force_n: float = 0.0
    inertia_moment_n_m: float = 0.0

    def __post_init__(self):
        for name, flag in (("alpha1_rad", "alpha1-deg"), ("alpha3_rad", "alpha3-deg")):
            value = getattr(self, name)
            if not (math.isfinite(value) and 0.0 < value < math.pi / 2):
                raise ValueError(f"lift angle {name[:-4]} (--{flag}) must be in (0, 90) deg, "
                                 f"got {math.degrees(value):g} deg")
        if not math.isfinite(self.phi2_rad):
            raise ValueError(f"roller angle phi2 (--phi2-deg) must be finite, got {self.phi2_rad}")
        for name in ("centrifugal_force_n", "inertia_moment_n_m"):
            if not math.isfinite(getattr(self, name)):
                raise ValueError(f"{name} must be finite, got {getattr(self, name)}")

    def to_dict(self) -> dict:
        return {"alpha1_deg": math.degrees(self.alpha1_rad),
                "alpha3_deg": math.degrees(self.alpha3_rad),
                "phi2_deg": math.degrees(self.phi2_rad),
                "centrifugal_force_n": self.centrifugal_force_n,
                "inertia_moment_n_m": self.inertia_moment_n_m}


@dataclass(frozen=True)
class RollerForces:
    """Solution of eqs. (14)-(20) for one finger shape at one operating point.

    Attributes
    ----------
    fingers : str
        ``"cylindrical"`` or ``"spherical"``.
    gamma_rad : float
        Lean of the finger reaction [rad].
    n1_n, n3_n : float
        Reactions of the driving and fixed tracks on the roller's fingers [N].
    s2p_n, s2pp_n : float
        Output shaft reaction components S2', S2'' [N], signed.
    m42_n_m : float
        Output shaft reaction moment M42 [N m].
    m1_n_m : float
        Input torque, eq. (20) [N m].
    eta : float or None
        M2 / (M1 u) [-]; None when M1 <= 0 (no driving torque).
    determinant : float
        det A of eq. (19) [m^2] (rows 17, 18 are moments).
    condition : float
        Condition number of A with its rows scaled to unit length [-].
    """

    fingers: str
    gamma_rad: float
    n1_n: float
    n3_n: float
    s2p_n: float
    s2pp_n: float
    m42_n_m: float
    m1_n_m: float
    eta: float | None
    determinant: float
    condition: float

    def to_dict(self) -> dict:
        return {"fingers": self.fingers, "gamma_deg": math.degrees(self.gamma_rad),
                "N1_n": self.n1_n, "N3_n": self.n3_n, "S2p_n": self.s2p_n,
                "S2pp_n": self.s2pp_n, "M42_n_m": self.m42_n_m, "M1_n_m": self.m1_n_m,
                "eta": self.eta, "det_A": self.determinant, "condition": self.condition}


def finger_angle(fingers: str, gear: TorusScrewGear,
                 finger_spacing_m: float = PAPER_FINGER_SPACING_M) -> float:
    """gamma [rad]: 0 for cylindrical fingers, arctan(S4 / (2 r4)) for spherical ones."""
    if fingers not in FINGER_KINDS:
        raise ValueError(f"fingers (--fingers) must be one of {', '.join(FINGER_KINDS)}, "
                         f"got {fingers!r}")
    if fingers == "cylindrical":
        return 0.0
    _positive("finger contact height S4 (--finger-spacing)", finger_spacing_m, "m")
    return math.atan(finger_spacing_m / (2.0 * gear.finger_radius_m))


def force_system(gear: TorusScrewGear, point: OperatingPoint, gamma_rad: float,
                 printed_signs: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Matrix A and right-hand side B of eq. (19); rows eqs. (14)-(18), columns
    ``[N1, N3, S2', S2'', M42]``.

    Parameters
    ----------
    printed_signs : bool
        Rebuild the system with the print's two sign slips instead of the consistent signs.
    """
    c1, s1 = math.cos(point.alpha1_rad), math.sin(point.alpha1_rad)
    c3, s3 = math.cos(point.alpha3_rad), math.sin(point.alpha3_rad)
    cp, sp = math.cos(point.phi2_rad), math.sin(point.phi2_rad)
    cg, sg = math.cos(gamma_rad), math.sin(gamma_rad)
    dr, dc = gear.rolling_friction, gear.sliding_friction
    r4, r0, r42, half = (gear.finger_radius_m, gear.finger_journal_radius_m,
                         gear.roller_journal_radius_m, gear.roller_length_m / 2.0)
    cg3 = cg if printed_signs else -cg          # eq. (14), N3 term
    sg3 = -sg if printed_signs else sg          # eq. (16), N3 term
    a = np.array([
        [sg * cp + sp * (-cg * c1 - dr * s1 + dc * s1),
         -sg * cp + sp * (cg3 * c3 + dr * s3 - dc * s3), -dc, -1.0, 0.0],
        [-cg * s1 + dr * c1 - dc * c1, -cg * s3 - dr * c3 + dc * c3, 0.0, 0.0, 0.0],
        [-sg * sp + cp * (-cg * c1 - dr * s1 + dc * s1),
         sg3 * sp + cp * (-cg * c3 + dr * s3 - dc * s3), 1.0, -dc, 0.0],
        [-dr * r4 + dc * r0, dr * r4 - dc * r0, 0.0, 0.0, 1.0],
        [half * (cg * c1 + dr * s1 - dc * s1), half * (-cg * c3 + dr * s3 - dc * s3),
         dc * r42, dc * r42, 0.0]])
    b = np.array([0.0, -gear.roller_load_n, -point.centrifugal_force_n, 0.0,
                  -point.inertia_moment_n_m])
    return a, b


def roller_forces(gear: TorusScrewGear, point: OperatingPoint, fingers: str,
                  finger_spacing_m: float = PAPER_FINGER_SPACING_M,
                  printed_signs: bool = False) -> RollerForces:
    """Solve eq. (19) and evaluate eq. (20) for one finger shape.

    Raises
    ------
    ValueError
        When A is singular for these angles (row-scaled condition number > MAX_CONDITION),
        or a contact force N1 or N3 comes out negative (the geometry is outside the
        model's validity: a contact that pulls).

    Examples
    --------
    >>> f = roller_forces(TorusScrewGear(), OperatingPoint(), "cylindrical")
    >>> round(f.n1_n, 1), round(f.n3_n, 1)          # paper: 160.61, 844.47
    (162.1, 844.2)
    """
    gamma = finger_angle(fingers, gear, finger_spacing_m)
    a, b = force_system(gear, point, gamma, printed_signs)
    det = float(np.linalg.det(a))
    scaled = a / np.linalg.norm(a, axis=1, keepdims=True)
    sv = np.linalg.svd(scaled, compute_uv=False)
    condition = float(sv[0] / sv[-1]) if sv[-1] > 0 else math.inf
    if not condition <= MAX_CONDITION:
        raise ValueError(
            f"the force system of eqs. (14)-(18) is singular for alpha1 = "
            f"{math.degrees(point.alpha1_rad):g} deg, alpha3 = {math.degrees(point.alpha3_rad):g}"
            f" deg, phi2 = {math.degrees(point.phi2_rad):g} deg, gamma = {math.degrees(gamma):g}"
            f" deg: det A = {det:.3g} (row-scaled condition number {condition:.3g}, must be <= "
            f"{MAX_CONDITION:.0e}); change --alpha1-deg, --alpha3-deg, --phi2-deg or "
            f"--finger-spacing")
    n1, n3, s2p, s2pp, m42 = (float(x) for x in np.linalg.solve(a, b))
    if n1 < 0 or n3 < 0:  # a track can only push on the finger: the contact would open
        raise ValueError(
            f"alpha1 = {math.degrees(point.alpha1_rad):g} deg, alpha3 = "
            f"{math.degrees(point.alpha3_rad):g} deg, phi2 = {math.degrees(point.phi2_rad):g} "
            f"deg ({fingers} fingers) is outside the force model's validity: eqs. (14)-(18) "
            f"give the contact force {'N1' if n1 < 0 else 'N3'} = {min(n1, n3):.4g} N < 0 (a "
            f"track can only push, so that contact would lift off); change --alpha1-deg, "
            f"--alpha3-deg or --phi2-deg")
    m1 = gear.rollers * n1 * math.cos(gamma) * math.sin(point.alpha1_rad) * gear.carrier_radius_m
    eta = gear.output_torque_n_m / (m1 * gear.ratio) if m1 > 0 else None
    return RollerForces(fingers, gamma, n1, n3, s2p, s2pp, m42, m1, eta, det, condition)


def _positive(label: str, value: float, unit: str) -> None:
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"{label} must be > 0{' ' + unit if unit else ''}, got {value:g}")
