"""Monte Carlo over what is not known exactly: parameter scatter and FE error (SI).

Each sample is one reducer as built: every mass scattered by ``scatter_masses``,
every spring but the ring support by ``scatter_stiffnesses`` and the ring
support (the mounting under ``"series"``, the preset's ``c_ru``/``c_r`` under
``"ratio"``) by ``scatter_mounting``, each log-normal with that relative
standard deviation and independent.  The FE error estimates (three mesh
levels, ``fem.three_level``) are taken as standard deviations of a discretisation
error common to every depth of a sample: ``body(d) = FE(d) + z err(d)`` with one
standard normal ``z`` per stiffness.  Under ``"direct"`` the ring support is the
FE body itself and scatters only by that error.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.lumped.batch import batch_frequencies
from hubvib.lumped.parameters import MASS_FIELDS, STIFFNESS_FIELDS

from .carrier import observed_omega
from .series import SERIES, ring_support

#: springs scattered by ``scatter_stiffnesses`` (the ring support has its own scatter)
SPRINGS = tuple(f for f in STIFFNESS_FIELDS if f not in ("c_ru", "c_r"))


@dataclass(frozen=True)
class Samples:
    """``n`` draws of the uncertain reducer.

    Attributes
    ----------
    fields : dict
        Scattered masses [kg] and springs [N/m] other than the ring support, shape (n,).
    support_ru, support_r : ndarray
        Ring mounting [N/m] (``"series"``) or the preset's total (``"ratio"``), (n,).
    z_ru, z_r, z_rp : ndarray
        Standard normal FE errors of the body's c_ru, c_r and of the c_rp ratio, (n,).
    """

    fields: dict
    support_ru: np.ndarray
    support_r: np.ndarray
    z_ru: np.ndarray
    z_r: np.ndarray
    z_rp: np.ndarray

    @property
    def n(self) -> int:
        return self.z_ru.size


def lognormal(median, relative_std: float, rng, n: int) -> np.ndarray:
    """Log-normal draws with the given median and relative standard deviation [-]."""
    sigma = math.sqrt(math.log1p(relative_std ** 2))
    return median * np.exp(sigma * rng.standard_normal(n))


def draw(model, options, n: int, rng) -> Samples:
    """``n`` samples of ``model`` (CrackModel) under ``options`` (DetectionOptions)."""
    params = model.params
    fields = {name: lognormal(getattr(params, name), options.scatter_masses, rng, n)
              for name in MASS_FIELDS}
    fields |= {name: lognormal(getattr(params, name), options.scatter_stiffnesses, rng, n)
               for name in SPRINGS if getattr(params, name) > 0}
    if model.apply == SERIES:
        base_ru, base_r = model.c_ru_mount, model.c_r_mount
    else:
        base_ru, base_r = params.c_ru, params.c_r
    return Samples(fields, lognormal(base_ru, options.scatter_mounting, rng, n),
                   lognormal(base_r, options.scatter_mounting, rng, n),
                   rng.standard_normal(n), rng.standard_normal(n), rng.standard_normal(n))


def nominal(model) -> Samples:
    """One sample: the model as given (no scatter, no FE error)."""
    params = model.params
    base = ((model.c_ru_mount, model.c_r_mount) if model.apply == SERIES
            else (params.c_ru, params.c_r))
    return Samples({}, np.array([base[0]]), np.array([base[1]]), np.zeros(1), np.zeros(1),
                   np.zeros(1))


def changes(model, samples: Samples, k, engaged: bool) -> dict:
    """Batch changes (``lumped.batch``) of every sample at depth index ``k`` (an int, or
    one index per sample)."""
    def body(values, errors, z):
        values, errors = np.asarray(values), np.asarray(errors)
        return values[k] + z * errors[k], values[0] + z * errors[0]

    ru, ru0 = body(model.c_ru_body, model.c_ru_body_error, samples.z_ru)
    r, r0 = body(model.c_r_body, model.c_r_body_error, samples.z_r)
    if engaged:  # the FE ratio with its error, then the crack's method on this c_rp
        ratio = np.clip(np.asarray(model.c_rp_ratio)[k] + samples.z_rp * np.asarray(
            model.c_rp_ratio_error)[k], 1e-6, None)
        factor = model.c_rp_factor(k, ratio, samples.fields.get("c_rp"))
    else:
        factor = np.ones(samples.n)
    rest = np.ones((samples.n, model.params.n_planets - 1))
    return dict(samples.fields,
                c_ru=ring_support(model.apply, ru, ru0, samples.support_ru, samples.support_ru),
                c_r=ring_support(model.apply, r, r0, samples.support_r, samples.support_r),
                c_rp_factors=np.column_stack([np.clip(factor, 1e-6, None), rest]))


def observed_frequencies(model, samples: Samples, fraction: float, long_record: bool,
                         workers: int = 1, depth_index=None) -> np.ndarray:
    """Frequencies [Hz] a record sees, shape (samples, depths, modes), ascending per point.

    ``fraction``: time the cracked tooth is in mesh; ``long_record``: the record spans
    more than one engagement (see :mod:`hubvib.detection.carrier`).  With
    ``depth_index`` (one index per sample) only depth 0 and that depth are solved:
    shape (samples, 2, modes).
    """
    return observed_frequencies_of([(model, samples)], fraction, long_record, workers,
                                   depth_index)[0]


def observed_frequencies_of(pairs, fraction: float, long_record: bool, workers: int = 1,
                            depth_index=None) -> list[np.ndarray]:
    """:func:`observed_frequencies` of several ``(model, samples)`` pairs whose models share
    their ``params`` (variants of one CrackModel) and whose samples scatter the same
    fields, solved in one batch: the same numbers (each point is one LAPACK call,
    :mod:`hubvib.lumped.batch`) at one batch's overhead (nominal_shifts: 7 variants)."""
    params, fields = pairs[0][0].params, sorted(pairs[0][1].fields)
    for model, samples in pairs:
        if model.params != params:
            raise ValueError(f"observed_frequencies_of: the models must share their params; "
                             f"{model.params} differs from {params}")
        if sorted(samples.fields) != fields:
            raise ValueError(f"observed_frequencies_of: the samples must scatter the same "
                             f"fields; {sorted(samples.fields)} differs from {fields}")
    stacked, shapes = [], []
    for model, samples in pairs:
        ks = (list(range(len(model.depths))) if depth_index is None
              else [0, np.asarray(depth_index)])
        # every depth at once, in the order (depth, sample): the same elementwise
        # arithmetic as one call per depth, without its Python overhead
        every = np.concatenate([np.broadcast_to(k, samples.n) for k in ks])
        tiled = _tiled(samples, len(ks))
        stacked += [changes(model, tiled, every, engaged) for engaged in (True, False)]
        shapes.append((len(ks), samples.n))
    joined = {name: np.concatenate([c[name] for c in stacked]) for name in stacked[0]}
    omega = batch_frequencies(params, joined, workers=workers).omega
    out, start = [], 0
    for depths, n in shapes:
        part = omega[start:start + 2 * depths * n]
        start += part.shape[0]
        part = part.reshape(2, depths, n, -1).transpose(0, 2, 1, 3)
        out.append(observed_omega(part[0], part[1], fraction, long_record) / (2 * math.pi))
    return out


def _tiled(samples: Samples, times: int) -> Samples:
    """``samples`` repeated ``times`` times, one after the other."""
    def tile(values):
        return np.tile(values, times)

    return Samples({name: tile(v) for name, v in samples.fields.items()},
                   tile(samples.support_ru), tile(samples.support_r), tile(samples.z_ru),
                   tile(samples.z_r), tile(samples.z_rp))
