"""The plane ring solved by substructures: each piece condensed onto its cuts, the ring of
cuts solved, the pieces' interiors recovered (SI units).

The ring mesh glued from pieces (``meshing.ring_pieces``) is solved piece by piece.
Each piece's plane-stress stiffness (its held outer nodes fixed) is condensed exactly
onto the DOFs of its two cuts,

    S = K_bb - K_bi X,   X = K_ii^-1 K_ib,

the z pieces' S, turned to their places, assemble the ring's cut system (sparse: each
cut couples only with its two neighbours), loads inside a piece enter condensed
(``f_b - K_bi K_ii^-1 f_i``), and the interiors follow from the cut displacements,
``u_i = K_ii^-1 f_i - X u_b``.  On the same mesh this is the whole ring's solution to
round-off (static condensation is exact).  The pieces that do not hold the crack (the
plain pitch, held or free on its arc, and the pitches with a support end) are the same
for every crack case of a ring and options: their condensations are kept between calls,
so a crack case factorises the crack's block and the ring of cuts only.  With a store
(``set_condensation_store``, e.g. a result cache on disk) they are also shared between
processes and runs: a kept condensation pickles without its factorisation, which is
made again from ``K_ii`` when it is read back.

``substructured(pieces, model)`` returns a system with the interface of
``fem.elasticity.SupportedSystem`` (``solve``, ``release``, ``method``) for the model of
the glued mesh, so every load and measure of that model applies unchanged.
"""
from __future__ import annotations

import functools
import time
from dataclasses import dataclass

import numpy as np

from hubvib.foundation.blas import blas_threads
from hubvib.meshing.gear import rotation

from .elasticity import Solution, plane_model, submatrix
from .material import Material
from .solvers import factorise, pick


def node_dof_table(model) -> np.ndarray:
    """(nodes, 2): the x and y DOFs of every node of the model's mesh (vertices and, on
    curved meshes, mid-edge nodes)."""
    mesh, basis = model.mesh, model.basis
    table = np.full((len(mesh.points), 2), -1, dtype=np.int64)
    vertices = np.flatnonzero(model.vertex_of >= 0)
    table[vertices] = basis.nodal_dofs[:, model.vertex_of[vertices]].T
    if mesh.order == 2:
        t2f = basis.mesh.t2f
        for j in range(3):
            table[mesh.cells[:, 3 + j]] = basis.facet_dofs[:, t2f[j]].T
    if (table < 0).any():
        raise ValueError("a node of the mesh carries no DOF")
    return table


@dataclass(eq=False)
class Condensed:
    """One piece's stiffness condensed onto its cut nodes (module docstring).

    Attributes
    ----------
    boundary, interior : ndarray
        The piece model's DOFs on its cuts (node by node, x then y) and inside (neither
        cut nor held).
    S : ndarray
        Condensed stiffness on ``boundary`` [N/m].
    X : ndarray
        ``K_ii^-1 K_ib`` [-].
    coupling : scipy.sparse matrix
        ``K_bi`` [N/m].
    factor : fem.solvers.Factor
        The factorisation of ``K_ii``.
    table : ndarray
        The piece model's node DOF table (``node_dof_table``).
    dofs : int
        DOFs of the piece model.
    K_ii : scipy.sparse matrix
        The interior stiffness [N/m] (a pickled condensation factorises it again).
    method : str
        The solver of ``factor``.
    """

    boundary: np.ndarray
    interior: np.ndarray
    S: np.ndarray
    X: np.ndarray
    coupling: object
    factor: object
    table: np.ndarray
    dofs: int
    K_ii: object = None
    method: str = "superlu"

    def release(self) -> None:
        self.factor.free()

    @functools.cached_property
    def interior_rows(self) -> np.ndarray:
        """For each entry of ``table`` (raveled): its row among ``interior`` (-1: a cut or
        held DOF)."""
        rows = np.full(self.dofs, -1, dtype=np.int64)
        rows[self.interior] = np.arange(len(self.interior))
        return rows[self.table.ravel()]

    @functools.cached_property
    def table_rows(self) -> np.ndarray:
        """For each entry of ``table`` (raveled): its row in ``[interior; boundary; 0]``
        (the last row for a held DOF)."""
        rows = np.full(self.dofs, len(self.interior) + len(self.boundary), dtype=np.int64)
        rows[self.interior] = np.arange(len(self.interior))
        rows[self.boundary] = len(self.interior) + np.arange(len(self.boundary))
        return rows[self.table.ravel()]

    def __getstate__(self) -> dict:
        return {k: v for k, v in self.__dict__.items() if k != "factor"}

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        self.factor = factorise(self.K_ii, self.method)


