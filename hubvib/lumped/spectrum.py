"""Natural frequencies and mode shapes as one result object."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import modes as _modes
from .eigensolve import solve_assembled, solve_network
from .network import dof_names, mass_diagonal, spring_network
from .parameters import MASS_FIELDS, STIFFNESS_FIELDS, ParameterError, PlanetaryParameters
from .printed import printed_stiffness_matrix


@dataclass(frozen=True)
class Spectrum:
    """Natural modes of one parameter set.

    Attributes
    ----------
    eigenvalues : ndarray
        ``lambda = omega^2`` [rad^2/s^2], ascending; negative only for an
        indefinite matrix (the paper's printed one).
    shapes : ndarray, shape (n_dof, n_modes)
        Mass-normalised mode shapes [m/sqrt(kg)], one column per mode, in
        canonical form (sign-fixed, repeated frequencies in a basis that does
        not depend on the solver).  Row order: :func:`lumped.network.dof_names`.
    mass : ndarray
        Diagonal of the mass matrix [kg].
    kind : tuple of str
        'rigid-body', 'rotational', 'translational', 'planet' or 'mixed'.
    multiplicity : tuple of int
        Number of modes sharing each mode's frequency.
    group : tuple of int
        Index of the repeated-frequency group each mode belongs to.
    n_rigid : int
        Number of rigid-body modes (their eigenvalues are exactly 0).
    method : str
        Eigensolver used.
    """

    params: PlanetaryParameters
    eigenvalues: np.ndarray
    shapes: np.ndarray
    mass: np.ndarray
    kind: tuple[str, ...]
    multiplicity: tuple[int, ...]
    group: tuple[int, ...]
    n_rigid: int
    method: str

    @property
    def omega(self) -> np.ndarray:
        """Natural frequencies [rad/s]; ``sqrt(|lambda|)`` where lambda < 0."""
        return np.sqrt(np.abs(self.eigenvalues))

    @property
    def frequency_hz(self) -> np.ndarray:
        """Natural frequencies [Hz]."""
        return self.omega / (2 * math.pi)

    @property
    def imaginary(self) -> np.ndarray:
        """True where lambda < 0: the 'frequency' is the magnitude of an imaginary root."""
        return self.eigenvalues < 0

    @property
    def dof_names(self) -> tuple[str, ...]:
        return dof_names(self.params.n_planets)

    def rows(self) -> list[dict]:
        """One dict per mode, for tables, CSV and JSON."""
        return [
            {
                "mode": i + 1,
                "omega_rad_s": float(w),
                "frequency_hz": float(f),
                "kind": k,
                "multiplicity": m,
                "imaginary": bool(im),
            }
            for i, (w, f, k, m, im) in enumerate(
                zip(self.omega, self.frequency_hz, self.kind, self.multiplicity, self.imaginary)
            )
        ]


def natural_modes(params: PlanetaryParameters, method: str = "jacobi") -> Spectrum:
    """Natural modes of the energy-consistent model (see :mod:`lumped.eigensolve`)."""
    mass = mass_diagonal(params)
    with np.errstate(over="ignore", invalid="ignore"):
        lam, shapes, n_rigid = solve_network(spring_network(params), mass, method)
    _check_finite(params, lam, shapes)
    return _spectrum(params, lam, shapes, mass, n_rigid, method)


def printed_modes(params: PlanetaryParameters) -> Spectrum:
    """Modes of the paper's printed matrix (eq. 11-13); it is indefinite.

    The eigenvalues keep their sign; ``omega`` is ``sqrt(|lambda|)``, which is
    how the published table was evidently obtained.
    """
    mass = mass_diagonal(params)
    with np.errstate(over="ignore", invalid="ignore"):
        lam, shapes = solve_assembled(printed_stiffness_matrix(params), mass,
                                      allow_indefinite=True)
    _check_finite(params, lam, shapes)
    order = np.argsort(np.abs(lam), kind="stable")
    return _spectrum(params, lam[order], shapes[:, order], mass, 0, "eigh (printed matrix)")


def _check_finite(params: PlanetaryParameters, lam, shapes) -> None:
    """Refuse a spectrum beyond double precision (omega^2 above ~1.8e308 rad^2/s^2)."""
    if np.all(np.isfinite(lam)) and np.all(np.isfinite(shapes)):
        return
    stiff = max(STIFFNESS_FIELDS, key=lambda name: getattr(params, name))
    light = min(MASS_FIELDS, key=lambda name: getattr(params, name))
    exponent = math.log10(getattr(params, stiff)) - math.log10(getattr(params, light))
    ratio = f"{10 ** (exponent % 1):.2f}e{math.floor(exponent):+d}"  # may exceed the float range
    raise ParameterError(
        f"natural frequencies overflow double precision ({int(np.sum(~np.isfinite(lam)))} of "
        f"{lam.size} not finite): {stiff} = {getattr(params, stiff):.3g} N/m over {light} = "
        f"{getattr(params, light):.3g} kg is {ratio} 1/s^2; stiffness/mass ratios must stay "
        "well below 1e300 1/s^2"
    )


def _spectrum(params, lam, shapes, mass, n_rigid, method) -> Spectrum:
    omega = np.sqrt(np.abs(lam))
    root_mass = np.sqrt(mass)[:, None]
    canonical = shapes.copy()
    kind = [""] * lam.size
    multiplicity = [0] * lam.size
    group = [0] * lam.size
    for g, idx in enumerate(_modes.clusters(omega, n_rigid)):
        W = _modes.canonical_basis(root_mass * shapes[:, idx])
        canonical[:, idx] = W / root_mass
        label = "rigid-body" if idx[0] < n_rigid else _modes.mode_type(W)
        for i in idx:
            kind[i], multiplicity[i], group[i] = label, idx.size, g
    return Spectrum(
        params=params, eigenvalues=lam, shapes=canonical, mass=mass, kind=tuple(kind),
        multiplicity=tuple(multiplicity), group=tuple(group), n_rigid=n_rigid, method=method,
    )
