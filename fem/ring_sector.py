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
(``meshing.ring_sector.ring_from_sector`` with ``fem.ring_stiffness``).  In practice the
condensation is PARDISO's Schur complement (one factorisation of the pitch, 1/z of the
ring), the held arc is condensed densely once per pattern of held facets, and the ring of
cuts is solved by block Cholesky around the ring (``cyclic_block_solve``).

``c_ru_work = T^2 / (f^T u) / r_b^2`` (``fem.ring_work``) at each carrier position, and
``c_r_work = F^2 / (f^T u)`` for 1 N along x and along y spread over all teeth.
"""
from __future__ import annotations

import ctypes
import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.linalg import cho_factor, cho_solve, solve_triangular

from hubvib.foundation.blas import blas_threads
from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.gear import rotation
from hubvib.meshing.ring_gear import RingGear
from hubvib.meshing.ring_sector import cut_pairs, in_support

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
        DOFs of the pitch model and of the condensed ring system (the free cut DOFs).
    patterns : int
        Distinct patterns of held outer facets over the pitches (one dense condensation
        of the held arc each).
    seconds : dict
        condense (model, loads and condensation of the pitch) and solve (the held arcs
        and the ring of cuts) wall times [s].
    """

    c_ru_positions: np.ndarray
    c_r: float
    dofs: int
    sector_dofs: int
    boundary_dofs: int
    patterns: int
    seconds: dict

    @property
    def c_ru(self) -> float:
        """Mean over the carrier positions [N/m]."""
        return float(np.mean(self.c_ru_positions))


#: MKL threads of the Schur factorisation (pitch models are small: on a busy 2-core
#: machine a second thread mostly waits)
THREADS = 1


def _boundary_node_dofs(model, groups, nodes) -> np.ndarray:
    """(len(nodes), 2): the x and y DOFs of mesh ``nodes``, each a node of a facet of
    ``groups`` (a vertex or, on curved meshes, a mid-edge node: the DOFs of its facet)."""
    basis, fe = model.basis, model.basis.mesh
    dofs = np.full((len(model.mesh.points), 2), -1, dtype=np.int64)
    for name in groups:
        facets = model.mesh.boundaries[name]
        ends = facets[:, :2].ravel()
        dofs[ends] = basis.nodal_dofs[:, model.vertex_of[ends]].T
        if facets.shape[1] == 3:
            dofs[facets[:, 2]] = basis.facet_dofs[:, fe.boundaries[name]].T
    out = dofs[nodes]
    if (out < 0).any():
        raise ValueError("a boundary node of the pitch mesh carries no DOF")
    return out


def _solved_condensation(K, G, boundary, interior, method):
    """S, G', C (module docstring) by solving K_ii X = [K_ib, G_i] (one column per
    boundary DOF)."""
    K_bi = K[boundary][:, interior].tocsr()  # sparse: only the DOFs next to the boundary
    is_b = np.ones(K.shape[0], dtype=bool)
    is_b[interior] = False
    factor = factorise(submatrix(K, ~is_b), method)
    try:
        X = factor.solve(np.column_stack([K_bi.T.toarray(), G[interior]]))
    finally:
        factor.free()
    nb2 = len(boundary)
    S = K[boundary][:, boundary].toarray() - K_bi @ X[:, :nb2]
    return S, G[boundary] - K_bi @ X[:, nb2:], G[interior].T @ X[:, nb2:]


