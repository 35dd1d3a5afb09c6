"""Natural frequencies of many parameter points at once (Monte Carlo, sweeps).

Every point shares the spring rows ``G`` of one :class:`PlanetaryParameters`
(planet angles, pressure angles) and changes only stiffness and mass values.
With the stacked factors ``B = diag(sqrt(k)) G M^(-1/2)`` (see
:mod:`lumped.eigensolve`) each point is solved by one LAPACK call through
numpy's stacked linear algebra, with no Python loop, in three tiers:

1. the symmetric eigenvalues of ``B^T B`` (``syevd``): relative error of
   lambda_i about ``n eps lambda_max / lambda_i``, half that on omega_i;
2. where that bound exceeds ``tolerance``: the singular values of ``B``
   (``gesdd``), relative error about ``n eps sigma_max / sigma_i``;
3. where that still exceeds it: the preconditioned one-sided Jacobi SVD one
   point at a time, ~1e-15 relative whatever the conditioning.

The bound of the lowest elastic mode is the largest; the default tolerance
1e-10 is the agreement with the Jacobi solver the tests check.

The matrices are 18 x 18: threading inside BLAS only costs synchronisation
(several times the call's own time on a loaded 2-core machine), so
the batch runs with one BLAS thread; parallelism, when asked for, is over
chunks of points.
"""
from __future__ import annotations

import math
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from hubvib.foundation.blas import blas_thread_counts, blas_threads
from hubvib.lumped.spectrum import natural_modes

from .eigensolve import rigid_body_count, solve_network
from .network import SpringNetwork, mass_diagonal, spring_network
from .parameters import MASS_FIELDS, ParameterError, PlanetaryParameters, STIFFNESS_FIELDS

#: bound on the relative error of omega above which a point is solved more accurately
TOLERANCE = 1e-10
EPS = np.finfo(float).eps


@dataclass(frozen=True)
class BatchFrequencies:
    """Natural frequencies of ``P`` parameter points.

    Attributes
    ----------
    omega : ndarray, shape (P, n_dof)
        Natural frequencies [rad/s], ascending per point; rigid-body modes exactly 0.
    tier : ndarray of int, shape (P,)
        How each point was solved: 1 eigenvalues of ``B^T B``, 2 singular values of
        ``B``, 3 Jacobi SVD one at a time (see the module docstring).
    error_bound : ndarray, shape (P,)
        Bound on the relative error of the lowest elastic frequency of the batched
        tier used (tiers 1 and 2) [-].
    """

    omega: np.ndarray
    tier: np.ndarray
    error_bound: np.ndarray

    @property
    def fallback(self) -> np.ndarray:
        """Points solved one at a time by the Jacobi solver."""
        return self.tier == 3

    @property
    def frequency_hz(self) -> np.ndarray:
        """Natural frequencies [Hz]."""
        return self.omega / (2 * math.pi)


def batch_frequencies(params: PlanetaryParameters, changes: Mapping[str, np.ndarray],
                      tolerance: float = TOLERANCE, workers: int = 1) -> BatchFrequencies:
    """Natural frequencies of ``params`` with fields changed point by point.

    Parameters
    ----------
    params : PlanetaryParameters
        Base point: its planet layout and every field not in ``changes``.
    changes : mapping
        Stiffness fields [N/m] and mass fields [kg] -> values, shape (P,);
        ``"c_rp_factors"`` -> shape (P, N), the factor on each planet's ring mesh.
    tolerance : float
        Relative error of omega above which a point is solved again by the Jacobi
        solver [-].
    workers : int
        Threads, each taking a chunk of points (numpy's linalg releases the GIL).

    Returns
    -------
    BatchFrequencies
    """
    network = spring_network(params)
    k, mass = _stacked_values(params, network, changes)
    chunks = np.array_split(np.arange(k.shape[0]), max(1, min(workers, k.shape[0])))
    with blas_threads(1):
        if len(chunks) == 1:
            parts = [_solve_chunk(network.G, k, mass, tolerance)]
        else:
            with ThreadPoolExecutor(len(chunks)) as pool:
                parts = list(pool.map(lambda idx: _solve_chunk(network.G, k[idx], mass[idx],
                                                                  tolerance),
                                      chunks))
        omega = np.concatenate([p[0] for p in parts])
        bound = np.concatenate([p[1] for p in parts])
        tier = np.concatenate([p[2] for p in parts])
        tier[~(bound <= tolerance)] = 3
        for i in np.flatnonzero(tier == 3):
            lam, _, _ = solve_network(SpringNetwork(network.G, k[i], network.parameter,
                                                    network.label), mass[i], "jacobi")
            omega[i] = np.sqrt(lam)
    return BatchFrequencies(omega, tier, bound)


