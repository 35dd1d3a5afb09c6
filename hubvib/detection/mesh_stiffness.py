"""Which ring-planet mesh stiffness the crack model uses, and what the other method gives (SI).

The crack adds the FE compliance ``dq = (1/ratio - 1) / c_rp_FE``
[m/N] to planet 1's tooth pair over the cracked tooth's engagement; the lumped
model takes it in series with its ``c_rp`` (``model.C_RP_SERIES``).  Where the
lumped ``c_rp`` is not the FE one (the paper's preset: 3e8 N/m, an effective
value holding more compliance than the tooth pair's), multiplying it by the FE
ratio instead (``model.C_RP_RATIO``, formerly) gives a larger shift, an
upper bound of the crack's effect; both are reported there.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubvib.reducer.stages import gear_body, ring_gear, spur_gears
from hubvib.fem.iso6336 import iso_stiffness
from hubvib.fem.mesh_cycle import GearPair

from .model import C_RP_RATIO, C_RP_SERIES
from .pod import pod_study
from .uncertainty import nominal, observed_frequencies_of


def iso_c_rp(design) -> float:
    """ISO 6336-1 ring-planet mesh stiffness c_gamma_alpha b of ``design`` [N/m] (the mean
    mesh stiffness; ``hubvib stiffness`` prints it as ``c_gamma b``)."""
    _, planet, ring = spur_gears(design)
    pair = GearPair(gear_body(design, "planet"), ring_gear(design))
    return float(iso_stiffness(planet, ring, pair.contact_ratio).per_face_width(
        design.face_width)[1])


@dataclass(frozen=True)
class MethodComparison:
    """Nominal record-averaged frequencies [Hz] per depth and mode under the model's own
    c_rp method and under the other one.

    Attributes
    ----------
    depths : ndarray
        [m]
    method, other : str
        The model's method (primary) and the other one.
    frequency_hz, other_hz : ndarray, shape (depths, modes)
        Frequencies a record sees, ascending per depth [Hz].
    factor, other_factor : ndarray, shape (depths,)
        Factor on planet 1's lumped c_rp with the cracked tooth in mesh [-].
    other_pod : PodResult or None
        The Monte Carlo POD under the other method (``pod.pod_study``; None when not run),
        against the reducer's own baseline only: no model baseline, no drift curves (what
        the report and ``results.json`` give of it is the family POD).
    """

    depths: np.ndarray
    method: str
    other: str
    frequency_hz: np.ndarray
    other_hz: np.ndarray
    factor: np.ndarray
    other_factor: np.ndarray
    other_pod: object = None

    @property
    def shift_hz(self) -> np.ndarray:
        return self.frequency_hz - self.frequency_hz[0]

    @property
    def other_shift_hz(self) -> np.ndarray:
        return self.other_hz - self.other_hz[0]

    def rows(self) -> list[dict]:
        """Per depth and mode: both record-averaged shifts [Hz] (JSON keys)."""
        return [{"depth_mm": 1e3 * float(d), "mode": i + 1,
                 f"record_shift_{self.method}_hz": float(self.shift_hz[k, i]),
                 f"record_shift_{self.other}_hz": float(self.other_shift_hz[k, i])}
                for k, d in enumerate(self.depths) for i in range(self.frequency_hz.shape[1])]


def compare_methods(model, timing, record_length: float, options=None,
                    workers: int = 1) -> MethodComparison:
    """The nominal record-averaged spectra of ``model`` (CrackModel, series or ratio) and
    of the same model under the other c_rp method, for records of ``record_length`` [s]
    with ``timing`` (``carrier.MeshTiming``); with ``options`` (DetectionOptions) also
    the other method's POD."""
    other = C_RP_RATIO if model.c_rp_method == C_RP_SERIES else C_RP_SERIES
    variant = model.with_c_rp_method(other)
    fraction, long = timing.engaged_fraction, timing.long_record(record_length)

    # the same draws as the model's own POD (the model baseline's calibration draws come
    # after them, so leaving it out changes no number)
    other_pod = (None if options is None
                 else pod_study(variant, options, timing, workers=workers,
                                model_baseline=False))
    pair = observed_frequencies_of([(m, nominal(m)) for m in (model, variant)], fraction, long)
    return MethodComparison(np.array(model.depths), model.c_rp_method, other, pair[0][0],
                            pair[1][0], np.asarray(model.c_rp_factor()),
                            np.asarray(variant.c_rp_factor()), other_pod)


def family_depths(pod) -> dict:
    """Record length [s] -> smallest depth [m] the watched family detects (NaN: none)."""
    return {T: float(pod.family_detectable_depth(T)) for T in sorted(pod.family_pod)}
