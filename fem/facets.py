"""Boundary integrals on curved meshes without inverting the isoparametric map.

scikit-fem's ``FacetBasis`` maps each facet quadrature point to the global
coordinates and back into its element by Newton's method, with an absolute
tolerance of 1e-12 on the reference coordinates.  On small curved elements
far from the origin the round-off of that residual (about eps |x| / h) is
larger than the tolerance and the iteration fails (the
ring at element scale 0.6).  The reference coordinates are known exactly
without it: a point with facet coordinates ``X`` lies at the same barycentric
position between the element's reference vertices that the facet joins,
because the trace of a Lagrange element on a facet is the facet element on
the same nodes.  This basis uses that, and is also faster.
"""
from __future__ import annotations

import functools

import numpy as np


def facet_basis(mesh, elem, facets: np.ndarray, intorder: int, dofs=None):
    """scikit-fem ``FacetBasis`` of ``elem`` on ``facets`` (indices into ``mesh.facets``),
    integrated from the side of ``mesh.f2t[0]``, DOF locations not computed.

    ``dofs``: an existing ``skfem.Dofs`` of ``elem`` on ``mesh`` (reused, not rebuilt).
    Affine meshes use scikit-fem's own class (its inverse map is exact).
    """
    import skfem

    facets = np.asarray(facets, dtype=np.int64)
    if mesh.affine:
        return skfem.FacetBasis(mesh, elem, facets=facets, intorder=intorder, dofs=dofs,
                                disable_doflocs=True)
    return _exact_facet_basis_class()(mesh, elem, facets, intorder, dofs)


def reference_points(mesh, facets: np.ndarray, elements: np.ndarray, X: np.ndarray
                     ) -> np.ndarray:
    """Reference coordinates (dim, n_facets, n_points) in ``elements`` of the points with
    facet reference coordinates ``X`` (dim - 1, n_points) on ``facets``."""
    corners = mesh.elem.refdom.p  # (dim, corners)
    # which local vertex of the element is each facet vertex (mesh.facets order)
    local = np.argmax(mesh.t[:, elements][None, :, :] == mesh.facets[:, facets][:, None, :],
                      axis=1)  # (facet vertices, n_facets)
    found = np.take_along_axis(mesh.t[:, elements], local, axis=0) == mesh.facets[:, facets]
    if not found.all():
        raise ValueError("a facet does not belong to the element it was paired with")
    # barycentric coordinates of X on the facet: 1 - sum(X), X_1, ..., X_{dim-1}
    weights = np.vstack([1.0 - X.sum(axis=0), X])  # (facet vertices, n_points)
    return np.einsum("dfv,vq->dfq", corners[:, local.T], weights)


@functools.cache
def _exact_facet_basis_class():
    import skfem
    from skfem.assembly.basis.abstract_basis import AbstractBasis
    from skfem.element import DiscreteField
    from skfem.mapping import MappingIsoparametric

    class ExactFacetBasis(skfem.FacetBasis):
        """``FacetBasis`` whose reference points come from ``reference_points``."""

        def __init__(self, mesh, elem, facets, intorder, dofs=None):
            # a mapping of its own: scikit-fem caches Jacobians per element set on the
            # mapping, and the mesh's shared one would keep them for the mesh's lifetime
            mapping = MappingIsoparametric(mesh, mesh.elem(), mesh.bndelem)
            AbstractBasis.__init__(self, mesh, elem, mapping, intorder, None, mesh.brefdom,
                                   dofs, True)
            self.find = facets
            self.tind = mesh.f2t[0, facets]
            self.tind_normals = self.tind
            Y = reference_points(mesh, facets, self.tind, self.X)
            self.normals = DiscreteField(value=mapping.normals(Y, self.tind, facets, mesh.t2f))
            self.nelems = len(facets)
            self.basis = [elem.gbasis(mapping, Y, j, tind=self.tind) for j in range(self.Nbfun)]
            self.dx = (np.abs(mapping.detDG(self.X, find=facets))
                       * np.broadcast_to(self.W, (self.nelems, self.W.shape[-1])))

    return ExactFacetBasis