def _stacked_values(params, network, changes):
    """Spring stiffnesses (P, rows) [N/m] and diagonal masses (P, n_dof) [kg]."""
    allowed = set(STIFFNESS_FIELDS) | set(MASS_FIELDS) | {"c_rp_factors"}
    unknown = set(changes) - allowed
    if unknown:
        raise ParameterError(f"batch changes {sorted(unknown)}: allowed are stiffness fields, "
                             f"mass fields and c_rp_factors ({sorted(allowed)})")
    sizes = {name: np.shape(v)[0] if np.ndim(v) else -1 for name, v in changes.items()}
    if not changes or len(set(sizes.values())) != 1 or -1 in sizes.values():
        raise ParameterError(f"batch changes need arrays of one common length P >= 1; "
                             f"got lengths {sizes}")
    P = next(iter(sizes.values()))
    values = {name: np.asarray(v, dtype=float) for name, v in changes.items()}
    for name, v in values.items():
        low = 0.0 if name in STIFFNESS_FIELDS else None
        bad = ~np.isfinite(v) | ((v < low) if low is not None else (v <= 0))
        if bad.any():
            i = np.argwhere(bad)[0]
            raise ParameterError(f"{name}[{', '.join(map(str, i))}] = {float(v[tuple(i)])!r}, but it "
                                 f"must be finite and {'>= 0' if low is not None else '> 0'}")
    n_planets = params.n_planets
    factors = np.broadcast_to(np.asarray(params.c_rp_factors or (1.0,) * n_planets, float),
                              (P, n_planets))
    if "c_rp_factors" in values:
        factors = values["c_rp_factors"]
        if factors.shape != (P, n_planets):
            raise ParameterError(f"c_rp_factors has shape {factors.shape}, but it must be "
                                 f"(P, N) = ({P}, {n_planets})")
    k = np.empty((P, network.k.size))
    for name in STIFFNESS_FIELDS:
        k[:, network.rows_of(name)] = (values[name] if name in values
                                       else np.full(P, getattr(params, name)))[:, None]
    k[:, network.rows_of("c_rp")] *= factors  # one row per planet, in planet order
    mass = np.broadcast_to(mass_diagonal(params), (P, params.n_dof)).copy()
    for name in MASS_FIELDS:
        if name in values:
            unit = (mass_diagonal(params.replace(**{name: 2.0}))
                    - mass_diagonal(params.replace(**{name: 1.0})))
            mass += (values[name] - getattr(params, name))[:, None] * unit[None, :]
    return k, mass


