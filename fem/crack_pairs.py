"""The two faces of a plane crack as pairs of coincident nodes, with the functionals of
their relative motion (SI units).

A cracked mesh carries the crack's faces as the boundary groups ``crack_a`` and
``crack_b``: the same geometry, separate nodes except at the tip.  Every node of face a
(P2: vertices and edge midpoints) has its twin on face b; the tip node is shared and
forms no pair.  At pair i

- the normal ``n_i`` is the outward normal of face a's material, so it points across the
  crack towards face b's material (a vertex: the mean of its edges' normals);
- the opening is ``g_i = n_i . (u_b - u_a)`` [m], positive when the faces are apart, and
  the slip ``s_i = t_i . (u_b - u_a)`` [m] with ``t_i`` the normal turned by +90 deg;
- the path length ``length_i`` [m] is the share of the crack path the node stands for:
  a quarter of each adjacent edge for a vertex, half its edge for a midpoint (the lengths
  sum to the crack's length less a quarter of the tip edge: the tip node is shared by both
  faces and forms no pair).

``G_n @ u`` and ``G_t @ u`` give the openings and slips from a DOF vector of the body
(its free DOFs); ``G_n.T @ lam`` is the load of pair forces ``lam`` [N] pushing the faces
apart (positive: a pressure between the faces).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp


class CrackPairsError(ValueError):
    """A body whose crack faces cannot be paired; the message says why."""


@dataclass(frozen=True, eq=False)
class CrackPairs:
    """Paired crack-face nodes of a plane body.

    Attributes
    ----------
    points : ndarray (pairs, 2)
        Position of each pair [m].
    normal : ndarray (pairs, 2)
        Unit normal of face a, towards face b [-].
    length : ndarray (pairs,)
        Crack path length each pair stands for [m].
    tip_distance : ndarray (pairs,)
        Distance of each pair from the crack tip [m].
    dofs_a, dofs_b : ndarray (pairs, 2)
        The model DOFs (x, y) of the node on face a and of its twin on face b.
    G_n, G_t : scipy.sparse.csr_matrix (pairs, free dofs)
        Relative normal opening and tangential slip [m per m].
    """

    points: np.ndarray
    normal: np.ndarray
    length: np.ndarray
    tip_distance: np.ndarray
    dofs_a: np.ndarray
    dofs_b: np.ndarray
    G_n: object
    G_t: object

    @property
    def count(self) -> int:
        return self.points.shape[0]

    @property
    def functionals(self):
        """(free dofs, 2 pairs): the loads of unit normal, then unit tangential pair forces."""
        return sp.vstack([self.G_n, self.G_t]).T.tocsc()


def crack_pairs(body) -> CrackPairs:
    """The crack-face pairs of ``body`` (``fem.ring_body.RingBody`` or any object with
    ``model`` (``PlaneModel``), ``expand`` (model dofs, free dofs) and ``tied``)."""
    if getattr(body, "tied", 0):
        raise CrackPairsError("the body's crack faces are tied (tie_crack=True): there is "
                              "nothing to pair; build it with the faces open")
    return pairs_of_model(body.model, body.expand)


def pairs_of_model(model, expand=None) -> CrackPairs:
    """The crack-face pairs of a plane ``model``; ``expand`` maps free to model DOFs
    (None: every DOF free)."""
    basis = model.basis
    mesh = basis.mesh
    groups = getattr(mesh, "boundaries", None) or {}
    if "crack_a" not in groups or "crack_b" not in groups:
        raise CrackPairsError("the mesh has no crack faces (boundary groups crack_a and "
                              "crack_b): an intact body has no crack pairs")
    facets_a, facets_b = np.asarray(groups["crack_a"]), np.asarray(groups["crack_b"])
    p = mesh.p
    scale = float(np.ptp(p, axis=1).max())
    tol = 1e-9 * scale

    ends_a = mesh.facets[:2, facets_a]
    tangent = p[:, ends_a[1]] - p[:, ends_a[0]]
    edge_length = np.linalg.norm(tangent, axis=0)
    normal = np.vstack([tangent[1], -tangent[0]]) / edge_length
    middle = 0.5 * (p[:, ends_a[0]] + p[:, ends_a[1]])
    element = mesh.f2t[0, facets_a]
    centroid = p[:, mesh.t[:3, element]].mean(axis=1)
    flip = np.einsum("ij,ij->j", middle - centroid, normal) < 0
    normal[:, flip] *= -1  # outward of face a's material

    twin = _match(middle, 0.5 * (p[:, mesh.facets[0, facets_b]] + p[:, mesh.facets[1, facets_b]]),
                  tol, "edge midpoints")
    mid_a = _facet_dofs(basis, facets_a)
    mid_b = _facet_dofs(basis, facets_b[twin])

    vertices_a = np.unique(ends_a)
    vertices_b = np.unique(mesh.facets[:2, facets_b])
    shared = np.intersect1d(vertices_a, vertices_b)
    if shared.size != 1:
        raise CrackPairsError(f"the crack faces share {shared.size} nodes; a crack with one "
                              "tip shares exactly one")
    tip = p[:, shared[0]]
    vertices_a = np.setdiff1d(vertices_a, shared)
    vertices_b = np.setdiff1d(vertices_b, shared)
    vtwin = _match(p[:, vertices_a], p[:, vertices_b], tol, "vertices")
    v_normal = np.zeros((2, vertices_a.size))
    v_length = np.zeros(vertices_a.size)
    index = {int(v): i for i, v in enumerate(vertices_a)}
    for j in range(facets_a.size):
        for end in ends_a[:, j]:
            i = index.get(int(end))
            if i is not None:
                v_normal[:, i] += normal[:, j]
                v_length[i] += 0.25 * edge_length[j]
    v_normal /= np.linalg.norm(v_normal, axis=0)
    nodal = basis.nodal_dofs

    points = np.hstack([p[:, vertices_a], middle]).T
    normals = np.hstack([v_normal, normal]).T
    lengths = np.concatenate([v_length, 0.5 * edge_length])
    dofs_a = np.vstack([nodal[:, vertices_a].T, mid_a])
    dofs_b = np.vstack([nodal[:, vertices_b[vtwin]].T, mid_b])
    order = np.argsort(np.linalg.norm(points - tip, axis=1))
    points, normals, lengths = points[order], normals[order], lengths[order]
    dofs_a, dofs_b = dofs_a[order], dofs_b[order]
    tangents = np.column_stack([-normals[:, 1], normals[:, 0]])

    def functional(direction):
        rows = np.repeat(np.arange(points.shape[0]), 4)
        cols = np.column_stack([dofs_b, dofs_a]).ravel()
        vals = np.column_stack([direction, -direction]).ravel()
        G = sp.csr_matrix((vals, (rows, cols)), shape=(points.shape[0], basis.N))
        return (G @ expand).tocsr() if expand is not None else G

    return CrackPairs(points, normals, lengths, np.linalg.norm(points - tip, axis=1),
                      dofs_a, dofs_b, functional(normals), functional(tangents))


def _facet_dofs(basis, facets) -> np.ndarray:
    """(facets, 2): the x and y DOFs of each facet's midpoint node (P2)."""
    dofs = basis.facet_dofs
    if dofs.shape[0] != 2:
        raise CrackPairsError(f"crack pairs need a P2 vector basis (one node per edge "
                              f"midpoint); this basis has {dofs.shape[0]} facet DOFs per edge")
    return dofs[:, facets].T


def _match(a: np.ndarray, b: np.ndarray, tol: float, what: str) -> np.ndarray:
    """For each column of ``a`` the column of ``b`` at the same place."""
    from scipy.spatial import cKDTree

    if a.shape[1] != b.shape[1]:
        raise CrackPairsError(f"crack faces: {a.shape[1]} {what} on face a, {b.shape[1]} on "
                              "face b")
    distance, twin = cKDTree(b.T).query(a.T)
    if a.shape[1] and (distance.max() > tol or np.unique(twin).size != twin.size):
        raise CrackPairsError(f"crack faces: the {what} of face a and face b do not coincide "
                              f"(largest distance {distance.max():.3g} m)")
    return twin
