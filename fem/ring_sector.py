"""Work-conjugate c_ru and c_r of an intact ring from ONE tooth pitch (SI units).

The intact ring is z identical tooth pitches (``meshing.ring_sector``); only the supports
on the held circle differ from pitch to pitch.  So the plane-stress stiffness of one
pitch is condensed (static condensation, exact) onto its boundary nodes: the two radial
cuts and the held arc,

    S = K_bb - K_bi K_ii^-1 K_ib,   G' = G_b - K_bi K_ii^-1 G_i,   C = G_i^T K_ii^-1 G_i,

with G the loads of 1 N along x and along y spread over the tooth's load patch.  The z
rotated copies of S assemble the ring's boundary system (cut nodes shared), the outer
nodes inside a support arc are held, and for a load of force ``a_k`` (2,) [N] on each
tooth k (in the pitch's own frame) the work of the loads is

    f^T u = F^T S^-1 F + sum_k a_k^T C a_k,   F = sum_k R_k G' a_k,

exactly what the whole ring meshed with the same pitch mesh gives
(``meshing.ring_sector.ring_from_sector`` with ``fem.ring_stiffness``).  One sparse
factorisation of the pitch interior (1/z of the ring) and one of the boundary system
(a few hundred DOFs per pitch) replace the factorisation of the whole ring.

``c_ru_work = T^2 / (f^T u) / r_b^2`` (``fem.ring_work``) at each carrier position, and
``c_r_work = F^2 / (f^T u)`` for 1 N along x and along y spread over all teeth.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.gear import rotation
from hubvib.meshing.ring_gear import RingGear
from hubvib.meshing.ring_sector import in_support

from .elasticity import plane_model, submatrix
from .material import Material
from .ring_stiffness import default_carrier_teeth, planet_teeth, tooth_forces
from .solvers import SingularSystemError, factorise, pick


@dataclass(frozen=True)
class SectorWork:
    """Work-conjugate stiffnesses of the ring from one pitch model.

    Attributes
    ----------
    c_ru_positions : ndarray
        ``T^2 / (f^T u) / r_b^2`` at each carrier position [N/m].
    c_r : float
        ``F^2 / (f^T u)`` of 1 N along x and along y spread over all teeth, mean [N/m].
    dofs : int
        DOFs of the whole ring with this pitch mesh (z pitches, cut nodes shared).
    sector_dofs, boundary_dofs : int
        DOFs of the pitch model and of the condensed ring system.
    seconds : dict
        assembly, condense, solve wall times [s].
    """

    c_ru_positions: np.ndarray
    c_r: float
    dofs: int
    sector_dofs: int
    boundary_dofs: int
    seconds: dict

    @property
    def c_ru(self) -> float:
        """Mean over the carrier positions [N/m]."""
        return float(np.mean(self.c_ru_positions))


def _boundary_node_dofs(model, groups) -> dict:
    """Mesh node -> its (x, y) DOFs, for every node of the facets of ``groups`` (vertices
    and, on curved meshes, mid-edge nodes: the DOFs of the facet they sit on)."""
    basis, fe = model.basis, model.basis.mesh
    dofs = {}
    for name in groups:
        facets = model.mesh.boundaries[name]
        for row, facet in zip(facets, fe.boundaries[name]):
            for node in row[:2]:
                dofs[int(node)] = tuple(basis.nodal_dofs[:, model.vertex_of[node]])
            if len(row) == 3:
                dofs[int(row[2])] = tuple(basis.facet_dofs[:, facet])
    return dofs


def sector_ring_work(ring: RingGear, sector: FEMesh, material: Material = Material(),
                     n_planets: int = 3, carrier_teeth=None, solver: str = "auto"
                     ) -> SectorWork:
    """c_ru_work at each carrier position (default: every tooth over one planet pitch)
    and c_r_work [N/m] of the intact ring whose tooth pitch is ``sector``
    (``meshing.ring_sector.sector_mesh``), plane stress over the face width."""
    from hubvib.meshing.ring_sector import cut_pairs

    if isinstance(n_planets, bool) or not isinstance(n_planets, int) or not 1 <= n_planets <= 12:
        raise ValueError(f"n_planets = {n_planets!r}, allowed integers 1..12")
    needed = {"tooth0_load", "tooth0_root", "cut_minus", "cut_plus", "outer"}
    if missing := sorted(needed - set(sector.boundaries)):
        raise ValueError(f"the pitch mesh lacks the groups {', '.join(missing)} "
                         "(meshing.ring_sector.sector_mesh makes them)")
    if carrier_teeth is None:
        carrier_teeth = default_carrier_teeth(ring, n_planets)
    z = ring.teeth
    t0 = time.perf_counter()
    model = plane_model(sector, material, ring.gear.face_width, "stress")
    patch = tooth_forces(model, [0])
    G = patch.loads(np.eye(2)[None, :, :])  # (ndofs, 2): 1 N along x, along y
    t1 = time.perf_counter()

    # boundary nodes: -pi/z cut, held arc (without the cut ends), +pi/z cut (paired)
    minus, plus = cut_pairs(sector, ring)
    outer = np.setdiff1d(np.unique(sector.boundaries["outer"]), np.concatenate([minus, plus]))
    nodes = np.concatenate([minus, outer, plus])
    where = _boundary_node_dofs(model, ("cut_minus", "cut_plus", "outer"))
    b = np.array([where[int(node)] for node in nodes], dtype=np.int64)  # (nb, 2)
    is_b = np.zeros(model.ndofs, dtype=bool)
    is_b[b.ravel()] = True
    interior = np.flatnonzero(~is_b)
    K = model.K.tocsr()
    K_ib = K[interior][:, b.ravel()].toarray()
    factor = factorise(submatrix(K, ~is_b), pick(solver, len(interior), 2))
    try:
        X = factor.solve(np.column_stack([K_ib, G[interior]]))
    finally:
        factor.free()
    nb2 = b.size
    S = K[b.ravel()][:, b.ravel()].toarray() - K_ib.T @ X[:, :nb2]
    Gc = G[b.ravel()] - K_ib.T @ X[:, nb2:]  # (nb2, 2)
    C = G[interior].T @ X[:, nb2:]  # (2, 2) [m/N]
    t2 = time.perf_counter()

    # ring boundary system: pitch k's node j -> global node; cut_plus -> next pitch's minus
    m, o = len(minus), len(outer)
    per = m + o
    nb = len(nodes)
    slot = np.arange(nb)
    slot[m + o:] = np.arange(m) + per  # shifted by one pitch below
    angles = np.array([ring.tooth_angle(k) for k in range(z)])
    R = np.stack([rotation(a) for a in angles])  # (z, 2, 2)
    glob = (np.arange(z)[:, None] * per + slot[None, :]) % (z * per)  # (z, nb)
    # rotated 2x2 blocks R_k S_ab R_k^T, assembled in COO
    blocks = S.reshape(nb, 2, nb, 2)
    rotated = np.einsum("kpi,aibj,kqj->kapbq", R, blocks, R, optimize=True)
    rows = (2 * glob[:, :, None, None, None] + np.arange(2)[None, None, :, None, None])
    cols = (2 * glob[:, None, None, :, None] + np.arange(2)[None, None, None, None, :])
    rows, cols = np.broadcast_arrays(rows, cols)
    n = 2 * z * per
    A = sp.coo_matrix((rotated.ravel(), (rows.ravel(), cols.ravel())), shape=(n, n)).tocsr()
    A = (A + A.T) * 0.5

    # held nodes: every node of an outer facet inside a support arc
    outer_facets = sector.boundaries["outer"]
    middle = (sector.points[outer_facets[:, 2]] if outer_facets.shape[1] == 3
              else sector.points[outer_facets[:, :2]].mean(axis=1))
    position = {node: i for i, node in enumerate(nodes)}
    facet_slots = np.vectorize(position.get)(outer_facets)
    held = np.zeros(n, dtype=bool)
    for k in range(z):
        inside = in_support(ring, np.arctan2(middle[:, 1], middle[:, 0]) + angles[k])
        fixed_nodes = glob[k, np.unique(facet_slots[inside])]
        held[2 * fixed_nodes] = held[2 * fixed_nodes + 1] = True
    if not held.any():
        raise SingularSystemError("no outer node of the ring lies in a support arc")

    # load cases: carrier positions (1 N along the line of action per loaded tooth), then
    # 1/z N along x and along y on every tooth; a_k in pitch k's own frame
    rb = ring.gear.base_diameter / 2
    direction = ring.load_point(0)[1]
    loaded = [planet_teeth(ring, int(s), n_planets) for s in carrier_teeth]
    cases = len(loaded) + 2
    a = np.zeros((z, 2, cases))
    for column, teeth in enumerate(loaded):
        for k in teeth:
            a[k, :, column] += direction
    a[:, :, -2] = np.einsum("kji,j->ki", R, np.array([1.0, 0.0])) / z
    a[:, :, -1] = np.einsum("kji,j->ki", R, np.array([0.0, 1.0])) / z
    local = np.einsum("nc,kcl->knl", Gc, a).reshape(z, nb, 2, cases)  # pitch frame
    turned = np.einsum("kpi,knil->knpl", R, local)
    F = np.zeros((n, cases))
    np.add.at(F, (2 * glob[:, :, None] + np.arange(2)[None, None, :]).ravel(),
              turned.reshape(-1, cases))
    free = np.flatnonzero(~held)
    system = factorise(A[free][:, free].tocsr(), pick(solver, len(free), 2))
    try:
        U = system.solve(F[free])
    finally:
        system.free()
    work = np.einsum("ic,ic->c", F[free], U) + np.einsum("kic,ij,kjc->c", a, C, a)
    t3 = time.perf_counter()
    if np.any(work <= 0):
        raise ValueError(f"the work of the ring loads is not positive ({work.min():.3e} N m)")
    torque = np.array([len(t) * rb for t in loaded])
    c_ru = torque ** 2 / work[:len(loaded)] / rb ** 2
    c_r = float(np.mean(1.0 / work[-2:]))
    dofs = 2 * z * (len(sector.points) - m)
    return SectorWork(c_ru, c_r, dofs, model.ndofs, len(free),
                      {"assembly": t1 - t0, "condense": t2 - t1, "solve": t3 - t2})
