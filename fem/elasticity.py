"""Plane linear elasticity on an ``FEMesh`` with scikit-fem (SI units).

DOF ordering is scikit-fem's for ``ElementVector``: use ``model.basis`` to
find the DOFs of a boundary (``basis.get_dofs(name)``) and
``model.basis.probes`` to read displacements at points.
"""
from __future__ import annotations

import functools
import time
from dataclasses import dataclass, field

import numpy as np

from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.to_skfem import to_skfem

from .basis import vector_basis
from .facets import facet_basis
from .fast_assembly import BlockMatrix, elasticity_block_matrix
from .locate import interpolation_matrix
from .material import Material, MaterialError
from .solvers import (DOUBLE_COLUMNS, SingularSystemError, factorise, factorise_free_blocks,
                      pick)

__all__ = ["PlaneModel", "plane_model", "Solution", "solve", "supported", "SupportedSystem",
           "rigid_body_modes", "SingularSystemError"]


@dataclass(eq=False)
class PlaneModel:
    """Assembled plane-elasticity model.

    Attributes
    ----------
    basis : skfem.Basis
        Vector basis (P1 or P2, on the mesh's own curved geometry).
    K : scipy.sparse.csr_matrix
        Stiffness [N/m], including the thickness.
    thickness : float
        [m]
    timings : dict
        Seconds for ``to_skfem``, ``basis`` and ``assembly``.
    blocks : fem.fast_assembly.BlockMatrix
        The same stiffness as its upper triangle of 2 x 2 node blocks [N/m].
    """

    mesh: FEMesh
    basis: object
    K: object
    material: Material
    thickness: float
    plane: str
    timings: dict = field(default_factory=dict)
    vertex_of: np.ndarray | None = None
    blocks: BlockMatrix | None = None

    def node_dofs(self, nodes, component: int) -> np.ndarray:
        """DOF indices of displacement ``component`` (0: x, 1: y) at mesh corner ``nodes``."""
        vertices = self.vertex_of[np.asarray(nodes)]
        if np.any(vertices < 0):
            raise ValueError("node_dofs: mid-edge nodes carry no vertex DOFs")
        return self.basis.nodal_dofs[component, vertices]

    @property
    def ndofs(self) -> int:
        return self.K.shape[0]

    def facet_basis(self, groups: list[str]):
        """skfem FacetBasis on the union of named boundaries (curved geometry; exact
        reference points, ``fem.facets``: no Newton iteration that can fail on fine meshes)."""
        fe = self.basis.mesh
        missing = [g for g in groups if g not in fe.boundaries or len(fe.boundaries[g]) == 0]
        if missing:
            raise KeyError(f"the mesh has no boundary group {', '.join(map(repr, missing))}")
        facets = np.concatenate([fe.boundaries[g] for g in groups])
        return facet_basis(fe, self.basis.elem, facets, 2 * self.mesh.order, self.basis.dofs)

    def unit_traction_loads(self, facet_basis) -> np.ndarray:
        """Load vectors (2, ndofs) of a uniform 1 Pa traction along x and along y [N]."""
        import skfem

        loads = []
        for i in range(2):
            @skfem.LinearForm
            def load(v, w, i=i):
                return self.thickness * v[i]
            loads.append(load.assemble(facet_basis))
        return np.array(loads)

    def probes(self, points: np.ndarray):
        """Sparse matrix (2 n, ndofs) giving u_x at the n ``points`` [m], then u_y.

        scikit-fem's own ``probes`` has no element finder for curved meshes:
        the cell is found on the straight-sided mesh of the corner nodes, then
        the isoparametric map is inverted by Newton (``fem.locate``, robust on
        fine meshes).  Points within the sagitta of a curved boundary edge may be
        missed: keep them ~10 um inside.
        """
        basis = self.basis
        points = np.asarray(points, dtype=float).reshape(-1, 2).T
        try:
            cells = self._element_finder(*points)
        except ValueError:
            raise ValueError("a probe point lies outside the mesh") from None
        return interpolation_matrix(basis, points, cells)

    @functools.cached_property
    def _element_finder(self):
        import skfem

        fe = self.basis.mesh
        return skfem.MeshTri1(fe.p, fe.t[:3]).element_finder()

    def energy(self, u: np.ndarray) -> float:
        """Strain energy 1/2 u^T K u [J]."""
        return 0.5 * float(u @ (self.K @ u))


