"""Isotropic linear-elasticity stiffness assembled straight into node blocks (SI units).

scikit-fem's generic form assembly evaluates the weak form once per pair of
local basis functions and hands scipy one (row, column, value) triplet per
element-matrix entry (900 per P2 tetrahedron), which scipy then sorts and sums
into CSR: in 3D that sort is most of the assembly time and memory.  Here

- the scalar shape-function gradients come from one inverse Jacobian per
  quadrature point (scikit-fem recomputes it for every basis function);
- all element matrices of a chunk of elements come from batched products;
- the sparsity is built once on the node graph (100 node pairs per P2
  tetrahedron, 9 times fewer than DOF pairs), only its upper triangle (the
  matrix is symmetric: 55 of the 100 pairs), and each element matrix is added
  into the ``dim x dim`` blocks by ``bincount``.

The result is the upper block triangle, which PARDISO factorises as it is
(``solvers.factorise_blocks``); ``BlockMatrix.csr`` gives the whole matrix.
Same quadrature, same matrix to rounding (``tests/fem/test_solid.py`` against
scikit-fem's own assembly).  A vector basis numbers its DOFs node by node,
``dim * node + component`` (scikit-fem's ``Dofs`` with ``order='F'``); this is checked.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

CHUNK = 20_000  # elements per block: bounds the (chunk, n, n) temporaries
UPPER_CHUNK = 500_000  # blocks per slice when ``BlockMatrix.upper`` copies the values


@dataclass(frozen=True, eq=False)
class BlockPattern:
    """Sparsity of a symmetric nodal matrix on the node graph, upper triangle.

    Attributes
    ----------
    indptr, indices : ndarray
        Node-level CSR structure of the upper triangle (sorted columns, each row
        starting with its diagonal): block ``(a, b)``, a <= b, exists when nodes ``a``
        and ``b`` share an element.
    upper : ndarray of bool (elements, n, n)
        Element node pairs ``(a, b)`` whose block is stored (node a <= node b).
    position : ndarray
        Block index in ``indices`` of each stored element node pair, element by element.
    start : ndarray (elements + 1,)
        Where each element's pairs begin in ``position``.  ``upper``, ``position`` and
        ``start`` serve the assembly only: an assembled ``BlockMatrix``'s pattern has
        them ``None`` (``assembled``).
    dim : int
        Components per node.
    """

    indptr: np.ndarray
    indices: np.ndarray
    upper: np.ndarray
    position: np.ndarray
    start: np.ndarray
    dim: int

    @property
    def nodes(self) -> int:
        return len(self.indptr) - 1

    def assembled(self) -> "BlockPattern":
        """The pattern without its element-to-block map (0.06 GB on the solid ring, held
        through the factorisation otherwise)."""
        return BlockPattern(self.indptr, self.indices, None, None, None, self.dim)

    @property
    def blocks(self) -> int:
        return len(self.indices)


def element_nodes(basis) -> np.ndarray:
    """(elements, n) node of each local scalar function of a vector basis; raises if the
    DOFs are not numbered ``dim * node + component``."""
    dim = basis.mesh.dim()
    dofs = basis.element_dofs.T.reshape(basis.nelems, -1, dim)
    nodes = dofs[:, :, 0] // dim
    if not np.array_equal(dofs, dim * nodes[:, :, None] + np.arange(dim)):
        raise ValueError("the vector basis does not number its DOFs node by node")
    return nodes


def block_pattern(nodes: np.ndarray, count: int, dim: int) -> BlockPattern:
    """The upper node-graph pattern of elements with nodes ``nodes`` (elements, n) among
    ``count`` nodes."""
    upper = nodes[:, :, None] <= nodes[:, None, :]
    rows = np.broadcast_to(nodes[:, :, None], upper.shape)[upper].astype(np.int32)
    cols = np.broadcast_to(nodes[:, None, :], upper.shape)[upper].astype(np.int32)
    graph = sp.csr_matrix((np.ones(len(rows), dtype=np.float32), (rows, cols)),
                          shape=(count, count))
    graph.sum_duplicates()  # sorted, unique columns per row
    # the block index of each node pair: the graph with its entries numbered
    numbered = sp.csr_matrix((np.arange(graph.nnz, dtype=np.float64), graph.indices,
                              graph.indptr), shape=graph.shape)
    position = np.asarray(numbered[rows, cols]).ravel().astype(np.int64)
    start = np.concatenate([[0], np.cumsum(upper.sum(axis=(1, 2)))])
    return BlockPattern(graph.indptr, graph.indices, upper, position, start, dim)


def scalar_gradients(mesh, element, points: np.ndarray, weights: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Gradients (elements, q, n, dim) [1/m] of the scalar ``element``'s n functions at the
    reference quadrature ``points`` (dim, q), and ``weights`` times |det J| (elements, q)."""
    from skfem.mapping import MappingIsoparametric

    # a mapping of its own for curved meshes: scikit-fem caches Jacobians on the mesh's one
    mapping = (mesh.mapping() if mesh.affine
               else MappingIsoparametric(mesh, mesh.elem(), mesh.bndelem))
    inverse = mapping.invDF(points)  # (dim, dim, elements, q)
    dx = np.abs(mapping.detDF(points)) * weights[None, :]
    reference = np.stack([element.lbasis(points, a)[1] for a in range(element.doflocs.shape[0])])
    # grad_j phi_a = sum_i invDF[i, j] dphi_a / dX_i, as scikit-fem's ElementH1.gbasis
    grads = np.einsum("ijeq,aiq->eqaj", inverse, reference, optimize=True)
    return np.ascontiguousarray(grads), dx


