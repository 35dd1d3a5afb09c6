"""Contact loss of the mesh springs: where a tooth pair would pull, it separates (SI).

The linear model lets a mesh spring carry tension when its dynamic force exceeds the
static one (``F_j = F_static,j + F_dyn,j`` changes sign).  Real teeth separate there
(backlash, as in ROSS's gear element and Kahraman & Singh 1990, "Non-linear
dynamics of a spur gear pair", J. Sound Vib. 142): the mesh stiffness is piecewise,
``k_j(t)`` where the mesh deflection ``delta_j + g_j . x - e_j`` keeps the sign of
the static one and 0 where it does not (backlash larger than the vibration, so no
back-side contact).  The periodic steady state of that piecewise-linear system is
found by fixing the contact pattern, solving the linear periodic problem, updating
the pattern from the new deflections and repeating until it stops changing (an
active-set iteration; it settles in a few passes when the separation is short).
"""
from __future__ import annotations

import numpy as np

#: passes of the active-set iteration before giving up
MAX_PASSES = 40


def deflection(dynamics, displacement: np.ndarray, error: np.ndarray | None) -> np.ndarray:
    """Mesh deflections ``delta_j + g_j . x - e_j`` at every step [m], (steps, 2N)."""
    out = dynamics.preload[None, :] + displacement @ dynamics.system.rows.T
    return out if error is None else out - error


def in_contact(dynamics, displacement: np.ndarray, error: np.ndarray | None) -> np.ndarray:
    """True where the mesh deflection has the sign of the static one (teeth touching)."""
    return deflection(dynamics, displacement, error) * np.sign(dynamics.preload)[None, :] > 0


def force_ratio(dynamics, forces: np.ndarray) -> np.ndarray:
    """Total over static mesh force, ``(F_static + F_dyn) / F_static`` [-], (steps, 2N)."""
    static = dynamics.static_force[None, :]
    return (static + forces) / static


def mesh_names(n_planets: int) -> list[str]:
    """Names of the mesh springs in the column order of the forces."""
    return ([f"sun-planet {i + 1}" for i in range(n_planets)]
            + [f"ring-planet {i + 1}" for i in range(n_planets)])
