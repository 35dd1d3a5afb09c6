"""The plane crack study's typed result: per depth the FE stiffnesses, the lumped
parameters and the tracked spectrum, and the rows its tables are written from (SI inside;
the row keys carry the units of the CSV / JSON boundary)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from hubvib.cases.results import PlaneCase
from hubvib.detection.mode_names import mode_names
from hubvib.foundation.output import explained
from hubvib.detection.model import CrackModel
from hubvib.lumped import Spectrum, frequency_sensitivity
from hubvib.studies.kind_registry import Scene

__all__ = ["SENSITIVE", "STIFFNESSES", "CrackStudyResult"]

#: a mode "follows" a stiffness when its relative sensitivity exceeds this
SENSITIVE = 0.01
#: the stiffnesses a ring crack changes (c_rp: all planets' ring meshes together)
STIFFNESSES = ("c_ru", "c_r", "c_rp")
#: why the rigid ring's sweep adds no depths
RIGID_REFINEMENT = ("the scene's FE depths only: each added depth would cost FE runs of the "
                    "ring (the elastic ring adds depths)")


@dataclass
class CrackStudyResult:
    """Per depth: the FE stiffnesses, the lumped parameters used and the tracked spectrum.

    ``omega[k, i]`` [rad/s] is mode i (numbered at depth 0) at ``depths[k]``;
    ``model`` is the crack as the lumped model sees it, ``detection`` the
    detection study (None when not run), ``c_rp_comparison`` the record shifts under
    the other c_rp method (``detection.mesh_stiffness``; None where the methods agree).
    """

    scene: Scene
    fe: list[PlaneCase]
    c_ru: np.ndarray
    c_r: np.ndarray
    c_rp_factor: np.ndarray
    spectra: list[Spectrum]
    omega: np.ndarray
    computed: int
    files: list[Path] = field(default_factory=list)
    report: str = ""  # the report.md text, once written
    model: CrackModel | None = None
    detection: object = None
    c_rp_comparison: object = None
    elastic: object = None  # hubvib.detection.result.DetectionResult, when the scene asks
    half_length: float | None = None
    elastic_validity: object = None  # hubvib.elastic.validity.ValidityBand, with ``elastic``
    elastic_map: object = None  # hubvib.detection.elastic_map.ElasticMap, ``[elastic] map``
    mode_map: tuple = ()  # hubvib.detection.mode_map.ModePair per elastic mode
    load_sensitivity: tuple = ()  # hubvib.detection.load_sensitivity.LoadVariant each
    pad_variant: object = None  # hubvib.detection.pad_variant.PadVariant, [elastic] pad_variant
    pad_variant_reason: str = "the elastic ring did not run"  # why ``pad_variant`` is None

    @cached_property
    def rigid(self):
        """The rigid ring's detection answer (``detection.result.DetectionResult``; None
        without the detection study): the scene's FE depths, none added (each would cost
        FE runs)."""
        if self.detection is None:
            return None
        from hubvib.detection.result import rigid_result

        return rigid_result(self.detection.pod, self.detection.options, self.kind,
                            RIGID_REFINEMENT)

    @property
    def labels(self) -> list[str]:
        """Per rigid-ring mode its identity: ``rigid 13 (rotational, 4548.5 Hz)``."""
        from hubvib.detection.mode_names import rigid_label

        f = self.omega[0] / (2 * math.pi)
        return [rigid_label(i, kind, f[i]) for i, kind in enumerate(self.kind)]

    @property
    def depths(self) -> np.ndarray:
        return np.array(self.scene.crack.depths)

    @property
    def kind(self) -> tuple[str, ...]:
        return self.spectra[0].kind

    @property
    def names(self) -> list[str]:
        """Per mode its name in every table and figure (split pairs named)."""
        return mode_names(self.omega[0])

    @property
    def percent(self) -> np.ndarray:
        return 100 * (self.omega / self.omega[0] - 1)

    def stiffness_rows(self) -> list[dict]:
        """Per depth the FE case (``PlaneCase``) beside the lumped values; the keys with units
        are the CSV / JSON boundary."""
        rows = []
        for case, cu, cr, fp in zip(self.fe, self.c_ru, self.c_r, self.c_rp_factor):
            f = case.estimate
            rows.append({
                "depth_mm": 1e3 * case.depth, "fe_c_ru_N_m": f.c_ru,
                "fe_c_ru_error_N_m": f.c_ru_error,
                "fe_c_ru_min_N_m": f.c_ru_min, "fe_c_ru_max_N_m": f.c_ru_max,
                "fe_c_r_N_m": f.c_r, "fe_c_r_error_N_m": f.c_r_error,
                "fe_c_rp_engaged_ratio": f.c_rp_engaged_ratio,
                "fe_c_rp_engaged_ratio_error": f.c_rp_engaged_ratio_error,
                "fe_c_rp_engaged_min_ratio": f.c_rp_engaged_min_ratio,
                "lumped_c_ru_N_m": float(cu), "lumped_c_r_N_m": float(cr),
                "lumped_c_rp_planet1_N_m": float(self.model.params.c_rp * fp),
                "fe_seconds": case.seconds_total,
                "fe_c_rp_engaged_intact_N_m": f.c_rp_engaged_intact,
                "lumped_c_rp_factor": float(fp),
                "lumped_c_rp_planet1_ratio_method_N_m": float(
                    self.model.params.c_rp * f.c_rp_engaged_ratio),
                "fe_c_rp_engaged_intact_window_N_m": f.c_rp_engaged_intact_window,
                "fe_c_ru_root_land_N_m": f.c_ru_root_land,
                "fe_c_r_root_land_N_m": f.c_r_root_land})
        return rows

    def frequency_rows(self) -> list[dict]:
        rows = []
        for k, depth in enumerate(self.depths):
            for i, kind in enumerate(self.kind):
                rows.append({"depth_mm": 1e3 * depth, "mode": i + 1,
                             "mode_name": self.names[i], "mode_label": self.labels[i],
                             "kind": kind,
                             "omega_rad_s": float(self.omega[k, i]),
                             "frequency_hz": float(self.omega[k, i] / (2 * math.pi)),
                             "shift_hz": float((self.omega[k, i] - self.omega[0, i]) / (2 * math.pi)),
                             "shift_percent": float(self.percent[k, i])})
        return rows

    @cached_property
    def sensitivities(self) -> dict[str, np.ndarray]:
        """Per stiffness of ``STIFFNESSES`` each mode's relative sensitivity
        (dω/ω)/(dc/c) at depth 0, solved once."""
        params = self.model.params if self.model is not None else self.scene.params
        base = self.spectra[0]
        return {name: frequency_sensitivity(params, name, self.scene.method, base).relative
                for name in STIFFNESSES}

    def mode_rows(self) -> list[dict]:
        """Per mode: what it follows (c_ru, c_r, c_rp), its largest shift, the depth from
        which it detects the crack (Monte Carlo POD, ``detectable_depth_mm``) and, for
        comparison, the first depth shifting it by the flat ``[study]`` threshold."""
        rel = self.sensitivities
        pod = self.detection.pod if self.detection is not None else None
        detectable = pod.detectable_depth() if pod is not None else None
        rows = []
        for i, kind in enumerate(self.kind):
            hits = np.flatnonzero(np.abs(self.percent[:, i]) >= self.scene.threshold_percent)
            follows = [n for n in STIFFNESSES if abs(rel[n][i]) > SENSITIVE] or ["none"]
            row = {"mode": i + 1, "mode_name": self.names[i], "mode_label": self.labels[i],
                   "kind": kind,
                   "frequency_intact_hz": float(self.omega[0, i] / (2 * math.pi)),
                   "shift_at_deepest_hz": float((self.omega[-1, i] - self.omega[0, i])
                                                / (2 * math.pi)),
                   "shift_at_deepest_percent": float(self.percent[-1, i]),
                   **{f"sensitivity_{n}": float(rel[n][i]) for n in STIFFNESSES},
                   "follows": "+".join(follows),
                   "smallest_detectable_depth_mm":
                       float(1e3 * self.depths[hits[0]]) if len(hits) else None}
            if pod is not None:
                row |= {"record_shift_at_deepest_hz": float(pod.nominal.shift_hz[-1, i]),
                        "sigma_hz": float(pod.sigma_hz[i]),
                        "signal_in": str(pod.nominal.carried_by[-1, i]),
                        "pod_at_deepest": float(pod.pod[-1, i]),
                        "detectable_depth_mm": (None if math.isnan(detectable[i])
                                                else 1e3 * float(detectable[i]))}
            deepest = f"{1e3 * self.depths[-1]:.3g} mm"
            rows.append(explained(
                row, smallest_detectable_depth_mm=(
                    f"no depth of the sweep (up to {deepest}) moves this mode by the "
                    f"scene's threshold of {self.scene.threshold_percent:g} %"),
                detectable_depth_mm=(
                    f"at no depth of the sweep (up to {deepest}) does this mode alone reach "
                    f"POD {pod.detection_probability:g} with a shift larger than the FE "
                    "error of what carries it" if pod is not None else "")))
        return rows