def elasticity_blocks(pattern: BlockPattern, grads: np.ndarray, dx: np.ndarray, lam: float,
                      mu: float) -> np.ndarray:
    """Block values (blocks, dim, dim) [N/m] of the stiffness for Lame constants ``lam``,
    ``mu`` [Pa]; ``grads``, ``dx`` from ``scalar_gradients``."""
    dim = pattern.dim
    blocks = np.zeros((dim, dim, pattern.blocks))
    for first in range(0, len(grads), CHUNK):
        chunk = slice(first, first + CHUNK)
        g = grads[chunk]
        gw = g * dx[chunk][:, :, None, None]
        # outer[i][j][e, a, b] = sum_q w G_ai G_bj: dim^2 batched (n, q) @ (q, n) products
        left = [np.ascontiguousarray(gw[..., i].transpose(0, 2, 1)) for i in range(dim)]
        right = [np.ascontiguousarray(g[..., j]) for j in range(dim)]
        outer = [[np.matmul(left[i], right[j]) for j in range(dim)] for i in range(dim)]
        dot = sum(outer[i][i] for i in range(dim))
        upper = pattern.upper[chunk]
        where = pattern.position[pattern.start[chunk.start]:
                                 pattern.start[min(first + CHUNK, len(grads))]]
        for i in range(dim):
            for j in range(dim):
                k = lam * outer[i][j] + mu * outer[j][i]
                if i == j:
                    k += mu * dot
                blocks[i, j] += np.bincount(where, k[upper], minlength=pattern.blocks)
    return np.ascontiguousarray(blocks.transpose(2, 0, 1))


@dataclass(frozen=True, eq=False)
class BlockMatrix:
    """A symmetric matrix stored as the ``dim x dim`` node blocks of its upper block
    triangle (diagonal blocks whole) on a ``BlockPattern``.

    ``values`` (blocks, dim, dim) [N/m]; DOF ``dim * node + component``.
    """

    pattern: BlockPattern
    values: np.ndarray

    @property
    def shape(self) -> tuple[int, int]:
        size = self.pattern.nodes * self.pattern.dim
        return size, size

    def csr(self):
        """The whole matrix in CSR (sorted indices)."""
        p = self.pattern
        upper = sp.bsr_matrix((self.values, p.indices, p.indptr), shape=self.shape).tocsr()
        diagonal = sp.bsr_matrix((self.values[p.indptr[:-1]], np.arange(p.nodes),
                                  np.arange(p.nodes + 1)), shape=self.shape).tocsr()
        whole = (upper + upper.T - diagonal).tocsr()
        whole.sort_indices()
        return whole

    def upper(self, keep: np.ndarray, dtype=np.float64
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Block-CSR ``(indptr, indices, values)`` of the rows and columns of the nodes where
        ``keep`` is true, renumbered in order (still the upper block triangle); ``values``
        in ``dtype`` (float32: rounded, for a single-precision factorisation)."""
        indptr, indices = self.pattern.indptr, self.pattern.indices
        rows = np.repeat(np.arange(self.pattern.nodes), np.diff(indptr))
        mask = keep[rows] & keep[indices]
        new = np.cumsum(keep) - 1
        counts = np.bincount(new[rows[mask]], minlength=int(keep.sum()))
        values = np.empty((int(mask.sum()),) + self.values.shape[1:], dtype=dtype)
        done = 0
        for first in range(0, len(mask), UPPER_CHUNK):  # no whole double copy on the way
            part = slice(first, first + UPPER_CHUNK)
            taken = self.values[part][mask[part]]
            values[done:done + len(taken)] = taken
            done += len(taken)
        return (np.concatenate([[0], np.cumsum(counts)]).astype(np.int32),
                new[indices[mask]].astype(np.int32), values)

    def scaled(self, factor: float) -> "BlockMatrix":
        return BlockMatrix(self.pattern, factor * self.values)


def elasticity_block_matrix(basis, lam: float, mu: float, cell_scale=None) -> BlockMatrix:
    """K [N/m] of a scikit-fem ``ElementVector`` basis for Lame constants ``lam``, ``mu`` [Pa],
    in node blocks; ``cell_scale`` (one factor per cell) scales each cell's stiffness."""
    dim = basis.mesh.dim()
    pattern = block_pattern(element_nodes(basis), basis.N // dim, dim)
    X, W = basis.quadrature
    grads, dx = scalar_gradients(basis.mesh, basis.elem.elem, X, W)
    if cell_scale is not None:
        dx = dx * np.asarray(cell_scale, dtype=float)[:, None]
    values = elasticity_blocks(pattern, grads, dx, lam, mu)
    return BlockMatrix(pattern.assembled(), values)


def elasticity_matrix(basis, lam: float, mu: float):
    """K [N/m] of a scikit-fem ``ElementVector`` basis for Lame constants ``lam``, ``mu`` [Pa]
    (CSR)."""
    return elasticity_block_matrix(basis, lam, mu).csr()