def plane_model(mesh: FEMesh, material: Material = Material(), thickness: float = 1.0,
                plane: str = "stress") -> PlaneModel:
    """Assemble K for a plane mesh; P1 or P2 follows the mesh order."""
    import skfem

    if mesh.dim != 2:
        raise ValueError(f"plane_model needs a plane mesh, got {mesh.cell_type}")
    if not (isinstance(thickness, (int, float)) and np.isfinite(thickness) and thickness > 0):
        raise MaterialError(f"thickness = {thickness!r}, allowed > 0 [m]")
    lam, mu = material.lame(plane)
    t0 = time.perf_counter()
    fe, vertex_of = to_skfem(mesh)
    t1 = time.perf_counter()
    basis = vector_basis(fe, skfem.ElementTriP2() if mesh.order == 2 else skfem.ElementTriP1(),
                         2 * mesh.order)
    t2 = time.perf_counter()
    blocks = elasticity_block_matrix(basis, lam, mu).scaled(thickness)
    K = blocks.csr()
    t3 = time.perf_counter()
    return PlaneModel(mesh, basis, K, material, thickness, plane,
                      {"to_skfem": t1 - t0, "basis": t2 - t1, "assembly": t3 - t2}, vertex_of,
                      blocks)


@dataclass(frozen=True)
class Solution:
    """Displacements [m] for each load column, the solve time [s] and the solver used."""

    u: np.ndarray
    seconds: float
    solver: str = "superlu"


def dof_components(basis) -> np.ndarray:
    """Displacement component (0: x, 1: y, 2: z) of every DOF of a vector basis."""
    dim = basis.mesh.dim()
    component = np.full(basis.N, -1)
    for name in ("nodal_dofs", "edge_dofs", "facet_dofs", "interior_dofs"):
        dofs = getattr(basis, name)
        if dofs.size:
            for c in range(dim):
                component[dofs[c::dim]] = c
    return component


def rigid_body_modes(basis) -> np.ndarray:
    """(ndofs, 3 or 6): translations, then rotations about the axes, as DOF vectors
    (exact for isoparametric P1/P2, which reproduce linear fields)."""
    component = dof_components(basis)
    x = basis.doflocs
    dim = x.shape[0]
    modes = [(component == c).astype(float) for c in range(dim)]
    axes = [(0, 1)] if dim == 2 else [(0, 1), (1, 2), (2, 0)]
    for a, b in axes:  # rotation in the (a, b) plane: u_a = -x_b, u_b = x_a
        modes.append(np.where(component == a, -x[b], 0.0) + np.where(component == b, x[a], 0.0))
    return np.column_stack(modes)


@dataclass(eq=False)
class SupportedSystem:
    """A model's stiffness with supports, factorised once: ``solve`` any number of load sets.

    Attributes
    ----------
    ndofs : int
        DOFs of the model.
    free : ndarray
        Indices of the unsupported DOFs.
    factor : fem.solvers.Factor
        The factorisation of K on them.
    seconds : float
        Wall time of the support check, the extraction and the factorisation [s].
    """

    ndofs: int
    free: np.ndarray
    factor: object
    seconds: float

    @property
    def method(self) -> str:
        return self.factor.method

    def solve(self, loads: np.ndarray) -> Solution:
        """Displacements [m] under ``loads`` [N], (ndofs,) or (ndofs, k); zero at the supports.
        ``Solution.seconds`` is this solve's time."""
        f = np.asarray(loads, dtype=float)
        if f.shape[0] != self.ndofs:
            raise ValueError(f"loads have {f.shape[0]} rows, the model {self.ndofs} DOFs")
        started = time.perf_counter()
        columns = f.reshape(self.ndofs, -1)
        u = np.zeros_like(columns)
        u[self.free] = self.factor.solve(columns[self.free])
        return Solution(u.reshape(f.shape), time.perf_counter() - started, self.method)

    def release(self) -> None:
        """Free the factorisation's memory."""
        self.factor.free()


