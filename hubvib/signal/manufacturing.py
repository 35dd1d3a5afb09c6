"""Manufacturing errors of the stage and the static load sharing among the planets (SI).

Carrier pin-hole errors: the pin of planet i sits ``e_t,i`` ahead of its nominal
place (tangential, in the sense of the planet angle ``theta``) and ``e_r,i`` outward
(radial).  Two effects, both in the model:

1. *Static*: the planet's bearing springs are pre-deformed.  With the rows
   ``g_b`` of :func:`hubvib.lumped.network.spring_network` ("planet i bearing
   tangential / radial", deformation ``g_b . q + e_b``), the errors load the model
   with ``f_e = -sum_b k_b g_b e_b``; the static state and hence the static mesh
   forces change (the load sharing).
2. *Mesh phase*: the planet stands at polar angle ``theta_i + e_t,i / a`` in its mesh
   cycles (``a``: centre distance), so its ring mesh runs ``r_br e_t,i / a`` ahead
   in roll length and its sun mesh as much behind (the rolling geometry of
   :mod:`hubvib.signal.mesh_phase`).  This breaks the phase cancellation of
   McFadden & Smith (1985) and puts energy on carrier orders that are not
   multiples of N even when the loads stay equal.

Ring run-out: the ring's tooth centre sits ``e_ro`` from the carrier axis at the
fixed angle ``beta``; in the carrier frame it turns at ``-Omega``, and ring mesh j
sees the deflection error ``e_j(t) = -(g_j[x_r] d_x(t) + g_j[y_r] d_y(t))``,
``d(t) = e_ro (cos(beta - Omega t), sin(beta - Omega t))``.  Sun and planet run-out
turn at orders that are not whole carrier orders and are not modelled (the steady
state here repeats every carrier revolution).

Quasi-static closed form (centre members held in translation, rigid planet
bearings; each planet a sun mesh ``k_s`` and a ring mesh ``k_r`` in series,
``k_sr = k_s k_r / (k_s + k_r)``, the planet's own rotation free): planet i's mesh
force is

    F_i = F_mean - k_sr [(cos a_s + cos a_r)(e_t,i - mean e_t)
                         + (sin a_s - sin a_r)(e_r,i - mean e_r)],

``F_mean = T_s / (N r_bs)`` (magnitudes; with the sun driven in the sense of the
planet angle, a pin ahead of its place unloads its planet).  With a floating sun (``c_s = 0``) and three planets the
sun's force balance leaves only equal mesh forces (three lines of action 120 deg
apart), whatever the errors (e.g. Kahraman 1994, "Load sharing characteristics of
planetary transmissions", Mech. Mach. Theory 29).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.lumped import PlanetaryParameters, spring_network

RING_TRANSLATION = (4, 5)  # x_r, y_r in the coordinates of the spring network


@dataclass(frozen=True)
class StageErrors:
    """Manufacturing errors [m, rad].

    Attributes
    ----------
    tangential : tuple of float
        Pin-hole position error of each planet along the planet circle [m] (empty: none).
    radial : tuple of float
        Pin-hole radial error of each planet [m] (empty: none).
    ring_runout : float
        Eccentricity of the ring's teeth about the carrier axis [m].
    ring_runout_phase : float
        Its direction, fixed in space [rad].
    """

    tangential: tuple[float, ...] = ()
    radial: tuple[float, ...] = ()
    ring_runout: float = 0.0
    ring_runout_phase: float = 0.0

    def any(self) -> bool:
        return bool(any(self.tangential) or any(self.radial) or self.ring_runout)

    def per_planet(self, n_planets: int) -> tuple[np.ndarray, np.ndarray]:
        """(tangential, radial) errors [m] as arrays of length N (zeros where not given).

        Raises
        ------
        ValueError
            A list whose length is not N.
        """
        out = []
        for name, values in (("planet_position_errors_m", self.tangential),
                             ("pin_hole_radial_errors_m", self.radial)):
            if values and len(values) != n_planets:
                raise ValueError(f"[signal] {name} has {len(values)} value(s), but the "
                                 f"reducer has {n_planets} planets; allowed: one per planet")
            out.append(np.array(values, dtype=float) if values else np.zeros(n_planets))
        return out[0], out[1]


def error_load(params: PlanetaryParameters, errors: StageErrors) -> np.ndarray:
    """Generalised force of the pre-deformed planet bearings, ``-sum_b k_b g_b e_b`` [N]."""
    network = spring_network(params)
    tangential, radial = errors.per_planet(params.n_planets)
    offsets = np.zeros(network.k.size)
    for i in range(params.n_planets):
        offsets[network.label.index(f"planet {i + 1} bearing tangential")] = tangential[i]
        offsets[network.label.index(f"planet {i + 1} bearing radial")] = radial[i]
    return -network.G.T @ (network.k * offsets)


def planet_shift(errors: StageErrors, n_planets: int, centre_distance: float) -> np.ndarray:
    """Shift of each planet's polar angle in its mesh cycles, ``e_t,i / a`` [rad]."""
    tangential, _ = errors.per_planet(n_planets)
    return tangential / centre_distance


def runout_error(rows: np.ndarray, carrier_angle: np.ndarray, errors: StageErrors,
                 n_planets: int) -> np.ndarray | None:
    """Mesh deflection errors of the ring run-out at these carrier angles [m],
    shape (steps, 2N) (sun meshes 0, ring meshes as in the module docstring); None
    without run-out."""
    if not errors.ring_runout:
        return None
    angle = errors.ring_runout_phase - np.asarray(carrier_angle)
    d = errors.ring_runout * np.stack([np.cos(angle), np.sin(angle)], axis=1)
    out = -(d @ rows[:, list(RING_TRANSLATION)].T)
    out[:, :n_planets] = 0.0
    return out


def rigid_centre_sharing(params: PlanetaryParameters, errors: StageErrors, sun_torque: float,
                         k_sun: float, k_ring: float) -> np.ndarray:
    """Static mesh force of each planet [N] by the closed form of the module docstring
    (centre members held in translation, rigid planet bearings), magnitudes."""
    tangential, radial = errors.per_planet(params.n_planets)
    k_sr = k_sun * k_ring / (k_sun + k_ring)
    mean = sun_torque / (params.n_planets * params.d_s / 2)
    c_t = math.cos(params.alpha_s) + math.cos(params.alpha_r)
    c_r = math.sin(params.alpha_s) - math.sin(params.alpha_r)
    return mean - k_sr * (c_t * (tangential - tangential.mean())
                          + c_r * (radial - radial.mean()))


def load_sharing(static_force: np.ndarray, n_planets: int) -> np.ndarray:
    """Ring-mesh static force of each planet over their mean [-] (1: equal sharing)."""
    ring = np.asarray(static_force)[n_planets:]
    return ring / ring.mean()
