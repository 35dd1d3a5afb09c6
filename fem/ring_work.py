"""Work-conjugate ring stiffnesses: c_ru and c_r from the work of the applied loads (SI).

For a load vector ``f`` with displacement ``u`` (``K u = f``) the work ``f^T u = 2 U``
is the load-weighted mean displacement the loads do work on, so
``c_ru_work = T^2 / (f^T u) / r_b^2`` with ``T = N F r_b`` (N teeth, 1 N each along the
line of action) and ``c_r_work = F^2 / (f^T u)`` (1 N spread over all teeth).  ``f^T u``
is the energy functional: for a conforming displacement FE it approaches the exact
value from below (the stiffness from above) at twice the energy-norm rate.

``c_ru_work`` holds everything between the supports and the load patches: the rim and
the loaded teeth (bending, shear, the patch's local compression).  The lumped model puts
the ring-body stiffness in series with the tooth-pair stiffness c_rp, whose ring tooth
is measured relative to the rigid motion of its root lands (``tooth_fe``).  The same
boundary splits the work here exactly: the rim part is the work of each loaded tooth's
forces on the rigid motion of that tooth's root lands (the rigid motion with their mean
u_x, u_y and mean rotation), the tooth part the rest, so
``1 / c_ru_work = 1 / c_ru_rim + 1 / c_ru_tooth`` to round-off.  The translation loads of
``c_r_work`` (1 N along x, along y, spread over all teeth) split on the same boundary:
``c_r_rim`` is the work of every tooth's share on the rigid motion of its root lands.

The lumped model uses the rim parts ``c_ru_rim`` and ``c_r_rim`` (``fem.estimate``):
the ring body in series with the tooth pairs, each counted once.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .elasticity import rigid_body_modes


@dataclass(frozen=True)
class RingWork:
    """Work-conjugate stiffnesses of one ring model.

    Attributes
    ----------
    c_ru_positions : ndarray
        ``T^2 / (f^T u) / r_b^2`` at each carrier position [N/m].
    c_ru_rim_positions, c_ru_tooth_positions : ndarray
        Its rim and loaded-tooth parts (in series) [N/m].
    c_r : float
        ``F^2 / (f^T u)`` of 1 N along x and along y spread over all teeth, mean [N/m].
    c_r_rim : float
        Its rim part: ``F^2`` over the work of every tooth's share on the rigid motion of
        its root lands, mean of x and y [N/m].
    """

    c_ru_positions: np.ndarray
    c_ru_rim_positions: np.ndarray
    c_ru_tooth_positions: np.ndarray
    c_r: float
    c_r_rim: float = float("nan")

    @property
    def c_ru(self) -> float:
        """Mean over the carrier positions [N/m]."""
        return float(np.mean(self.c_ru_positions))

    @property
    def c_ru_rim(self) -> float:
        """Mean rim part [N/m]."""
        return float(np.mean(self.c_ru_rim_positions))

    @property
    def c_ru_tooth(self) -> float:
        """Mean loaded-tooth part [N/m]."""
        return float(np.mean(self.c_ru_tooth_positions))


def in_plane_modes(model) -> np.ndarray:
    """(ndofs, 3): translation x, y and rotation about the ring axis (z) as DOF vectors
    (``elasticity.rigid_body_modes``; in 3D its columns 0, 1 and 3)."""
    modes = rigid_body_modes(model.basis)
    return modes if modes.shape[1] == 3 else modes[:, [0, 1, 3]]


def land_rigid_motions(model, lands, teeth, u: np.ndarray) -> np.ndarray:
    """(teeth, 3, columns): translation x, y [m] and rotation [rad] of the rigid motion
    with the same mean u_x, u_y and mean rotation over each tooth's root lands as the
    displacements ``u`` (ndofs, columns); exact for a rigid in-plane ``u``."""
    modes = in_plane_modes(model)
    rows = lands.rows(teeth)
    measured = np.stack([lands.u_x[rows] @ u, lands.u_y[rows] @ u,
                         lands.rotation[rows] @ u], axis=1)  # (teeth, 3, columns)
    of_modes = np.stack([lands.u_x[rows] @ modes, lands.u_y[rows] @ modes,
                         lands.rotation[rows] @ modes], axis=1)  # (teeth, 3, 3)
    return np.linalg.solve(of_modes, measured)


def ring_work(model, ring, loads, u: np.ndarray, forces, lands) -> RingWork:
    """Work-conjugate c_ru (with its rim and tooth parts) and c_r [N/m].

    ``loads`` is ``ring_stiffness.RingLoads`` (1 N along the line of action on each
    loaded tooth per carrier position, then 1 N along x and along y over all teeth),
    ``u`` its displacements (ndofs, columns), ``forces`` the ``ToothForces`` of every
    tooth and ``lands`` the ``RootLands`` of every tooth."""
    rb = ring.gear.base_diameter / 2
    work = np.einsum("ij,ij->j", loads.loads, u)
    if np.any(work <= 0):
        raise ValueError(f"the work of the ring loads is not positive ({work.min():.3e} "
                         "N m): the model is not supported or the loads vanish")
    positions = len(loads.loaded)
    teeth = list(range(ring.teeth))
    rigid = land_rigid_motions(model, lands, teeth, u[:, :positions])
    per_unit = forces.resultants(in_plane_modes(model))  # (teeth, 2, 3)
    torque = np.empty(positions)
    rim = np.empty(positions)
    for column, loaded in enumerate(loads.loaded):
        torque[column] = len(loaded) * rb  # [N m], 1 N per tooth along the line of action
        rim[column] = sum(ring.load_point(k)[1] @ per_unit[forces.teeth.index(k)]
                          @ rigid[k, :, column] for k in loaded)
    total = work[:positions]
    c_ru = torque ** 2 / total / rb ** 2
    c_rim = torque ** 2 / rim / rb ** 2
    c_tooth = torque ** 2 / (total - rim) / rb ** 2
    c_r = float(np.mean(1.0 / work[positions:positions + 2]))
    # the translation loads: 1/z N along x (column 0) and along y (column 1) on every tooth
    shifted = land_rigid_motions(model, lands, teeth, u[:, positions:positions + 2])
    share = 1.0 / ring.teeth
    rim_r = [share * sum(per_unit[forces.teeth.index(k), axis] @ shifted[k, :, axis]
                         for k in teeth) for axis in (0, 1)]
    if min(rim_r) <= 0:
        raise ValueError(f"the rim work of the translation loads is not positive "
                         f"({min(rim_r):.3e} N m): the model is not supported")
    c_r_rim = float(np.mean([1.0 / w for w in rim_r]))
    return RingWork(c_ru, c_rim, c_tooth, c_r, c_r_rim)
