"""Frequency shift between a baseline and a modified parameter set."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.lumped.parameters import ParameterError, scalar_field_names

from .parameters import PlanetaryParameters
from .sweep import sweep


#: relative frequency change at or below which a shift is the eigensolver's round-off
ROUND_OFF = 1e-10


@dataclass(frozen=True)
class FrequencyShift:
    """Per-mode shift; modes matched by shape along a continuation path.

    ``omega_base``, ``omega_modified`` [rad/s]; ``percent`` is
    ``100 (omega_modified - omega_base) / omega_base``.  A change within
    :data:`ROUND_OFF` of the base frequency is exactly 0: a mode the parameter does not
    touch (its sign would be the eigensolver's round-off, which differs between BLAS
    builds).
    """

    parameter: str
    base_value: float
    modified_value: float
    kind: tuple[str, ...]
    omega_base: np.ndarray
    omega_modified: np.ndarray

    @property
    def delta_rad_s(self) -> np.ndarray:
        delta = self.omega_modified - self.omega_base
        return np.where(np.abs(delta) <= ROUND_OFF * np.abs(self.omega_base), 0.0, delta)

    @property
    def delta_hz(self) -> np.ndarray:
        return self.delta_rad_s / (2 * math.pi)

    @property
    def percent(self) -> np.ndarray:
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.omega_base > 0, 100 * self.delta_rad_s / self.omega_base, 0.0)

    def rows(self) -> list[dict]:
        return [
            {
                "mode": i + 1, "kind": k,
                "omega_base_rad_s": float(a), "omega_modified_rad_s": float(b),
                "delta_rad_s": float(d), "delta_hz": float(h), "percent": float(p),
            }
            for i, (k, a, b, d, h, p) in enumerate(
                zip(self.kind, self.omega_base, self.omega_modified,
                    self.delta_rad_s, self.delta_hz, self.percent)
            )
        ]


def frequency_shift(
    params: PlanetaryParameters, parameter: str, modified_value: float,
    steps: int = 16, method: str = "jacobi",
) -> FrequencyShift:
    """Shift of every mode when ``parameter`` goes from its value in ``params``
    to ``modified_value``.

    Modes are followed through ``steps`` intermediate values (geometric when
    both ends are positive) so that crossings do not swap them.
    """
    if parameter not in scalar_field_names():
        raise ParameterError(f"parameter = {parameter!r}; allowed one-number fields: "
                             f"{', '.join(scalar_field_names())}")
    base = float(getattr(params, parameter))
    params.replace(**{parameter: float(modified_value)})  # validates the target
    if base > 0 and modified_value > 0:
        path = np.geomspace(base, modified_value, steps + 1)
    else:
        path = np.linspace(base, modified_value, steps + 1)
    result = sweep(params, parameter, path, method)
    return FrequencyShift(
        parameter, base, float(modified_value), result.kind, result.omega[0], result.omega[-1]
    )
