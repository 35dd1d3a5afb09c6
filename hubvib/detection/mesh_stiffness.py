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


def mesh_stiffness_section(model, iso: float, comparison: MethodComparison | None,
                           watched, pod=None) -> list[str]:
    """Report lines: which c_rp the lumped model uses and why, with the FE, ISO 6336-1
    and lumped values [N/m]; with ``comparison`` the shifts of the ``watched`` modes
    (0-based) under both methods and, with ``pod`` (the model's PodResult) and the
    comparison's ``other_pod``, the depth the watched family detects under each."""
    fe = model.c_rp_fe[0]
    lumped = model.params.c_rp
    lines = ["## Ring-planet mesh stiffness", ""]
    window = model.c_rp_fe_window[0] if model.c_rp_fe_window else float("nan")
    numbers = (f"FE intact c_rp {fe:.4g} N/m over the mesh cycle and {window:.4g} N/m over "
               f"the cracked tooth's contact window, ISO 6336-1 c_gamma_alpha b {iso:.4g} N/m")
    if model.c_rp_source == "fe":
        lines.append(
            f"The lumped model uses the FE intact c_rp = {fe:.4g} N/m for every planet "
            f"({numbers}): the design gives no c_rp, and one mesh stiffness serves the intact "
            "and the cracked tooth. The crack's FE compliance (1/ratio - 1) over the window's "
            "intact mean, in series with it, scales planet 1's c_rp by the FE cracked/intact "
            f"ratio's change times {fe / window:.4g} to first order (the two means' ratio).")
    else:
        lines.append(
            f"The lumped model uses the given c_rp = {lumped:.4g} N/m ({numbers}). A given "
            "value is an effective mesh stiffness that holds more compliance than the tooth "
            "pair's (for the paper's Raba 118/76 preset, its table's value). The crack adds "
            "the FE compliance (1/ratio - 1)/c_rp_FE (c_rp_FE: the intact mean over the "
            "contact window, the ratio's denominator) in series with it (method `series`, "
            "primary). Multiplying the given c_rp by the FE ratio instead (method `ratio`, "
            "used before issue 22) treats all of it as the tooth pair's: an upper bound of "
            "the crack's effect.")
    lines.append("")
    if comparison is None:
        return lines
    lines += ["Time-averaged shift a record sees [Hz] under both methods, and planet 1's "
              "c_rp factor with the cracked tooth in mesh (`results.json`: "
              "`mesh_stiffness`, `c_rp_methods`):", ""]
    head = (f"| depth [mm] | factor {comparison.method} | factor {comparison.other} | "
            + " | ".join(f"mode {i + 1} {comparison.method} | mode {i + 1} {comparison.other}"
                         for i in watched))
    lines += [head + " |", "|---:|---:|---:|" + "---:|---:|" * len(watched)]
    for k, d in enumerate(comparison.depths):
        cells = [f"{comparison.shift_hz[k, i]:+.3g} | {comparison.other_shift_hz[k, i]:+.3g}"
                 for i in watched]
        lines.append(f"| {1e3 * d:.3g} | {comparison.factor[k]:.4f} | "
                     f"{comparison.other_factor[k]:.4f} | " + " | ".join(cells) + " |")
    lines.append("")
    if pod is None or comparison.other_pod is None:
        return lines
    mine, other = family_depths(pod), family_depths(comparison.other_pod)
    lines += [f"Smallest depth the watched modes detect together (POD >= "
              f"{pod.detection_probability:g}, family-wise false-alarm rate "
              f"{pod.false_alarm_rate:g}, no drift; the same Monte Carlo draws):", "",
              f"| record [s] | {comparison.method} (primary) | {comparison.other} |",
              "|---:|---:|---:|"]
    for T in mine:
        cells = ["none" if np.isnan(d) else f"{1e3 * d:.3g} mm" for d in (mine[T], other[T])]
        lines.append(f"| {T:g} | " + " | ".join(cells) + " |")
    return lines + [""]
