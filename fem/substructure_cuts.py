"""The ring's cut system: the condensed pieces assembled on the DOFs of their cuts and
factorised (SI units; ``fem.substructure``)."""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from hubvib.meshing.gear import rotation

from .solvers import SingularSystemError, factorise, pick


def turned_stiffness(S: np.ndarray, angle: float) -> np.ndarray:
    """``R S R^T`` for ``S`` on node pairs (x, y) and R the rotation by ``angle`` [rad] of
    every node."""
    n = S.shape[0] // 2
    R = rotation(angle)
    blocks = S.reshape(n, 2, n, 2)
    return np.einsum("ij,ajbk,lk->aibl", R, blocks, R).reshape(S.shape)


def cut_system(parts: list, held: np.ndarray, ndofs: int, solver: str = "auto"):
    """The free cut DOFs of the glued model (ascending), each part's boundary DOFs as
    positions among them (-1: held) and the factorised cut system.

    ``parts``: (piece, ``Condensed``, glued node DOF table) per piece; ``held``: the
    glued model's supported DOFs (bool, ``ndofs``)."""
    glued_boundary = []
    for piece, part, glued in parts:
        glued_boundary.append(glued[piece.cut_nodes].ravel())
    every = np.unique(np.concatenate(glued_boundary))
    interface = every[~held[every]]
    position = np.full(ndofs, -1, dtype=np.int64)
    position[interface] = np.arange(len(interface))
    positions, rows, cols, data = [], [], [], []
    for (piece, part, glued), dofs in zip(parts, glued_boundary):
        where = position[dofs]
        positions.append(where)
        keep = np.flatnonzero(where >= 0)
        S = turned_stiffness(part.S, piece.angle)[np.ix_(keep, keep)]
        rows.append(np.repeat(where[keep], len(keep)))
        cols.append(np.tile(where[keep], len(keep)))
        data.append(S.ravel())
    n = len(interface)
    K = sp.csr_matrix((np.concatenate(data), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(n, n))
    K.sum_duplicates()
    if n == 0:
        raise SingularSystemError("the ring has no free cut DOF")
    return interface, positions, factorise(K, pick(solver, n, 2))
