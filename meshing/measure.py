"""Measures of an ``FEMesh`` computed from its own nodes (independent of the geometry)."""
from __future__ import annotations

import numpy as np

from .fe_mesh import FEMesh

# 3-point rule on the reference triangle, exact for quadratics (det J of a P2 map)
_TRI_POINTS = np.array([[1 / 6, 1 / 6], [2 / 3, 1 / 6], [1 / 6, 2 / 3]])
_TRI_WEIGHTS = np.full(3, 1 / 6)


def _p2_gradients(xi, eta):
    """d(shape)/d(xi, eta) of the six gmsh-ordered P2 triangle shape functions."""
    l0 = 1 - xi - eta
    dxi = np.array([1 - 4 * l0, 4 * xi - 1, 0, 4 * (l0 - xi), 4 * eta, -4 * eta])
    deta = np.array([1 - 4 * l0, 0, 4 * eta - 1, -4 * xi, 4 * xi, 4 * (l0 - eta)])
    return dxi, deta


def area(mesh: FEMesh) -> float:
    """Area of a plane mesh [m^2], exact for its (straight or curved) elements."""
    if mesh.dim != 2:
        raise ValueError(f"area() needs a plane mesh, got {mesh.cell_type}")
    x = mesh.points[mesh.cells]  # (n, nodes, 2)
    if mesh.order == 1:
        a, b, c = x[:, 0], x[:, 1], x[:, 2]
        return float(0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1])
                                  - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])).sum())
    total = 0.0
    for (xi, eta), w in zip(_TRI_POINTS, _TRI_WEIGHTS):
        dxi, deta = _p2_gradients(xi, eta)
        jx = np.einsum("k,nkd->nd", dxi, x)
        je = np.einsum("k,nkd->nd", deta, x)
        total += w * np.abs(jx[:, 0] * je[:, 1] - jx[:, 1] * je[:, 0]).sum()
    return float(total)


def mass(mesh: FEMesh, face_width: float, density: float) -> float:
    """Mass of a plane mesh extruded by ``face_width`` [m] at ``density`` [kg/m^3]."""
    return area(mesh) * face_width * density
