"""What moves the frequencies between two records besides a crack: temperature and load (SI).

Temperature: a uniform temperature change dT of an all-steel reducer scales every
spring by ``1 + (e_E + alpha) dT`` (the modulus falls by ``e_E`` per K, every
length grows by the expansion ``alpha`` per K; a spring of an elastic body is
proportional to E times a length) and leaves every mass unchanged, so every
natural frequency moves by the same relative amount ``(e_E + alpha) dT / 2``.
Load: the mesh stiffnesses depend on the transmitted torque (Hertzian contact
and tooth bending); a load change between records is taken as a common
relative change ``dL`` of every sun-planet and ring-planet mesh stiffness,
which moves mode i by ``f_i (S_sp,i + S_rp,i) dL`` (relative sensitivities,
:func:`hubvib.lumped.frequency_sensitivity`).  Both are normal with the
scene's standard deviations, independent.  Carrier position is no drift: a
record longer than one pass sees the time-averaged stiffness
(:mod:`.carrier`).

Compensation: the statistic of a watched mode i minus ``f_i / f_r`` times that of
a reference mode r that the crack does not move removes a uniform relative
shift (temperature) exactly and the load term where the two modes share their
mesh sensitivity.  :func:`references` picks, per watched mode, the unmoved mode
leaving the least variance.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubvib.lumped import frequency_sensitivity


@dataclass(frozen=True)
class Drift:
    """Drift of the natural frequencies between two records.

    Attributes
    ----------
    per_kelvin_hz : ndarray, shape (modes,)
        Frequency change per K of uniform temperature change [Hz/K].
    per_load_hz : ndarray, shape (modes,)
        Frequency change per unit relative change of every mesh stiffness [Hz].
    temperature_std : float
        Standard deviation of the temperature change between records [K].
    load_std : float
        Standard deviation of the relative mesh-stiffness change between records [-].
    """

    per_kelvin_hz: np.ndarray
    per_load_hz: np.ndarray
    temperature_std: float
    load_std: float

    def covariance(self) -> np.ndarray:
        """Covariance [Hz^2] of the drift of all modes, (modes, modes)."""
        t = self.temperature_std * self.per_kelvin_hz
        g = self.load_std * self.per_load_hz
        return np.outer(t, t) + np.outer(g, g)

    def draw(self, rng, n: int) -> np.ndarray:
        """``n`` drift vectors [Hz], shape (n, modes)."""
        z = rng.standard_normal((n, 2))
        return (np.outer(z[:, 0] * self.temperature_std, self.per_kelvin_hz)
                + np.outer(z[:, 1] * self.load_std, self.per_load_hz))


def drift_model(params, frequency_hz, options, method: str = "jacobi") -> Drift:
    """Drift of the modes of ``params`` (intact) with nominal frequencies ``frequency_hz``
    [Hz] under ``options`` (DetectionOptions)."""
    f = np.asarray(frequency_hz, dtype=float)
    per_kelvin = 0.5 * (options.modulus_per_K + options.expansion_per_K) * f
    mesh = sum(frequency_sensitivity(params, name, method).relative
               for name in ("c_sp", "c_rp"))
    return Drift(per_kelvin, f * mesh, options.temperature_std, options.mesh_load_std)


#: relative difference of two compensation variances below which they are the same
TIE = 1e-9


def references(shift_hz: np.ndarray, sigma_hz: np.ndarray, drift: Drift,
               frequency_hz: np.ndarray, watched: np.ndarray,
               separation: float = 0.0) -> np.ndarray:
    """Per watched mode, the reference mode (0-based) for compensation: among the modes
    the deepest crack moves by less than a tenth of their identification scatter and
    that lie more than ``separation`` times the watched mode's frequency away from it
    and from every watched mode (their identification bands must not overlap: the law
    holds for well-separated modes), the one leaving the least variance of
    ``s_i - (f_i / f_r) s_r``; -1 where none does.  Variances within :data:`TIE` of each
    other are equal (the members of a repeated pair): the lower mode number is taken, so
    the choice is not the eigensolver's round-off."""
    f = np.asarray(frequency_hz, dtype=float)
    still = np.flatnonzero(np.abs(shift_hz) < 0.1 * sigma_hz)
    chosen = []
    for i in watched:
        best, value = -1, np.inf
        for r in still:
            if r == i or f[r] <= 0 or (np.abs(f[r] - f[watched])
                                       <= separation * f[watched]).any():
                continue
            q = f[i] / f[r]
            var = (2 * sigma_hz[i] ** 2 + 2 * (q * sigma_hz[r]) ** 2
                   + (drift.temperature_std * (drift.per_kelvin_hz[i]
                                               - q * drift.per_kelvin_hz[r])) ** 2
                   + (drift.load_std * (drift.per_load_hz[i] - q * drift.per_load_hz[r])) ** 2)
            if var < value * (1 - TIE):
                best, value = int(r), var
        chosen.append(best)
    return np.array(chosen, dtype=int)


def compensate(values: np.ndarray, frequency_hz: np.ndarray, watched: np.ndarray,
               refs: np.ndarray) -> np.ndarray:
    """Statistics of the watched modes, each minus ``f_i / f_r`` times its reference
    mode's (where it has one), from ``values`` (..., modes) [Hz]."""
    f = np.asarray(frequency_hz, dtype=float)
    out = np.array(values[..., watched], dtype=float)
    has = refs >= 0
    ratio = f[watched][has] / f[refs[has]]
    out[..., has] -= ratio * values[..., refs[has]]
    return out


def family_pod(shifts: np.ndarray, sigma_hz: np.ndarray, frequency_hz: np.ndarray,
               watched: np.ndarray, alpha: float, rng, drift: Drift | None = None,
               refs: np.ndarray | None = None, calibration: int = 20000) -> np.ndarray:
    """Probability that some watched mode alarms, per depth, by Monte Carlo (own intact
    baseline, two records each with normal identification noise ``sigma_hz`` [Hz]).

    ``shifts`` (samples, depths, modes) [Hz]: the sampled reducers' shifts; ``drift``: add
    a drift between the records; ``refs``: compensate each watched mode by its reference
    mode (:func:`compensate`).  The alarm rule ``c_i < -z s_i`` (``s_i`` the standard
    deviation of mode i's statistic on intact reducers) has one ``z``, calibrated on
    ``calibration`` intact draws so that the family raises a false alarm with
    probability ``alpha``.
    """
    sigma = np.asarray(sigma_hz, dtype=float)
    modes = shifts.shape[-1]

    def noise(count):
        e = rng.standard_normal((count, modes)) * np.sqrt(2.0) * sigma
        return e + (drift.draw(rng, count) if drift is not None else 0.0)

    def statistic(values):
        return values[..., watched] if refs is None else compensate(values, frequency_hz,
                                                                    watched, refs)

    intact = statistic(noise(calibration))
    spread = intact.std(axis=0)
    z = -np.quantile((intact / spread).min(axis=1), alpha)
    observed = statistic(shifts + noise(shifts.shape[0])[:, None, :])
    return (observed < -z * spread).any(axis=-1).mean(axis=0)
