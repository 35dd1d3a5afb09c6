"""Linear elasticity of a solid (3D) ``FEMesh`` with scikit-fem (SI units).

The same interface as ``elasticity.PlaneModel`` where the ring-stiffness code
needs it: boundary groups are surfaces, ``thickness`` is 1 (loads and means
are integrals over areas), ``boundary_means`` gives the mean in-plane
displacement and the mean rotation about the z axis.  The stiffness is kept
in 3 x 3 node blocks (``blocks``), which PARDISO factorises directly; the
CSR matrix ``K`` is built only when asked for.

A half-width mesh (``meshing.ring_mesh_3d``, ``half_width``: z from 0 to the mid-plane
``mirror_z``, group ``mid_plane``) stands for the whole body mirrored about that plane:
when body, supports and loads are all mirror-symmetric, the exact solution is too, so it
is the half's solution with u_z = 0 on the mid-plane (``mirror_dofs``, to be held by the
solve).  The half's stiffness is assembled twice over (the two halves in parallel): a load
normalised to the modelled part (a force spread over the half of a swept patch, 1 N over
the half's strips) then gives the whole body's displacement under the same total force,
and every mean reading (root lands, the work of 1 N) is the whole body's.
"""
from __future__ import annotations

import functools
import time
from dataclasses import dataclass, field

import numpy as np

from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.to_skfem import to_skfem

from .basis import vector_basis
from .elasticity import PlaneModel
from .fast_assembly import BlockMatrix, elasticity_block_matrix
from .material import Material


#: the boundary group of a half-width mesh's mid-plane
MIRROR_GROUP = "mid_plane"


@dataclass(eq=False)
class SolidModel:
    """Assembled 3D model: ``basis`` (P1 or curved P2 tetrahedra) and the stiffness in
    node blocks ``blocks`` [N/m]; ``K`` is the same in CSR."""

    mesh: FEMesh
    basis: object
    blocks: BlockMatrix
    material: Material
    timings: dict = field(default_factory=dict)
    thickness: float = 1.0

    @property
    def mirror_z(self) -> float | None:
        """z [m] of the mid-plane a half-width mesh is mirrored about (None: whole body)."""
        return self.mesh.info.get("mirror_z")

    @property
    def mirror_dofs(self) -> np.ndarray:
        """The u_z DOFs on the mid-plane (group ``mid_plane``) of a half-width mesh, held
        zero by the solve; empty for a whole body."""
        if self.mirror_z is None:
            return np.zeros(0, dtype=np.int64)
        if MIRROR_GROUP not in self.mesh.boundaries:
            raise ValueError(f"mesh.info['mirror_z'] = {self.mirror_z!r} m but the mesh has no "
                             f"group {MIRROR_GROUP!r}")
        dofs = np.unique(self.basis.get_dofs(MIRROR_GROUP).flatten())
        return dofs[dofs % 3 == 2]  # DOF 3 node + component

    @functools.cached_property
    def K(self):
        return self.blocks.csr()

    @property
    def ndofs(self) -> int:
        return self.blocks.shape[0]

    # with thickness 1 the plane model's surface integrals hold in 3D
    facet_basis = PlaneModel.facet_basis
    unit_traction_loads = PlaneModel.unit_traction_loads


def solid_model(mesh: FEMesh, material: Material = Material(), cell_scale=None) -> SolidModel:
    """Assemble K for a tetrahedral mesh; P1 or P2 follows the mesh order.

    ``cell_scale`` (one factor per cell, default 1) scales each cell's stiffness: how much
    a result depends on some cells (e.g. the poorly shaped ones).  A half-width mesh
    (``mesh.info["mirror_z"]``) is assembled with twice its stiffness (see the module's
    doc)."""
    import skfem

    if mesh.dim != 3:
        raise ValueError(f"solid_model needs a tetrahedral mesh, got {mesh.cell_type}")
    lam, mu = material.lame("strain")  # 3D: the true Lame constants
    t0 = time.perf_counter()
    fe, _ = to_skfem(mesh)
    t1 = time.perf_counter()
    # degree 2 integrates the P2 stiffness exactly on straight tetrahedra with 4 points
    # instead of the 11 of skfem's default: assembly dominates the 3D cost (fe_facts)
    basis = vector_basis(fe, skfem.ElementTetP2() if mesh.order == 2 else skfem.ElementTetP1(),
                         2 if mesh.order == 2 else 1)
    t2 = time.perf_counter()
    if mesh.info.get("mirror_z") is not None:  # the two halves in parallel
        cell_scale = 2.0 * (np.ones(len(mesh.cells)) if cell_scale is None
                            else np.asarray(cell_scale, dtype=float))
    blocks = elasticity_block_matrix(basis, lam, mu, cell_scale)
    t3 = time.perf_counter()
    return SolidModel(mesh, basis, blocks, material,
                      {"to_skfem": t1 - t0, "basis": t2 - t1, "assembly": t3 - t2})
