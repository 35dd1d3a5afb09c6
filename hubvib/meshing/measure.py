"""Measures of an ``FEMesh`` computed from its own nodes (independent of the geometry)."""
from __future__ import annotations

import numpy as np

from .fe_mesh import TETRA10_EDGES, FEMesh

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


def _tet_rule():
    """Collapsed 3x3x3 Gauss rule on the reference tetrahedron (exact to degree 5)."""
    g, w = np.polynomial.legendre.leggauss(3)
    g, w = (g + 1) / 2, w / 2
    u, v, t = (a.ravel() for a in np.meshgrid(g, g, g, indexing="ij"))
    weights = np.einsum("i,j,k->ijk", w, w, w).ravel() * (1 - u) ** 2 * (1 - v)
    return np.column_stack([u, (1 - u) * v, (1 - u) * (1 - v) * t]), weights


def _tet10_gradients(x, y, z):
    """d(shape)/d(x, y, z) of the ten gmsh-ordered P2 tetrahedron shape functions, (3, 10)."""
    lam = np.array([1 - x - y - z, x, y, z])
    dlam = np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    grads = [(4 * lam[i] - 1) * dlam[i] for i in range(4)]
    grads += [4 * (lam[j] * dlam[i] + lam[i] * dlam[j]) for i, j in TETRA10_EDGES]
    return np.array(grads).T


def volume(mesh: FEMesh) -> float:
    """Volume of a solid mesh [m^3], exact for its (straight or curved) tetrahedra."""
    if mesh.dim != 3:
        raise ValueError(f"volume() needs a solid mesh, got {mesh.cell_type}")
    x = mesh.points[mesh.cells]
    if mesh.order == 1:
        edges = x[:, 1:] - x[:, :1]
        return float(np.abs(np.linalg.det(edges)).sum() / 6)
    points, weights = _tet_rule()
    total = 0.0
    for p, w in zip(points, weights):
        jac = np.einsum("dk,nke->ned", _tet10_gradients(*p), x)
        total += w * np.abs(np.linalg.det(jac)).sum()
    return float(total)


def mass(mesh: FEMesh, face_width: float, density: float) -> float:
    """Mass [kg] at ``density`` [kg/m^3]: a plane mesh is extruded by ``face_width`` [m]."""
    if mesh.dim == 3:
        return volume(mesh) * density
    return area(mesh) * face_width * density
