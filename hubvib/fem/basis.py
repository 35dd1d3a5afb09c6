"""A scikit-fem vector ``CellBasis`` that evaluates its functions only when asked.

A model needs its basis for the DOF numbering (boundary DOFs, DOF locations,
element DOFs) far more often than for quadrature: the stiffness comes from
``fast_assembly``, which computes the scalar gradients itself.  scikit-fem's
``CellBasis`` evaluates every vector basis function at every quadrature point
when it is built (30 functions x 4 points per P2 tetrahedron: about 1 GB and
seconds at 5e5 DOFs, the inverse Jacobian recomputed for each function).  This
subclass builds the numbering at once and the function values (``basis``,
``dx``) on first use, so mass matrices, stresses and interpolation still work
unchanged.  DOF locations of an element on its own mesh type are the mesh
nodes, taken as they are instead of mapping every reference DOF point.
"""
from __future__ import annotations

import functools

import numpy as np


def vector_basis(mesh, scalar, intorder: int):
    """``CellBasis`` of ``ElementVector(scalar)`` on ``mesh`` with quadrature degree ``intorder``;
    function values are computed on first access."""
    import skfem

    elem = skfem.ElementVector(scalar, mesh.dim())
    return _lazy_class()(mesh, elem, intorder)


@functools.cache
def _lazy_class():
    import skfem
    from skfem.assembly.basis.abstract_basis import AbstractBasis

    class LazyCellBasis(skfem.CellBasis):
        """``CellBasis`` with ``basis`` and ``dx`` computed on first access."""

        def __init__(self, mesh, elem, intorder):
            own_nodes = type(elem.elem) is type(mesh.elem())
            AbstractBasis.__init__(self, mesh, elem, None, intorder, None, mesh.refdom, None,
                                   own_nodes)
            self.tind = None
            self.nelems = mesh.nelements
            if own_nodes:  # DOF dim * node + c sits at mesh node ``node``
                self.doflocs = np.repeat(mesh.doflocs, mesh.dim(), axis=1)

        @functools.cached_property
        def basis(self):
            return [self.elem.gbasis(self.mapping, self.X, j, tind=self.tind)
                    for j in range(self.Nbfun)]

        @functools.cached_property
        def dx(self):
            return (np.abs(self.mapping.detDF(self.X, tind=self.tind))
                    * np.broadcast_to(self.W, (self.nelems, self.W.shape[-1])))

    return LazyCellBasis
