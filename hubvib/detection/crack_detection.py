"""The detection part of a crack study: POD, detectability map, carrier position (SI)."""
from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hubvib.foundation.blas import blas_threads
from hubvib.runtime.result_cache import cached_figure, cached_result

from hubvib.detection.carrier import CarrierStudy, MeshTiming, carrier_study
from hubvib.detection.mesh_stiffness import MethodComparison, compare_methods
from hubvib.detection.detectability import DetectabilityMap, detectability_map
from hubvib.detection.options import DetectionOptions
from hubvib.detection.pod import PodResult, pod_study


@dataclass(frozen=True)
class DetectionStudy:
    """What a crack of each depth does to what can be measured.

    Attributes
    ----------
    options : DetectionOptions
    timing : MeshTiming
    pod : PodResult
        At the scene's mounting.
    map : DetectabilityMap
        Against the mounting stiffness.
    carrier : CarrierStudy
        In and out of the cracked tooth's engagement.
    """

    options: DetectionOptions
    timing: MeshTiming
    pod: PodResult
    map: DetectabilityMap
    carrier: CarrierStudy

    def watched_modes(self, count: int | None = None) -> np.ndarray:
        """Mode indices (0-based) of the alarm family: the modes whose deepest-crack shift
        is largest against their identification scatter (:func:`.pod.watched`)."""
        return self.pod.watched[:count]


def detection_study(model, options: DetectionOptions, timing: MeshTiming,
                    workers: int = 1) -> DetectionStudy:
    """POD at the model's mounting, the map against the mounting, spectra against the
    carrier position (``model``: a CrackModel).

    With ``workers`` > 1 the scene's POD runs on a thread beside the map's threads, all
    at one BLAS thread (numpy releases the GIL in the eigen-solves and the bands; the
    process-wide BLAS count is set once here, not by each thread); the numbers are the
    same as on one thread."""
    with blas_threads(1):
        if workers <= 1:
            pod = pod_study(model, options, timing, workers=workers)
            return DetectionStudy(options, timing, pod,
                                  detectability_map(model, options, timing, workers=workers),
                                  carrier_study(model, timing, options.record_length))
        with ThreadPoolExecutor(1) as beside:
            pod = beside.submit(pod_study, model, options, timing, workers=workers)
            dmap = detectability_map(model, options, timing, workers=workers)
            carrier = carrier_study(model, timing, options.record_length)
            return DetectionStudy(options, timing, pod.result(), dmap, carrier)


#: the entry module of the cached detection results: they are keyed on the source of
#: every hubvib module it imports (``hubvib.foundation.source_graph``)
SOURCE = (__name__,)


def cached_detection_study(model, options: DetectionOptions, timing: MeshTiming,
                           workers: int = 1) -> DetectionStudy:
    """:func:`detection_study`, kept on disk by its inputs and by the source of the modules
    it runs (:mod:`hubvib.runtime.result_cache`): a rerun of a scene loads it."""
    return cached_result("detection", (model, options, timing, workers), SOURCE,
                         lambda: detection_study(model, options, timing, workers=workers),
                         DetectionStudy)


def cached_compare_methods(model, timing: MeshTiming, record_length: float, options=None,
                           workers: int = 1):
    """:func:`.mesh_stiffness.compare_methods`, kept on disk like
    :func:`cached_detection_study`."""
    return cached_result("c_rp_methods", (model, timing, record_length, options, workers),
                         SOURCE, lambda: compare_methods(model, timing, record_length,
                                                              options, workers=workers),
                         MethodComparison)


def cached_plot(path: Path, build, *args) -> Path:
    """``build(*args)`` (a figure of :mod:`.plots`) saved as PNG at ``path``, drawn once
    per data and source (:func:`hubvib.runtime.result_cache.cached_figure`)."""
    return cached_figure(path, build, args)