def condense(mesh, cut_nodes, held_nodes, material: Material, thickness: float,
             solver: str = "auto") -> Condensed:
    """The plane-stress model of ``mesh`` with ``held_nodes`` fixed, condensed onto the
    DOFs of ``cut_nodes``."""
    model = plane_model(mesh, material, thickness, "stress")
    table = node_dof_table(model)
    boundary = table[np.asarray(cut_nodes)].ravel()
    kind = np.zeros(model.ndofs, dtype=np.int8)  # 0 interior, 1 boundary, 2 held
    kind[table[np.asarray(held_nodes, dtype=np.int64)].ravel()] = 2
    kind[boundary] = 1
    interior = np.flatnonzero(kind == 0)
    K = model.K.tocsr()
    K_ii = submatrix(K, kind == 0)
    method = pick(solver, len(interior), 2)
    factor = factorise(K_ii, method)
    K_bi = K[boundary][:, interior]
    X = factor.solve(K_bi.T.toarray())
    S = K[boundary][:, boundary].toarray() - K_bi @ X
    return Condensed(boundary, interior, (S + S.T) / 2, X, K_bi.tocsr(), factor, table,
                     model.ndofs, K_ii, method)


#: where kept condensations come from beside this process's memory
#: (``set_condensation_store``)
_STORE = None


def set_condensation_store(store) -> None:
    """Let ``store(compute, inputs)`` give the intact pieces' condensations (None: compute
    them here): it returns the ``Condensed`` that ``compute()`` returns for ``inputs``
    (the piece's mesh, cut and held nodes, material, thickness and solver), e.g. from a
    result cache on disk shared by processes and runs."""
    global _STORE
    _STORE = store


@functools.lru_cache(maxsize=64)
def _kept(mesh_key, mesh, cut_nodes: tuple, held_nodes: tuple, material: Material,
          thickness: float, solver: str) -> Condensed:
    def compute() -> Condensed:
        return condense(mesh, np.array(cut_nodes, dtype=np.int64),
                        np.array(held_nodes, dtype=np.int64), material, thickness, solver)
    if _STORE is None:
        return compute()
    return _STORE(compute, (mesh, cut_nodes, held_nodes, material, thickness, solver))


def piece_condensation(piece, material: Material, thickness: float,
                       solver: str = "auto") -> Condensed:
    """The condensation of ``piece`` (``meshing.ring_pieces.Piece``); an intact piece's
    is kept between calls (the same mesh object and held nodes give the same one)."""
    cut, held = piece.cut_nodes, piece.held_nodes
    if piece.kind == "block":
        return condense(piece.mesh, cut, held, material, thickness, solver)
    return _kept(id(piece.mesh), piece.mesh, tuple(cut.tolist()), tuple(held.tolist()),
                 material, thickness, solver)


def _turn(values: np.ndarray, angle: float) -> np.ndarray:
    """(nodes, 2, ...) vectors turned by ``angle`` [rad]."""
    return np.einsum("ij,nj...->ni...", rotation(angle), values)


