"""Friction losses and efficiency of a ball/roller planetary gear (seed 001).

Kapitonov 2024 (Transport Engineering 3:20-30). The driving link carries a single-period track
(z1 = 1), the fixed link a multi-period track of ``z2 = i - 1`` periods, the carrier-separator is
the output, so ``i = z1 + z2`` and ``omega1 = i omega3``. A satellite rolls on the driving track
(friction f1), rolls with sliding on the fixed track (f2) and slides in the carrier slot (f3).

Eqs. (1)-(3) give the friction forces ``F1t = f1 F1h / sin a1``, ``F2t = f2 F2h / sin a2``,
``F3t = f3 F3n`` (the print writes F_1F, F_2T where the horizontal forces F1h, F2h are meant);
eqs. (5)-(7) the sliding speeds ``v1 = rho (w1 - w3) / cos a1``, ``v2 = rho w3 / cos a2``,
``v2s = rho w3 tan a2``; eqs. (8)-(10) the losses, ``psi = W_loss / W_out`` and
``eta = 1 / (1 + psi)``. With the force balance of the paper's ref. [1] (``F1h w1 = F3n w3``,
``F3n = F1h + F2h``) each link's loss referred to the output power ``W_out = F3n rho w3`` is::

    psi_driving = f1 (z2 / i) / (sin a1 cos a1)
    psi_fixed   = f2 (z2 / i) / (sin a2 cos a2)
    psi_carrier = f3 tan a2,         a2 = arctan(z2 tan a1)   (eq. 11)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.optimize import minimize_scalar

from hubvib.companion.efficiency.track_geometry import check_alpha1, fixed_track_lift_angle

#: Input power of the paper's loss plots, W1 = 1500 W [W].
PAPER_INPUT_POWER_W = 1500.0

#: Whole-degree lift angles the optimum is searched over [deg].
WHOLE_DEGREES = tuple(range(1, 90))

#: Lift angles of the paper's loss and efficiency curves, Figs. 5-8 [deg].
CURVE_DEGREES = tuple(range(1, 31))


@dataclass(frozen=True)
class Friction:
    """Friction coefficients of the three contacts [-]; defaults are the paper's.

    Attributes
    ----------
    f1 : float
        Satellite rolling on the driving single-period track (0.004).
    f2 : float
        Satellite rolling with sliding on the fixed multi-period track (0.05).
    f3 : float
        Satellite sliding in the carrier-separator slot (0.1).
    """

    f1: float = 0.004
    f2: float = 0.05
    f3: float = 0.1

    def __post_init__(self):
        for name in ("f1", "f2", "f3"):
            value = getattr(self, name)
            if not (math.isfinite(value) and 0.0 <= value < 1.0):
                raise ValueError(f"friction coefficient {name} (--{name}) must be in [0, 1), "
                                 f"got {value:g}")

    def to_dict(self) -> dict:
        return {"f1": self.f1, "f2": self.f2, "f3": self.f3}


@dataclass(frozen=True)
class LinkPower:
    """Power balance of the gear at a given input power [W].

    ``input_w = output_w + driving_w + fixed_w + carrier_w``; each link loss is its relative loss
    times the output power, ``W_k = psi_k W_out`` with ``W_out = eta W_in``.
    """

    input_w: float
    output_w: float
    driving_w: float
    fixed_w: float
    carrier_w: float

    @property
    def total_loss_w(self) -> float:
        """Sum of the three link losses [W]."""
        return self.driving_w + self.fixed_w + self.carrier_w

    def to_dict(self) -> dict:
        return {"input_w": self.input_w, "output_w": self.output_w,
                "driving_w": self.driving_w, "fixed_w": self.fixed_w,
                "carrier_w": self.carrier_w, "total_loss_w": self.total_loss_w}


@dataclass(frozen=True)
class Losses:
    """Relative power losses of each link at one driving-track lift angle.

    Attributes
    ----------
    ratio : int
        Gear ratio i = z1 + z2 (z1 = 1).
    alpha1_rad, alpha2_rad : float
        Lift angles of the driving and fixed tracks [rad].
    psi_driving, psi_fixed, psi_carrier : float
        Losses in the driving link, the fixed link and the carrier-separator, each referred to
        the output power [-].
    """

    ratio: int
    alpha1_rad: float
    alpha2_rad: float
    psi_driving: float
    psi_fixed: float
    psi_carrier: float

    @property
    def z2(self) -> int:
        """Periods of the fixed track."""
        return self.ratio - 1

    @property
    def psi(self) -> float:
        """Relative loss of the gear, eq. (9) [-]."""
        return self.psi_driving + self.psi_fixed + self.psi_carrier

    @property
    def eta(self) -> float:
        """Efficiency, eq. (10) [-] (a fraction, not percent)."""
        return 1.0 / (1.0 + self.psi)

    def power(self, input_power_w: float = PAPER_INPUT_POWER_W) -> LinkPower:
        """Link losses [W] at the input power ``input_power_w`` [W]."""
        if not (math.isfinite(input_power_w) and input_power_w > 0.0):
            raise ValueError(f"input power (--input-power-w) must be > 0 W, got {input_power_w:g}")
        out = self.eta * input_power_w
        return LinkPower(input_power_w, out, self.psi_driving * out, self.psi_fixed * out,
                         self.psi_carrier * out)

    def to_dict(self) -> dict:
        return {"alpha1_deg": round(math.degrees(self.alpha1_rad), 10),
                "alpha2_deg": math.degrees(self.alpha2_rad),
                "psi_driving": self.psi_driving, "psi_fixed": self.psi_fixed,
                "psi_carrier": self.psi_carrier, "psi": self.psi, "eta": self.eta}


@dataclass(frozen=True)
class Optimum:
    """Efficiency-optimal driving-track lift angle for one ratio.

    Attributes
    ----------
    whole : Losses
        Best whole-degree lift angle (the paper's scan).
    continuous : Losses
        Minimum of psi over the continuous lift angle.
    """

    whole: Losses
    continuous: Losses

    def to_dict(self) -> dict:
        return {"alpha1_whole_deg": round(math.degrees(self.whole.alpha1_rad)),
                "eta_whole": self.whole.eta,
                "alpha1_continuous_deg": math.degrees(self.continuous.alpha1_rad),
                "eta_continuous": self.continuous.eta}


#: largest ratio of one stage: i = 1000 already needs a 12 m track radius with 15 mm
#: balls (eq. 12); 1e300 ended in R = -inf and exit 0
MAX_RATIO = 1000


def check_ratio(ratio: float) -> int:
    """Return the ratio as an int if it is a whole number in 2..MAX_RATIO, else raise
    ValueError."""
    if not (math.isfinite(ratio) and 2 <= ratio <= MAX_RATIO and float(ratio).is_integer()):
        raise ValueError(f"ratio i (--ratio) must be a whole number in 2..{MAX_RATIO} "
                         f"(i = z1 + z2, z1 = 1), got {ratio:g}")
    return int(ratio)


def losses(ratio: int, alpha1_rad: float, friction: Friction = Friction()) -> Losses:
    """Relative losses of each link at the lift angle ``alpha1_rad`` [rad].

    Examples
    --------
    >>> round(losses(5, math.radians(9)).eta * 100, 2)    # paper: 85.3 %
    85.28
    """
    i = check_ratio(ratio)
    a1 = check_alpha1(alpha1_rad)
    z2 = i - 1
    a2 = fixed_track_lift_angle(a1, z2)
    share = z2 / i
    return Losses(i, a1, a2,
                  psi_driving=friction.f1 * share / (math.sin(a1) * math.cos(a1)),
                  psi_fixed=friction.f2 * share / (math.sin(a2) * math.cos(a2)),
                  psi_carrier=friction.f3 * math.tan(a2))


def loss_curve(ratio: int, alpha1_deg, friction: Friction = Friction()) -> tuple[Losses, ...]:
    """Losses at each lift angle of ``alpha1_deg`` [deg] (the paper's Figs. 5-8)."""
    return tuple(losses(ratio, math.radians(a), friction) for a in alpha1_deg)


def optimum(ratio: int, friction: Friction = Friction()) -> Optimum:
    """Lift angle of least psi: on whole degrees 1..89 and continuous.

    psi -> infinity at both ends of (0, 90) deg; the continuous minimum is refined by a bounded
    Brent search within one degree of the whole-degree one.
    """
    curve = loss_curve(ratio, WHOLE_DEGREES, friction)
    whole = min(curve, key=lambda item: item.psi)
    lo = max(whole.alpha1_rad - math.radians(1.0), 1e-9)
    hi = min(whole.alpha1_rad + math.radians(1.0), math.pi / 2 - 1e-9)
    found = minimize_scalar(lambda a: losses(ratio, a, friction).psi, bounds=(lo, hi),
                            method="bounded", options={"xatol": 1e-12})
    return Optimum(whole, losses(ratio, float(found.x), friction))
