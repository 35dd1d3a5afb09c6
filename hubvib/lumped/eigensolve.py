"""Eigenvalues of ``K phi = lambda M phi`` for the lumped model.

Methods, all returning mass-normalised modes ``phi^T M phi = I``:

``"jacobi"`` (default)
    Preconditioned one-sided Jacobi SVD (LAPACK ``dgejsv``, JOBA='F') of the
    factor ``B = diag(sqrt(k)) G M^(-1/2)`` with ``B^T B = M^(-1/2) K M^(-1/2)``.
    ``B`` is a well-conditioned matrix scaled on both sides by the spring
    stiffnesses and masses, the case in which this SVD keeps every singular
    value to high *relative* accuracy (Drmac & Veselic, SIAM J. Matrix Anal.
    Appl. 29, 2008).  Stiffness ratios of 1e14 and mass ratios of 1e9 cost
    nothing in accuracy (about 1e-15 relative, ``hubvib stability``).
``"svd"``
    Householder SVD (``gesdd``) of the same factor: absolute error
    ``eps * sigma_max``, so about ``eps * sqrt(k_max / k_min)`` relative.
``"eigh"``
    ``scipy.linalg.eigh`` on the assembled matrices: absolute error
    ``eps * lambda_max``; loses the lowest modes of stiff systems.

Rigid-body modes are counted from the null space of the rows of ``G`` whose
stiffness is non-zero: a mechanism of the spring network, independent of how
large the stiffnesses are.  They are reported with eigenvalue exactly 0.
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla
from scipy.linalg import lapack

from .network import SpringNetwork

METHODS = ("jacobi", "svd", "eigh")


class IndefiniteStiffnessError(ValueError):
    """The stiffness matrix has negative eigenvalues: no real frequencies."""


def rigid_body_count(network: SpringNetwork) -> int:
    """Number of zero-energy motions (mechanisms) of the spring network."""
    active = network.G[network.k > 0]
    n = network.G.shape[1]
    if active.shape[0] == 0:
        return n
    return n - int(np.linalg.matrix_rank(active, tol=1e-10 * max(active.shape)))


def solve_network(network: SpringNetwork, mass: np.ndarray, method: str = "jacobi"):
    """Eigenpairs of the network with diagonal masses ``mass`` [kg].

    Returns ``(eigenvalues [rad^2/s^2], modes, n_rigid)`` sorted ascending,
    the first ``n_rigid`` eigenvalues exactly zero.
    """
    if method not in METHODS:
        raise ValueError(f"method = {method!r}, but it must be one of {METHODS}")
    n = mass.size
    n_rigid = rigid_body_count(network)
    scale = 1.0 / np.sqrt(mass)
    active = network.k > 0
    B = np.sqrt(network.k[active])[:, None] * network.G[active] * scale[None, :]
    if method == "eigh":
        lam, vectors = sla.eigh(B.T @ B)
    else:
        if B.shape[0] < n:
            B = np.vstack([B, np.zeros((n - B.shape[0], n))])
        if method == "jacobi":
            sigma, vectors = _jacobi_svd(B)
        else:
            _, sigma, vt = sla.svd(B, full_matrices=False, lapack_driver="gesdd")
            vectors = vt.T
        order = np.argsort(sigma)
        lam, vectors = sigma[order] ** 2, vectors[:, order]
    lam = np.array(lam, dtype=float)
    lam[:n_rigid] = 0.0
    return lam, scale[:, None] * vectors, n_rigid


def _jacobi_svd(B: np.ndarray):
    sva, _, v, work, _, info = lapack.dgejsv(B, joba=2, jobu=3, jobv=0, jobr=0, jobt=0, jobp=0)
    if info != 0:
        raise RuntimeError(f"LAPACK dgejsv failed with info = {info}")
    return sva * (work[0] / work[1]), v


def solve_assembled(K: np.ndarray, mass: np.ndarray, allow_indefinite: bool = False):
    """Eigenpairs of an assembled symmetric ``K`` [N/m] with diagonal masses [kg].

    Eigenvalues within ``n eps |K|`` of zero are set to 0.  Negative ones
    beyond that raise :class:`IndefiniteStiffnessError` unless
    ``allow_indefinite``, when they are returned as they are.
    """
    K = np.asarray(K, dtype=float)
    n = mass.size
    if K.shape != (n, n):
        raise ValueError(f"K.shape = {K.shape}, but the masses give {n} coordinates")
    asymmetry = np.abs(K - K.T).max()
    if asymmetry > 1e-12 * np.abs(K).max():
        raise ValueError(f"K is not symmetric: max |K - K^T| = {asymmetry:.3e}")
    scale = 1.0 / np.sqrt(mass)
    lam, vectors = sla.eigh(scale[:, None] * K * scale[None, :])
    zero = n * np.finfo(float).eps * np.abs(lam).max()
    lam[np.abs(lam) <= zero] = 0.0
    negative = lam[lam < 0]
    if negative.size and not allow_indefinite:
        raise IndefiniteStiffnessError(
            f"the stiffness matrix is indefinite: {negative.size} negative eigenvalue(s) "
            f"{np.array2string(negative, precision=4)} rad^2/s^2; no real natural frequency exists for them"
        )
    return lam, scale[:, None] * vectors