def _solve_chunk(G, k, mass, tolerance):
    """Ascending omega [rad/s], the relative error bound and the tier of each point.

    First the symmetric eigenvalues of ``B^T B`` (error ``n eps lambda_max / lambda_i``
    on lambda, half that on omega); where that bound exceeds ``tolerance``, the
    singular values of ``B`` (``n eps sigma_max / sigma_i``).
    """
    n = G.shape[1]
    omega = np.zeros((k.shape[0], n))
    bound = np.full(k.shape[0], np.inf)
    tier = np.ones(k.shape[0], dtype=int)
    active = k > 0
    if (active == active[0]).all():
        groups = [(active[0], np.arange(k.shape[0]))]
    else:
        patterns, inverse = np.unique(active, axis=0, return_inverse=True)
        groups = [(p, np.flatnonzero(inverse.ravel() == i)) for i, p in enumerate(patterns)]
    for pattern, idx in groups:
        rows = np.flatnonzero(pattern)
        n_rigid = rigid_body_count(SpringNetwork(G, pattern.astype(float), (), ()))
        if rows.size == 0 or n_rigid == n:
            bound[idx] = 0.0
            continue
        B = (np.sqrt(k[idx][:, rows])[:, :, None] * G[rows][None]
             / np.sqrt(mass[idx])[:, None, :])
        lam = np.linalg.eigvalsh(np.matmul(B.transpose(0, 2, 1), B))
        lam[:, :n_rigid] = 0.0
        sigma = np.sqrt(np.maximum(lam, 0.0))
        error = 0.5 * n * EPS * lam[:, -1] / np.maximum(lam[:, n_rigid], np.finfo(float).tiny)
        poor = np.flatnonzero(~(error <= tolerance))
        if poor.size:
            Bp = B[poor]
            if rows.size < n:
                Bp = np.concatenate([Bp, np.zeros((poor.size, n - rows.size, n))], axis=1)
            s = np.sort(np.linalg.svd(Bp, compute_uv=False), axis=1)
            s[:, :n_rigid] = 0.0
            sigma[poor] = s
            error[poor] = n * EPS * s[:, -1] / np.maximum(s[:, n_rigid], np.finfo(float).tiny)
            tier[idx[poor]] = 2
        omega[idx], bound[idx] = sigma, error
    return omega, bound, tier


def benchmark_batch(params: PlanetaryParameters, points: int = 10_000, single: int = 200,
                    seed: int = 0, workers: int = 2) -> dict:
    """Batched against one-at-a-time solves, measured in the same run.

    Scatters every stiffness by 10 % and every mass by 2 % (log-normal) around
    ``params`` (the benchmark: the Raba 118/76 preset), solves ``points`` of them batched and ``single`` of
    them one at a time with :func:`lumped.natural_modes` (Jacobi), and compares.

    Returns
    -------
    dict
        ``points``, ``workers``, ``batch_seconds``, ``points_per_second``,
        ``single_seconds_per_point``, ``speedup`` (one-at-a-time time per point
        over batched time per point), ``svd_points`` and ``fallback_points`` (points
        solved by tier 2 and 3), ``max_relative_difference``
        (against Jacobi on the ``single`` points), ``blas_threads`` (during the
        batch; empty when no OpenBLAS was found).
    """
    rng = np.random.default_rng(seed)
    changes = {name: getattr(params, name) * np.exp(0.1 * rng.standard_normal(points))
               for name in STIFFNESS_FIELDS if getattr(params, name) > 0}
    changes |= {name: getattr(params, name) * np.exp(0.02 * rng.standard_normal(points))
                for name in MASS_FIELDS}
    batch_frequencies(params, {n: v[:10] for n, v in changes.items()})  # warm-up
    started = time.perf_counter()
    result = batch_frequencies(params, changes, workers=workers)
    batch_seconds = time.perf_counter() - started
    with blas_threads(1):
        threads = blas_thread_counts()
    started = time.perf_counter()
    reference = np.array([natural_modes(params.replace(**{n: float(v[i])
                                                          for n, v in changes.items()})).omega
                          for i in range(single)])
    single_seconds = (time.perf_counter() - started) / single
    elastic = reference > 0
    difference = np.abs(result.omega[:single][elastic] / reference[elastic] - 1).max()
    return {"points": points, "workers": workers, "batch_seconds": batch_seconds,
            "points_per_second": points / batch_seconds,
            "single_seconds_per_point": single_seconds,
            "speedup": single_seconds * points / batch_seconds,
            "svd_points": int((result.tier == 2).sum()),
            "fallback_points": int(result.fallback.sum()),
            "max_relative_difference": float(difference), "blas_threads": threads}