def supported(model, fixed_groups: list[str], fixed_dofs=(), solver: str = "auto",
              columns: int = 1) -> SupportedSystem:
    """Factorise K with zero displacement on ``fixed_groups`` (every component) and at
    ``fixed_dofs`` (DOF indices, e.g. from ``PlaneModel.node_dofs``).  A half-width solid
    model (``fem.solid``, ``mirror_z`` set) also gets u_z = 0 on its mid-plane
    (``mirror_dofs``), always.

    ``columns``: how many load columns are to be solved; 3D PARDISO factorises in single
    precision and refines each solve, from ``fem.solvers.DOUBLE_COLUMNS`` columns on in
    double precision (the cheaper of the two there).

    ``solver``: one of ``fem.solvers.SOLVERS``; ``"auto"`` picks by size and dimension.
    PARDISO works on the node blocks when the supports hold whole nodes (in 3D always).  Raises
    SingularSystemError when nothing is fixed, when the supports leave a rigid-body
    motion, or when the solver finds the reduced matrix singular.
    """
    fe = model.basis.mesh
    missing = [g for g in fixed_groups if g not in fe.boundaries or len(fe.boundaries[g]) == 0]
    if missing or not (len(fixed_groups) or len(fixed_dofs)):
        raise SingularSystemError(
            f"no support: fixed groups {fixed_groups} ({'missing: ' + ', '.join(missing) if missing else 'none given'}); "
            "an unsupported body has rigid-body modes and K is singular")
    started = time.perf_counter()
    # a half-width solid stands for the mirrored whole only with u_z held on its mid-plane:
    # held here, so that no caller can solve it softer by forgetting the condition
    mirror = getattr(model, "mirror_dofs", np.zeros(0, dtype=np.int64))
    fixed = np.unique(np.concatenate([model.basis.get_dofs(g).flatten() for g in fixed_groups]
                                     + [np.asarray(fixed_dofs, dtype=np.int64), mirror]))
    rigid = rigid_body_modes(model.basis)
    held = np.linalg.matrix_rank(rigid[fixed]) if len(fixed) else 0
    if held < rigid.shape[1]:
        raise SingularSystemError(
            f"the supports leave {rigid.shape[1] - held} rigid-body motion(s) free (fixed "
            f"groups {fixed_groups}, {len(fixed_dofs)} single DOFs): K is singular")
    keep = np.ones(model.ndofs, dtype=bool)
    keep[fixed] = False
    free = np.flatnonzero(keep)
    method = pick(solver, len(free), fe.dim())
    blocks = getattr(model, "blocks", None)
    dim = fe.dim()
    whole_nodes = keep.reshape(-1, dim).all(axis=1) == keep.reshape(-1, dim).any(axis=1)
    # 3D: a node with some components held (a symmetry plane's u_z) stays a block too
    if method == "pardiso" and blocks is not None and (whole_nodes.all() or dim == 3):
        # single precision pays off where the factorisation dominates (3D), not in 2D,
        # where the refinement of many load columns costs more than it saves
        factor = factorise_free_blocks(blocks, keep.reshape(-1, dim),
                                       single=dim == 3 and columns < DOUBLE_COLUMNS)
    else:
        near_null = rigid[free] if method == "amg" else None
        factor = factorise(submatrix(model.K, keep), method, near_null)
    return SupportedSystem(model.ndofs, free, factor, time.perf_counter() - started)


def submatrix(K, keep: np.ndarray):
    """The rows and columns of CSR ``K`` where ``keep`` is true (``K[keep][:, keep]``
    without scipy's two copies)."""
    K = K.tocsr()
    rows = np.repeat(np.arange(K.shape[0]), np.diff(K.indptr))
    mask = keep[rows] & keep[K.indices]
    new = np.cumsum(keep) - 1
    count = int(keep.sum())
    indptr = np.concatenate([[0], np.cumsum(np.bincount(new[rows[mask]], minlength=count))])
    return K.__class__((K.data[mask], new[K.indices[mask]], indptr), shape=(count, count))


def solve(model, loads: np.ndarray, fixed_groups: list[str], fixed_dofs=(),
          solver: str = "auto") -> Solution:
    """Solve K u = f with zero displacement on ``fixed_groups`` (every component)
    and at ``fixed_dofs`` (DOF indices, e.g. from ``PlaneModel.node_dofs``).

    ``loads`` is (ndofs,) or (ndofs, k).  ``solver``: one of ``fem.solvers.SOLVERS``;
    ``"auto"`` picks by size and dimension.  Raises SingularSystemError when
    nothing is fixed or the solver finds the reduced matrix singular.  To solve
    more load sets later with the same factorisation, use ``supported``.
    """
    system = supported(model, fixed_groups, fixed_dofs, solver,
                       columns=1 if np.ndim(loads) == 1 else np.shape(loads)[1])
    try:
        solution = system.solve(loads)
    finally:
        system.release()
    return Solution(solution.u, system.seconds + solution.seconds, solution.solver)