def _pardiso_condensation(K, G, boundary):
    """S, G', C (module docstring) as PARDISO's Schur complement (``iparm[35] = 1``: the
    factorisation stops before the boundary block and returns its Schur complement,
    dense) of K bordered by two virtual DOFs that carry the loads:

        [[K, -G], [-G^T, 0]]  ->  [[S, -G'], [-G'^T, -C]]  on (boundary, virtual),

    so one factorisation gives all three, with no right-hand side per boundary DOF."""
    from .pardiso import PardisoError, mkl_library

    n = K.shape[0]
    order = np.argsort(boundary)
    bordered = sp.bmat([[K, sp.csr_matrix(-G)], [sp.csr_matrix(-G.T), None]], format="csr")
    upper = sp.triu(bordered, format="coo")
    # PARDISO wants every diagonal entry stored: the virtual DOFs' zeros explicitly
    upper = sp.csr_matrix((np.r_[upper.data, 0.0, 0.0],
                           (np.r_[upper.row, n, n + 1], np.r_[upper.col, n, n + 1])),
                          shape=bordered.shape)
    upper.sort_indices()
    rows = len(boundary) + 2
    indptr = np.ascontiguousarray(upper.indptr, dtype=np.int32)
    indices = np.ascontiguousarray(upper.indices, dtype=np.int32)
    data = np.ascontiguousarray(upper.data, dtype=np.float64)
    if len(indices) != upper.nnz or not (indptr[1:] > indptr[:-1]).all():
        raise ValueError("PARDISO Schur complement: a row of the bordered matrix is empty")
    schur = np.zeros(n + 2, dtype=np.int32)
    schur[boundary] = 1
    schur[n:] = 1
    pt = np.zeros(64, dtype=np.int64)
    iparm = np.zeros(64, dtype=np.int32)
    iparm[0], iparm[1], iparm[9], iparm[34], iparm[35] = 1, 2, 8, 1, 1
    out = np.zeros(rows * rows)
    pardiso = mkl_library()
    i32 = ctypes.c_int32
    pointer = ctypes.POINTER(i32)

    def call(phase):
        error = i32(0)
        pardiso(pt.ctypes.data_as(ctypes.POINTER(ctypes.c_int64)), ctypes.byref(i32(1)),
                ctypes.byref(i32(1)), ctypes.byref(i32(2)), ctypes.byref(i32(phase)),
                ctypes.byref(i32(n + 2)), data.ctypes.data, indptr.ctypes.data_as(pointer),
                indices.ctypes.data_as(pointer), schur.ctypes.data_as(pointer),
                ctypes.byref(i32(1)), iparm.ctypes.data_as(pointer), ctypes.byref(i32(0)),
                np.zeros(1).ctypes.data, out.ctypes.data, ctypes.byref(error))
        if error.value != 0:
            raise PardisoError(error.value, phase)

    try:
        with blas_threads(THREADS):
            call(12)  # analysis and factorisation up to the Schur block
    finally:
        call(-1)
    full = out.reshape(rows, rows)  # rows and columns in index order: boundary, virtual
    position = np.empty(len(boundary), dtype=np.int64)
    position[order] = np.arange(len(boundary))
    S = full[np.ix_(position, position)]
    S = (S + S.T) / 2
    return S, -full[position, -2:], -full[-2:, -2:]


@dataclass(frozen=True, eq=False)
class PitchCondensation:
    """One pitch's stiffness condensed onto its boundary nodes (module docstring).

    Attributes
    ----------
    S : ndarray (2 nb, 2 nb)
        Schur complement on the boundary nodes' x, y DOFs [N/m], node order ``minus``,
        ``outer``, ``plus``.
    G : ndarray (2 nb, 2)
        Condensed loads of 1 N along x and along y on the load patch [N/N].
    C : ndarray (2, 2)
        Interior compliance of those loads, ``G_i^T K_ii^-1 G_i`` [m/N].
    minus, outer, plus : ndarray
        Mesh nodes of the -pi/z cut, of the held arc without the cut ends, and of the
        +pi/z cut paired with ``minus``.
    dofs : int
        DOFs of the pitch model.
    """

    S: np.ndarray
    G: np.ndarray
    C: np.ndarray
    minus: np.ndarray
    outer: np.ndarray
    plus: np.ndarray
    dofs: int


def condense_pitch(ring: RingGear, sector: FEMesh, material: Material = Material(),
                   solver: str = "auto") -> PitchCondensation:
    """Plane-stress model of the pitch over the face width, condensed exactly onto its cuts
    and held arc (PARDISO's Schur complement, else one solve per boundary DOF)."""
    model = plane_model(sector, material, ring.gear.face_width, "stress")
    G = tooth_forces(model, [0]).loads(np.eye(2)[None, :, :])  # 1 N along x, along y
    minus, plus = cut_pairs(sector, ring)
    outer = np.setdiff1d(np.unique(sector.boundaries["outer"]), np.concatenate([minus, plus]))
    nodes = np.concatenate([minus, outer, plus])
    b = _boundary_node_dofs(model, ("cut_minus", "cut_plus", "outer"), nodes).ravel()
    is_b = np.zeros(model.ndofs, dtype=bool)
    is_b[b] = True
    interior = np.flatnonzero(~is_b)
    K = model.K.tocsr()
    method = pick(solver, len(interior), 2)
    if method == "pardiso":
        S, Gc, C = _pardiso_condensation(K, G, b)
    else:
        S, Gc, C = _solved_condensation(K, G, b, interior, method)
    return PitchCondensation(S, Gc, C, minus, outer, plus, model.ndofs)