@dataclass(eq=False)
class SubstructuredSystem:
    """The glued ring's stiffness with its supports, solved by substructures.

    ``solve(loads)`` gives what ``fem.elasticity.supported(model, ["supports"])``
    would: the displacements [m] of the glued model under ``loads`` [N]."""

    ndofs: int
    parts: list  # (piece, Condensed, glued DOF table (nodes, 2))
    interface: np.ndarray  # glued DOFs of the cut nodes, free ones only
    factor: object  # of the cut system
    positions: list  # per part: index into ``interface`` of its boundary DOFs (-1 held)
    seconds: float

    @property
    def method(self) -> str:
        return self.factor.method

    def solve(self, loads: np.ndarray) -> Solution:
        started = time.perf_counter()
        f = np.asarray(loads, dtype=float)
        columns = f.reshape(self.ndofs, -1)
        m = columns.shape[1]
        u = np.zeros_like(columns)
        rhs = columns[self.interface].copy()
        # interior loads of every loaded part, solved together per condensation (one call
        # each); a part without loads has none inside (its interior follows from its cuts)
        groups: dict = {}
        for index, (piece, part, glued) in enumerate(self.parts):
            on_part = columns[glued]  # (nodes, 2, m)
            if not on_part.any():
                continue
            turned = _turn(on_part, -piece.angle).reshape(-1, m)
            rows = part.interior_rows
            f_i = np.zeros((len(part.interior), m))
            f_i[rows[rows >= 0]] = turned[rows >= 0]
            groups.setdefault(id(part), (part, []))[1].append((index, f_i))
        inner = [None] * len(self.parts)
        for part, members in groups.values():
            stacked = np.hstack([f_i for _, f_i in members])
            used = np.flatnonzero(np.any(stacked != 0, axis=0))
            solved = np.zeros_like(stacked)
            if len(used):
                with blas_threads(1):
                    solved[:, used] = part.factor.solve(stacked[:, used])
            for j, (index, _) in enumerate(members):
                inner[index] = solved[:, j * m:(j + 1) * m]
        for (piece, part, glued), where, y in zip(self.parts, self.positions, inner):
            if y is None:
                continue
            condensed = -(part.coupling @ y)  # (boundary, m), piece frame
            turned = _turn(condensed.reshape(-1, 2, m), piece.angle).reshape(-1, m)
            keep = where >= 0
            np.add.at(rhs, where[keep], turned[keep])
        u_cut = self.factor.solve(rhs)
        u[self.interface] = u_cut
        with blas_threads(1):  # many small products: threads only contend
            for (piece, part, glued), where, y in zip(self.parts, self.positions, inner):
                u_b = np.zeros((len(where), m))
                u_b[where >= 0] = u_cut[where[where >= 0]]
                u_b = _turn(u_b.reshape(-1, 2, m), -piece.angle).reshape(-1, m)
                n_i = len(part.interior)
                local = np.empty((n_i + len(part.boundary) + 1, m))  # interior, cuts, held 0
                local[:n_i] = -(part.X @ u_b) if y is None else y - part.X @ u_b
                local[n_i:-1] = u_b
                local[-1] = 0.0
                values = local[part.table_rows].reshape(len(glued), 2, m)  # (nodes, 2, m)
                u[glued.ravel()] = _turn(values, piece.angle).reshape(-1, m)
        return Solution(u.reshape(f.shape), time.perf_counter() - started, self.method)

    def release(self) -> None:
        """Free the block's and the cut system's factorisations (the intact pieces' are
        kept for the next case)."""
        self.factor.free()
        for piece, part, _ in self.parts:
            if piece.kind == "block":
                part.release()


def substructured(pieces, model, material: Material, thickness: float,
                  solver: str = "auto") -> SubstructuredSystem:
    """The substructured system of ``pieces`` (``meshing.ring_pieces.RingPieces``) for
    ``model``, the plane model of ``pieces.mesh``."""
    from .substructure_cuts import cut_system

    started = time.perf_counter()
    table = node_dof_table(model)
    parts = []
    for piece in pieces.pieces:
        part = piece_condensation(piece, material, thickness, solver)
        parts.append((piece, part, table[piece.nodes]))
    held = np.zeros(model.ndofs, dtype=bool)
    held[model.basis.get_dofs("supports").flatten()] = True
    interface, positions, factor = cut_system(parts, held, model.ndofs, solver)
    return SubstructuredSystem(model.ndofs, parts, interface, factor, positions,
                               time.perf_counter() - started)
