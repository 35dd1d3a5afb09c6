"""The model as a spring network: potential energy ``1/2 sum_j k_j (g_j . q)^2``.

Every elastic element j contributes one row ``g_j`` (how its deformation
depends on the coordinates) and one stiffness ``k_j``, so the stiffness matrix
is ``K = G^T diag(k) G``: symmetric positive semidefinite by construction, and
available in factored form for the accurate eigensolver.

Coordinates (paper eq. 5), all displacements [m]::

    0 x_s   1 y_s   2 x_c   3 y_c   4 x_r   5 y_r   6 u_s   7 u_c   8 u_r
    9 + 3 i: tau_i (tangential), eta_i (radial), u_i   for planet i = 0..N-1

``u`` is the rotation expressed as the arc length along the base circle.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .parameters import PlanetaryParameters

CENTRAL_DOFS = ("x_s", "y_s", "x_c", "y_c", "x_r", "y_r", "u_s", "u_c", "u_r")
CENTRAL_TRANSLATIONS = (0, 1, 2, 3, 4, 5)
CENTRAL_ROTATIONS = (6, 7, 8)


def dof_names(n_planets: int) -> tuple[str, ...]:
    """Coordinate names in matrix order (planets numbered from 1)."""
    planets = [f"{name}_{i + 1}" for i in range(n_planets) for name in ("tau", "eta", "u")]
    return CENTRAL_DOFS + tuple(planets)


def dof_members(n_planets: int) -> tuple[str, ...]:
    """Member owning each coordinate: 'sun', 'carrier', 'ring', 'planet 1', ..."""
    central = ("sun", "sun", "carrier", "carrier", "ring", "ring", "sun", "carrier", "ring")
    return central + tuple(f"planet {i + 1}" for i in range(n_planets) for _ in range(3))


@dataclass(frozen=True)
class SpringNetwork:
    """Rows ``G`` [-], stiffnesses ``k`` [N/m] and the parameter behind each row."""

    G: np.ndarray
    k: np.ndarray
    parameter: tuple[str, ...]
    label: tuple[str, ...]

    def stiffness_matrix(self) -> np.ndarray:
        """Assembled ``K = G^T diag(k) G`` [N/m]."""
        K = self.G.T @ (self.k[:, None] * self.G)
        return 0.5 * (K + K.T)  # exactly symmetric, not only to rounding

    def rows_of(self, parameter: str) -> np.ndarray:
        """Boolean mask of the rows whose stiffness is ``parameter``."""
        return np.array([p == parameter for p in self.parameter])


def spring_network(params: PlanetaryParameters) -> SpringNetwork:
    """Elastic elements of the model (paper eq. 6-8), sun bearing added."""
    n = params.n_dof
    rows, ks, names, labels = [], [], [], []

    def spring(coefficients: dict[int, float], parameter: str, label: str, factor=1.0):
        g = np.zeros(n)
        for index, value in coefficients.items():
            g[index] += value
        rows.append(g)
        ks.append(factor * getattr(params, parameter))
        names.append(parameter)
        labels.append(label)

    for axis, offset in (("x", 0), ("y", 1)):
        spring({0 + offset: 1.0}, "c_s", f"sun bearing {axis}")
        spring({2 + offset: 1.0}, "c_c", f"carrier bearing {axis}")
        spring({4 + offset: 1.0}, "c_r", f"ring support {axis}")
    spring({6: 1.0}, "c_su", "sun torsion")
    spring({7: 1.0}, "c_cu", "carrier torsion")
    spring({8: 1.0}, "c_ru", "ring torsion")

    a_s, a_r = params.alpha_s, params.alpha_r
    rp_factors = params.c_rp_factors or (1.0,) * params.n_planets
    for i, th in enumerate(params.theta):
        tau, eta, u = 9 + 3 * i, 10 + 3 * i, 11 + 3 * i
        s, c = math.sin(th), math.cos(th)
        spring({3: s, 2: c, eta: -1.0}, "c_p", f"planet {i + 1} bearing radial")
        spring({3: c, 2: -s, tau: -1.0, 7: 1.0}, "c_p", f"planet {i + 1} bearing tangential")
        spring(
            {0: math.sin(th - a_s), 1: -math.cos(th - a_s), 6: -1.0, u: -1.0,
             tau: math.cos(a_s), eta: math.sin(a_s)},
            "c_sp", f"sun-planet {i + 1} mesh",
        )
        spring(
            {4: math.sin(th + a_r), 5: -math.cos(th + a_r), u: 1.0, 8: -1.0,
             tau: math.cos(a_r), eta: -math.sin(a_r)},
            "c_rp", f"ring-planet {i + 1} mesh", rp_factors[i],
        )
    return SpringNetwork(np.array(rows), np.array(ks, dtype=float), tuple(names), tuple(labels))


def mass_diagonal(params: PlanetaryParameters) -> np.ndarray:
    """Diagonal of the mass matrix A (paper eq. 15) [kg]."""
    p = params
    central = [p.m_s, p.m_s, p.m_c, p.m_c, p.m_r, p.m_r, p.mu_s, p.mu_c, p.mu_r]
    return np.array(central + [p.m_p, p.m_p, p.mu_p] * p.n_planets, dtype=float)


def stiffness_matrix(params: PlanetaryParameters) -> np.ndarray:
    """Stiffness matrix C derived from the potential energy [N/m]."""
    return spring_network(params).stiffness_matrix()


def mass_matrix(params: PlanetaryParameters) -> np.ndarray:
    """Mass matrix A [kg] (diagonal)."""
    return np.diag(mass_diagonal(params))