def _held_patterns(ring: RingGear, sector: FEMesh, pitch: PitchCondensation):
    """Which outer nodes each pitch holds (those of its outer facets inside a support
    arc): the distinct patterns (held boundary slots), each pitch's pattern and, per cut
    node, whether it is held (cut z is cut 0)."""
    z, m, o = ring.teeth, len(pitch.minus), len(pitch.outer)
    nodes = np.concatenate([pitch.minus, pitch.outer, pitch.plus])
    facets = sector.boundaries["outer"]
    middle = (sector.points[facets[:, 2]] if facets.shape[1] == 3
              else sector.points[facets[:, :2]].mean(axis=1))
    slot_of = np.full(len(sector.points), -1, dtype=np.int64)
    slot_of[nodes] = np.arange(len(nodes))
    facet_slots = slot_of[facets]
    held = np.zeros((z + 1, m), dtype=bool)
    pattern_of = np.empty(z, dtype=np.int64)
    patterns: dict = {}
    for k in range(z):
        inside = in_support(ring, np.arctan2(middle[:, 1], middle[:, 0]) + ring.tooth_angle(k))
        held_slots = np.unique(facet_slots[inside])
        pattern_of[k] = patterns.setdefault(tuple(held_slots), len(patterns))
        held[k] |= np.isin(np.arange(m), held_slots)
        held[k + 1] |= np.isin(m + o + np.arange(m), held_slots)
    held[0] |= held[z]
    if not held.any():
        raise SingularSystemError("no outer node of the ring lies in a support arc")
    return list(patterns), pattern_of, held[:z]


def _cut_blocks(pitch: PitchCondensation, patterns: list, z: int):
    """Per pattern, the pitch condensed further onto its two cuts (free held-arc nodes
    condensed densely, held ones dropped): stiffness (4m, 4m), loads (4m, 2) and interior
    compliance (2, 2).  Cut j's DOFs are x, y in pitch j's frame, so the +pi/z cut enters
    turned by one pitch (u in frame k = Q u in frame k+1, Q the rotation by 2 pi / z):
    the same turn for every pitch, so no block is rotated per pitch."""
    m, o = len(pitch.minus), len(pitch.outer)
    S, Gc, C = pitch.S, pitch.G, pitch.C
    cut_slots = np.concatenate([np.arange(m), m + o + np.arange(m)])
    cut = (2 * cut_slots[:, None] + np.arange(2)).ravel()
    turn = np.eye(4 * m)
    turn[2 * m:, 2 * m:] = np.kron(np.eye(m), rotation(2 * math.pi / z))
    S_cut = np.empty((len(patterns), 4 * m, 4 * m))
    G_cut = np.empty((len(patterns), 4 * m, 2))
    C_cut = np.empty((len(patterns), 2, 2))
    with blas_threads(1):  # small dense kernels: more threads only wait (foundation.blas)
        for p, held_slots in enumerate(patterns):
            free = np.setdiff1d(np.arange(m, m + o), held_slots)
            f = (2 * free[:, None] + np.arange(2)).ravel()
            solved = cho_solve(cho_factor(S[np.ix_(f, f)], check_finite=False),
                               np.column_stack([S[f][:, cut], Gc[f]]), check_finite=False)
            coupling = S[cut][:, f]
            S_cut[p] = turn.T @ (S[np.ix_(cut, cut)] - coupling @ solved[:, :4 * m]) @ turn
            G_cut[p] = turn.T @ (Gc[cut] - coupling @ solved[:, 4 * m:])
            C_cut[p] = C + Gc[f].T @ solved[:, 4 * m:]
    return S_cut, G_cut, C_cut


def _tooth_forces(ring: RingGear, loaded: list) -> np.ndarray:
    """(z, 2, cases): force [N] on each tooth in its pitch's frame: 1 N along the line of
    action on each loaded tooth per carrier position, then 1/z N along x and along y
    (ring frame) on every tooth."""
    z = ring.teeth
    angles = np.array([ring.tooth_angle(k) for k in range(z)])
    a = np.zeros((z, 2, len(loaded) + 2))
    for column, teeth in enumerate(loaded):
        for k in teeth:
            a[k, :, column] += ring.load_point(0)[1]
    a[:, :, -2] = np.column_stack([np.cos(angles), -np.sin(angles)]) / z  # R_k^T e_x
    a[:, :, -1] = np.column_stack([np.sin(angles), np.cos(angles)]) / z  # R_k^T e_y
    return a


