"""POD of the frequency route beside the indicators' (SI).

The frequency route compares natural frequencies identified in a record of the reducer
now with those of an intact record.  Per crack depth of the study, the frequencies a
long record sees are those of the time-averaged stiffness (:mod:`hubvib.detection.carrier`:
``lambda = (1 - f) lambda_out + f lambda_in`` mode by mode), with the engaged planet's
ring mesh at the engagement window's mean ratio cracked / intact
(:func:`hubvib.signal.ambient.engaged_ratio`) for the fraction ``f`` of the time the
cracked tooth spends in that window with some planet.  Modes the single-mode identifier
can use (:func:`hubvib.identification.modes.identifiable`) enter with the Cramer-Rao
standard deviation of the Bayesian-FFT identification (:func:`hubvib.identification.law.
fisher_sigma_hz`, acceleration response shape) at the record's length and the study's
damping, at a modal signal-to-noise ratio ``SNR`` (the diagnosis default).

Test per mode: the drop ``-(f_now - f_intact) / (sqrt 2 sigma)`` above ``z(1 - alpha / m)``
(m modes, Bonferroni: family-wise false-alarm rate at most ``alpha``, the indicators'
rate); a crack only softens the ring, so the test is one-sided.  The modes' errors are
independent, so ``POD = 1 - prod_i Phi(z - delta_i / (sqrt 2 sigma_i))``.  The law is
nominal: no scatter of the reducer's parameters, no drift between the records (both
lower the POD; see ``hubvib diagnose``).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.stats import norm

from hubvib.foundation.output import explained
from hubvib.identification.law import fisher_sigma_hz
from hubvib.identification.modes import identifiable
from hubvib.identification.records import Record
from hubvib.lumped import natural_modes

from .ambient import engaged_ratio
from .mesh_curves import MeshCurves
from .mesh_phase import MeshPhasing

#: modal signal-to-noise ratio of the identification [-] (``[detection] snr`` default)
SNR = 100.0


def observed_hz(params, curves: MeshCurves, phasing: MeshPhasing) -> np.ndarray:
    """Natural frequencies [Hz] a long record sees at the depth of ``curves`` (already
    scaled as the study's ``mesh_stiffness`` says)."""
    base = params.replace(c_sp=curves.sun_mean, c_rp=curves.ring_mean, c_rp_factors=())
    out = natural_modes(base).omega ** 2
    ratio = engaged_ratio(curves)
    if ratio == 1.0:
        return np.sqrt(out) / (2 * math.pi)
    n = params.n_planets
    inside = natural_modes(base.replace(c_rp_factors=(ratio,) + (1.0,) * (n - 1))).omega ** 2
    span = (curves.cracked_s[-1] - curves.cracked_s[0]) / phasing.ring_base_radius
    fraction = min(1.0, n * span / (2 * math.pi))
    return np.sqrt((1 - fraction) * out + fraction * inside) / (2 * math.pi)


def frequency_route(params, curves: list[MeshCurves], phasing: MeshPhasing,
                    damping_ratio: float, record_s: float, sample_rate: float,
                    false_alarm_rate: float) -> dict:
    """POD per depth of the frequency route (module docstring) and what it rests on."""
    f = np.array([observed_hz(params, c, phasing) for c in curves])
    probe = Record(np.zeros(max(2, int(record_s * sample_rate))), sample_rate)
    kappas, skipped = identifiable(f[0], damping_ratio, probe)
    modes = sorted(kappas)
    sigma = np.array([fisher_sigma_hz(f[0, i], damping_ratio, record_s, SNR, kappas[i], 4)
                      for i in modes])
    shift = f[:, modes] - f[0, modes]
    pod = [0.0] * len(curves)
    if modes:
        z = norm.ppf(1 - false_alarm_rate / len(modes))
        miss = norm.cdf(z + shift / (math.sqrt(2) * sigma)).prod(axis=1)
        pod = [float(1 - m) for m in miss]
    depths = [1e3 * c.depth for c in curves]
    seen = next((d for d, p in zip(depths, pod) if p >= 0.9), None)
    return explained(
        {"modes": [i + 1 for i in modes], "sigma_hz": sigma.tolist(),
         "shift_hz": shift.tolist(), "pod": pod, "first_depth_seen_mm": seen,
         "record_s": record_s, "damping_ratio": damping_ratio, "snr": SNR,
         "skipped_modes": {str(i + 1): why for i, why in sorted(skipped.items())}},
        first_depth_seen_mm=(f"no depth of the sweep reaches POD 0.9 by the frequency route"
                             if modes else "no mode is identifiable from these records"))
