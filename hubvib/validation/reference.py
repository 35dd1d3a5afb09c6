"""High-precision reference eigenvalues (mpmath), independent of LAPACK.

The mass-scaled stiffness ``M^(-1/2) G^T diag(k) G M^(-1/2)`` is assembled in
``dps``-digit arithmetic from the same double-precision inputs (each double
is exact in mpmath) and diagonalised by mpmath's Jacobi-type ``eigsy``.
"""
from __future__ import annotations

import mpmath as mp
import numpy as np

from hubvib.lumped.network import mass_diagonal, spring_network
from hubvib.lumped.parameters import PlanetaryParameters


def reference_eigenvalues(params: PlanetaryParameters, dps: int = 50) -> np.ndarray:
    """Eigenvalues [rad^2/s^2], ascending, rounded to double at the end."""
    network = spring_network(params)
    mass = mass_diagonal(params)
    return eigenvalues_of_factor(network.G, network.k, mass, dps)


def eigenvalues_of_factor(G, k, mass, dps: int = 50) -> np.ndarray:
    """Eigenvalues of ``M^(-1/2) G^T diag(k) G M^(-1/2)`` in ``dps`` digits."""
    n = G.shape[1]
    with mp.workdps(dps):
        scale = [1 / mp.sqrt(mp.mpf(float(m))) for m in mass]
        K = mp.zeros(n, n)
        for row, stiffness in zip(G, k):
            nz = np.flatnonzero(row)
            kk = mp.mpf(float(stiffness))
            g = {j: mp.mpf(float(row[j])) * scale[j] for j in nz}
            for a in nz:
                for b in nz:
                    K[a, b] += kk * g[a] * g[b]
        values = mp.eigsy(K, eigvals_only=True)
        return np.sort(np.array([float(v) for v in values]))