def sector_ring_work(ring: RingGear, sector: FEMesh, material: Material = Material(),
                     n_planets: int = 3, carrier_teeth=None, solver: str = "auto"
                     ) -> SectorWork:
    """c_ru_work at each carrier position (default: every tooth over one planet pitch)
    and c_r_work [N/m] of the intact ring whose tooth pitch is ``sector``
    (``meshing.ring_sector.sector_mesh``), plane stress over the face width."""
    if isinstance(n_planets, bool) or not isinstance(n_planets, int) or not 1 <= n_planets <= 12:
        raise ValueError(f"n_planets = {n_planets!r}, allowed integers 1..12")
    needed = {"tooth0_load", "cut_minus", "cut_plus", "outer"}
    if missing := sorted(needed - set(sector.boundaries)):
        raise ValueError(f"the pitch mesh lacks the groups {', '.join(missing)} "
                         "(meshing.ring_sector.sector_mesh makes them)")
    if carrier_teeth is None:
        carrier_teeth = default_carrier_teeth(ring, n_planets)
    z = ring.teeth
    t0 = time.perf_counter()
    pitch = condense_pitch(ring, sector, material, solver)
    t1 = time.perf_counter()
    patterns, pattern_of, held = _held_patterns(ring, sector, pitch)
    S_cut, G_cut, C_cut = _cut_blocks(pitch, patterns, z)
    loaded = [planet_teeth(ring, int(s), n_planets) for s in carrier_teeth]
    a = _tooth_forces(ring, loaded)
    m = len(pitch.minus)
    local = np.einsum("knc,kcl->knl", G_cut[pattern_of], a)  # (z, 4m, cases), cut frames
    F = np.zeros((z + 1, 2 * m, a.shape[-1]))  # load on each cut, cut z is cut 0
    F[:z] += local[:, :2 * m]
    F[1:] += local[:, 2 * m:]
    F[0] += F[z]
    with blas_threads(1):
        U = cyclic_block_solve(S_cut[pattern_of], np.repeat(held, 2, axis=1), F[:z])
    work = (np.einsum("jic,jic->c", F[:z], U)
            + np.einsum("kic,kij,kjc->c", a, C_cut[pattern_of], a))
    t2 = time.perf_counter()
    if np.any(work <= 0):
        raise ValueError(f"the work of the ring loads is not positive ({work.min():.3e} N m)")
    rb = ring.gear.base_diameter / 2
    torque = np.array([len(t) * rb for t in loaded])
    return SectorWork(torque ** 2 / work[:len(loaded)] / rb ** 2, float(np.mean(1.0 / work[-2:])),
                      2 * z * (len(sector.points) - m), pitch.dofs, 2 * int((~held).sum()),
                      len(patterns), {"condense": t1 - t0, "solve": t2 - t1})


def cyclic_block_solve(blocks: np.ndarray, held: np.ndarray, loads: np.ndarray) -> np.ndarray:
    """Solve the ring's cut system: z cuts of d DOFs each, pitch k coupling cut k (its first
    d rows of ``blocks[k]``, (z, 2d, 2d)) with cut k+1 (mod z) (its last d rows); ``held``
    (z, d) DOFs are zero; ``loads`` (z, d, cases).  Block Cholesky along the chain of
    cuts 1..z-1 with cut 0 as the border that closes the ring: per cut one Cholesky factor
    L and one triangular solve W = L^-1 [border, load, coupling to the next cut], then
    symmetric updates, O(z d^3).  Returns the displacements (z, d, cases), zero where
    held."""
    z, d2 = blocks.shape[:2]
    d = d2 // 2
    free = [np.flatnonzero(~held[j]) for j in range(z)]

    def diagonal(j):
        return (blocks[j][:d, :d] + blocks[j - 1][d:, d:])[np.ix_(free[j], free[j])]

    def coupling(j):  # rows: cut j, columns: cut j+1
        return blocks[j][:d, d:][np.ix_(free[j], free[(j + 1) % z])]

    D0 = diagonal(0)
    r0 = loads[0][free[0]].copy()
    D, B, r = diagonal(1), coupling(0).T, loads[1][free[1]].copy()  # B: cut 1 x cut 0
    steps = [None] * z
    for j in range(1, z):
        if j == z - 1:
            B = B + coupling(z - 1)
        E = coupling(j) if j < z - 1 else np.zeros((len(free[j]), 0))
        L = cho_factor(D, lower=True, check_finite=False)[0]  # upper triangle unused
        W = solve_triangular(L, np.column_stack([B, r, E]), lower=True, check_finite=False)
        nb, nr = B.shape[1], r.shape[1]
        W_B, W_r, W_E = W[:, :nb], W[:, nb:nb + nr], W[:, nb + nr:]
        steps[j] = (L, W_B, W_r, W_E)
        D0 = D0 - W_B.T @ W_B
        r0 = r0 - W_B.T @ W_r
        if j < z - 1:
            D = diagonal(j + 1) - W_E.T @ W_E
            B = -(W_E.T @ W_B)
            r = loads[j + 1][free[j + 1]] - W_E.T @ W_r
    out = np.zeros((z, d, loads.shape[-1]))
    x0 = cho_solve(cho_factor(D0, lower=True, check_finite=False), r0, check_finite=False)
    out[0][free[0]] = x0
    after = None
    for j in range(z - 1, 0, -1):
        L, W_B, W_r, W_E = steps[j]
        right = W_r - W_B @ x0
        if j < z - 1:
            right = right - W_E @ after
        after = solve_triangular(L, right, lower=True, trans="T", check_finite=False)
        out[j][free[j]] = after
    return out
