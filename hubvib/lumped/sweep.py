"""Sweeps of one parameter with modes followed across crossings."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .parameters import ParameterError, PlanetaryParameters
from .spectrum import natural_modes
from .tracking import match


@dataclass(frozen=True)
class Sweep:
    """Frequencies along a sweep of ``parameter``.

    ``omega[k, i]`` [rad/s] is mode i (numbered by its order at the first
    value) at ``values[k]``; ``sorted_omega`` is the same without tracking.
    ``kind[i]`` is the mode type at the first value; ``mac_min[k]`` the
    weakest shape match between step k - 1 and k (1 for k = 0).
    """

    parameter: str
    values: np.ndarray
    omega: np.ndarray
    sorted_omega: np.ndarray
    kind: tuple[str, ...]
    mac_min: np.ndarray

    def ratio(self, i_from: int, i_to: int) -> np.ndarray:
        """``omega`` at ``values[i_to]`` divided by that at ``values[i_from]``, per mode."""
        return self.omega[i_to] / self.omega[i_from]


def sweep(params: PlanetaryParameters, parameter: str, values, method: str = "jacobi") -> Sweep:
    """Natural frequencies for each value of ``parameter`` (others as in ``params``)."""
    values = np.asarray(values, dtype=float)
    if values.ndim != 1 or values.size < 1:
        raise ParameterError(f"values must be a non-empty 1-D sequence, got shape {values.shape}")
    spectra = [natural_modes(params.replace(**{parameter: float(v)}), method) for v in values]
    n = spectra[0].eigenvalues.size
    omega = np.empty((values.size, n))
    mac_min = np.ones(values.size)
    order = np.arange(n)
    omega[0] = spectra[0].omega
    for k in range(1, values.size):
        step, quality = match(spectra[k - 1], spectra[k])
        order = step[order]
        omega[k] = spectra[k].omega[order]
        mac_min[k] = quality.min()
    sorted_omega = np.array([s.omega for s in spectra])
    return Sweep(parameter, values, omega, sorted_omega, spectra[0].kind, mac_min)
