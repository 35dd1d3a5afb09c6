"""Mixed-mode stress intensity factors at a crack tip and the kink angle of the crack (SI).

K_I and K_II come from the domain form of the interaction integral (Yau, Wang &
Corten 1980; Moran & Shih 1987; as in Moes, Dolbow & Belytschko 1999, eq. 23):

    I = int_A [ sigma_ij du^aux_i/dx_1 + sigma^aux_ij du_i/dx_1 - sigma_ij eps^aux_ij delta_1j ]
        dq/dx_j dA,        K = E' I / 2,

in the tip frame (x_1 along the crack's extension, x_2 to its left), with the
auxiliary fields the Williams near-tip fields of unit K_I (then K_II), and ``q``
a smooth weight, 1 within ``r_in`` of the tip and 0 beyond ``r_out``.  Only the
annulus r_in < r < r_out contributes, away from the tip where the FE solution is
worst, so plain P2 elements (no quarter-point nodes) suffice.  ``E' = E`` in plane
stress, ``E / (1 - nu^2)`` in plane strain.  The annulus must cut the crack on a
straight piece: keep ``r_out`` below the length of the crack's last segment.

The kink angle follows the maximum tangential stress criterion (Erdogan & Sih
1963): the crack grows where sigma_theta_theta(theta) at the tip is largest,
``theta = 2 atan[(K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II)]``, negative for
positive K_II (the crack turns clockwise from its own direction).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .elasticity import PlaneModel

#: quadrature degree of the interaction integral (the auxiliary fields are not polynomial)
QUADRATURE = 6
#: default inner radius of the weight's ramp as a fraction of r_out
INNER_FRACTION = 0.25


class FractureError(ValueError):
    """A crack-tip quantity cannot be computed; the message says why and the range allowed."""


@dataclass(frozen=True)
class StressIntensity:
    """Stress intensity factors at one crack tip.

    Attributes
    ----------
    k_i, k_ii : float
        Opening and in-plane shear modes [Pa sqrt(m)].
    tip : tuple of float
        Tip position (x, y) [m].
    direction : tuple of float
        Unit vector of the crack's extension at the tip.
    r_in, r_out : float
        Radii of the integration annulus [m].
    cells : int
        Cells in the integration domain.
    """

    k_i: float
    k_ii: float
    tip: tuple
    direction: tuple
    r_in: float
    r_out: float
    cells: int

    @property
    def kink_angle(self) -> float:
        """Maximum-tangential-stress kink angle [rad] (``mts_angle``)."""
        return mts_angle(self.k_i, self.k_ii)


def mts_angle(k_i: float, k_ii: float) -> float:
    """Kink angle [rad] of the maximum tangential stress criterion (Erdogan & Sih 1963).

    ``theta = 2 atan[(K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II)]``, 0 for pure mode I,
    -+70.53 deg for pure mode II of sign +-; from the crack's direction, counter-clockwise
    positive.  Raises FractureError for a closed crack (K_I < 0 beyond round-off), where
    the criterion does not hold.
    """
    for name, value in (("k_i", k_i), ("k_ii", k_ii)):
        if not math.isfinite(value):
            raise FractureError(f"{name} = {value!r}: a finite stress intensity is needed")
    scale = math.hypot(k_i, k_ii)
    if scale == 0:
        raise FractureError("k_i = k_ii = 0: an unloaded crack has no growth direction")
    if k_i < -1e-9 * scale:
        raise FractureError(f"k_i = {k_i:.6g} Pa m^0.5 < 0: the crack faces press together, "
                            "the maximum tangential stress criterion needs K_I >= 0")
    if abs(k_ii) <= 1e-12 * scale:
        return 0.0
    return 2.0 * math.atan((k_i - math.sqrt(k_i ** 2 + 8.0 * k_ii ** 2)) / (4.0 * k_ii))


def mts_driving_force(k_i: float, k_ii: float) -> float:
    """The maximum tangential stress criterion's driving force [Pa sqrt(m)]:
    ``sigma_theta_theta sqrt(2 pi r)`` at the MTS angle, ``cos(t/2) [K_I cos^2(t/2) -
    3/2 K_II sin t]`` (Erdogan & Sih 1963); K_I for pure mode I, 2/sqrt(3) |K_II| for pure
    mode II.  0 for a closed crack (K_I < 0): it does not drive the crack."""
    scale = math.hypot(k_i, k_ii)
    if k_i < -1e-9 * scale:
        return 0.0
    return float(hoop_stress(mts_angle(k_i, k_ii), k_i, k_ii))


def hoop_stress(theta, k_i: float, k_ii: float):
    """sigma_theta_theta sqrt(2 pi r) of the singular near-tip field [Pa sqrt(m)] at the
    angles ``theta`` [rad] from the crack direction (Williams)."""
    theta = np.asarray(theta, dtype=float)
    c = np.cos(theta / 2)
    return c * (k_i * c ** 2 - 1.5 * k_ii * np.sin(theta))


def williams(r, theta, mode: int, mu: float, kappa: float):
    """Near-tip displacement [m] and stress [Pa] of unit K (1 Pa sqrt(m)) in mode 1 or 2.

    Tip frame; returns ``(u1, u2), (s11, s22, s12)``; ``kappa`` is Kolosov's constant.
    """
    r = np.asarray(r, dtype=float)
    c, s = np.cos(theta / 2), np.sin(theta / 2)
    c3, s3 = np.cos(1.5 * theta), np.sin(1.5 * theta)
    root = np.sqrt(r / (2 * math.pi)) / (2 * mu)
    f = 1 / np.sqrt(2 * math.pi * r)
    if mode == 1:
        u = (root * c * (kappa - 1 + 2 * s ** 2), root * s * (kappa + 1 - 2 * c ** 2))
        sigma = (f * c * (1 - s * s3), f * c * (1 + s * s3), f * s * c * c3)
    elif mode == 2:
        u = (root * s * (kappa + 1 + 2 * c ** 2), -root * c * (kappa - 1 - 2 * s ** 2))
        sigma = (-f * s * (2 + c * c3), f * s * c * c3, f * c * (1 - s * s3))
    else:
        raise FractureError(f"mode = {mode!r}, allowed 1 or 2")
    return u, sigma


def _aux_gradient(r, theta, mode, mu, kappa, step=1e-6):
    """d(u1, u2)/dx_1 of the unit auxiliary field in the tip frame.

    u = sqrt(r) f(theta) gives du/dx_1 = cos(theta) u / (2 r) - sin(theta) sqrt(r) f'(theta)
    / r; f' by a central difference of step ``step`` [rad] (never across theta = +-pi,
    where quadrature points do not lie)."""
    up, _ = williams(r, theta + step, mode, mu, kappa)
    down, _ = williams(r, theta - step, mode, mu, kappa)
    here, _ = williams(r, theta, mode, mu, kappa)
    return [np.cos(theta) * u0 / (2 * r) - np.sin(theta) * (a - b) / (2 * step) / r
            for u0, a, b in zip(here, up, down)]


def interaction_integral(model: PlaneModel, u: np.ndarray, tip, direction, r_out: float,
                         r_in: float | None = None) -> StressIntensity:
    """K_I and K_II [Pa sqrt(m)] at the crack tip ``tip`` [m] from the displacement ``u``
    [m] of the plane ``model``.

    ``direction`` points along the crack's extension (away from its faces); ``r_out`` [m]
    is the outer radius of the integration annulus (shorter than the crack's last straight
    piece and inside the body), ``r_in`` its inner radius (default r_out / 4).
    """
    import skfem

    tip = np.asarray(tip, dtype=float).reshape(2)
    e1 = np.asarray(direction, dtype=float).reshape(2)
    if not np.all(np.isfinite(e1)) or np.hypot(*e1) == 0:
        raise FractureError(f"direction = {direction!r}: a non-zero vector is needed")
    e1 = e1 / np.hypot(*e1)
    e2 = np.array([-e1[1], e1[0]])
    r_in = INNER_FRACTION * r_out if r_in is None else r_in
    if not (math.isfinite(r_out) and 0 <= r_in < r_out):
        raise FractureError(f"r_in = {r_in!r} m, r_out = {r_out!r} m: need 0 <= r_in < r_out")
    fe = model.basis.mesh
    corners = fe.p[:, fe.t[:3]]  # (2, 3, cells)
    centroid = corners.mean(axis=1)
    radius = np.max(np.hypot(*(corners - centroid[:, None, :])), axis=0)
    near = np.flatnonzero(np.hypot(*(centroid - tip[:, None])) - radius < r_out)
    if len(near) == 0:
        raise FractureError(f"no cell within r_out = {r_out:g} m of the tip {tip.tolist()}")
    basis = skfem.CellBasis(fe, model.basis.elem, intorder=QUADRATURE, elements=near)
    grad = basis.interpolate(u).grad  # (2, 2, cells, points): d u_i / d x_j, global frame
    x = np.asarray(basis.global_coordinates())  # (2, cells, points)
    weight = basis.dx

    rot = np.array([e1, e2])          # local = rot @ global
    d = x - tip[:, None, None]
    x1 = rot[0, 0] * d[0] + rot[0, 1] * d[1]
    x2 = rot[1, 0] * d[0] + rot[1, 1] * d[1]
    r = np.hypot(x1, x2)
    theta = np.arctan2(x2, x1)
    grad_local = np.einsum("ia,abcq,jb->ijcq", rot, grad, rot)

    E, nu = model.material.E, model.material.nu
    lam, mu = model.material.lame(model.plane)
    if model.plane == "stress":
        kappa, e_prime = (3 - nu) / (1 + nu), E
    else:
        kappa, e_prime = 3 - 4 * nu, E / (1 - nu ** 2)
    strain = 0.5 * (grad_local + grad_local.transpose(1, 0, 2, 3))
    trace = strain[0, 0] + strain[1, 1]
    s11 = lam * trace + 2 * mu * strain[0, 0]
    s22 = lam * trace + 2 * mu * strain[1, 1]
    s12 = 2 * mu * strain[0, 1]

    ramp = r_out - r_in
    sfrac = np.clip((r - r_in) / ramp, 0.0, 1.0)
    dq_dr = -6 * sfrac * (1 - sfrac) / ramp
    active = dq_dr != 0
    safe_r = np.where(active, r, 1.0)
    q1 = np.where(active, dq_dr * x1 / safe_r, 0.0)
    q2 = np.where(active, dq_dr * x2 / safe_r, 0.0)

    values = []
    for mode in (1, 2):
        _, (a11, a22, a12) = williams(safe_r, theta, mode, mu, kappa)
        ua1, ua2 = _aux_gradient(safe_r, theta, mode, mu, kappa)
        # eps^aux from sigma^aux (Hooke in the model's plane condition)
        tr_a = (a11 + a22) / (2 * (lam + mu))
        ea11, ea22, ea12 = (a11 - lam * tr_a) / (2 * mu), (a22 - lam * tr_a) / (2 * mu), \
            a12 / (2 * mu)
        w12 = s11 * ea11 + s22 * ea22 + 2 * s12 * ea12
        term = ((s11 * ua1 + s12 * ua2) * q1 + (s12 * ua1 + s22 * ua2) * q2
                + (a11 * grad_local[0, 0] + a12 * grad_local[1, 0]) * q1
                + (a12 * grad_local[0, 0] + a22 * grad_local[1, 0]) * q2
                - w12 * q1)
        values.append(float(np.sum(np.where(active, term, 0.0) * weight)))
    k_i, k_ii = (0.5 * e_prime * v for v in values)
    return StressIntensity(k_i, k_ii, tuple(tip.tolist()), tuple(e1.tolist()), float(r_in),
                           float(r_out), int(len(near)))
