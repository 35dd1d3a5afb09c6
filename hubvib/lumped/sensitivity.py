"""Analytic derivatives of the natural frequencies with respect to a parameter.

For mass-normalised modes ``d lambda / dp = phi^T (dK/dp - lambda dM/dp) phi``.
A repeated frequency splits under a perturbation: its derivatives are the
eigenvalues of that matrix projected on the mode group, in ascending order.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .network import mass_diagonal, spring_network
from .parameters import MASS_FIELDS, ParameterError, PlanetaryParameters
from .spectrum import Spectrum, natural_modes


@dataclass(frozen=True)
class Sensitivity:
    """Derivatives of every mode with respect to ``parameter``.

    ``d_eigenvalue`` [rad^2/s^2 per unit of p]; ``d_omega`` [rad/s per unit of
    p] (for a rigid-body mode: 0 if it stays rigid, ``inf`` if p makes it
    elastic); ``relative = (p / omega) d omega / dp`` [-]: percent change of
    frequency per percent change of p (0 for rigid-body modes).
    """

    parameter: str
    spectrum: Spectrum
    d_eigenvalue: np.ndarray
    d_omega: np.ndarray
    relative: np.ndarray


def frequency_sensitivity(
    params: PlanetaryParameters, parameter: str, method: str = "jacobi",
    spectrum: Spectrum | None = None,
) -> Sensitivity:
    """Analytic ``d omega_i / d parameter`` for a stiffness or mass parameter."""
    spectrum = spectrum or natural_modes(params, method)
    dK, dM = _matrix_derivatives(params, parameter)
    d_lambda = np.zeros(spectrum.eigenvalues.size)
    groups = np.array(spectrum.group)
    for g in np.unique(groups):
        idx = np.flatnonzero(groups == g)
        lam = spectrum.eigenvalues[idx[0]]
        phi = spectrum.shapes[:, idx]
        projected = phi.T @ (dK - lam * dM) @ phi
        d_lambda[idx] = np.linalg.eigvalsh(0.5 * (projected + projected.T))
    omega = spectrum.omega
    elastic = omega > 0
    d_omega = np.where(d_lambda > 0, np.inf, 0.0)
    d_omega[elastic] = d_lambda[elastic] / (2 * omega[elastic])
    relative = np.zeros_like(d_omega)
    relative[elastic] = getattr(params, parameter) * d_omega[elastic] / omega[elastic]
    return Sensitivity(parameter, spectrum, d_lambda, d_omega, relative)


def _matrix_derivatives(params, parameter):
    n = params.n_dof
    dK, dM = np.zeros((n, n)), np.zeros((n, n))
    network = spring_network(params)
    rows = network.rows_of(parameter)
    if rows.any():
        dK = network.G[rows].T @ network.G[rows]
    elif parameter in MASS_FIELDS:  # the mass matrix is linear in each mass field
        dM = np.diag(mass_diagonal(params.replace(**{parameter: 2.0}))
                     - mass_diagonal(params.replace(**{parameter: 1.0})))
    else:
        raise ParameterError(
            f"parameter = {parameter!r}: sensitivities exist for stiffnesses "
            f"{sorted(set(network.parameter))} and masses {list(MASS_FIELDS)}"
        )
    return dK, dM
