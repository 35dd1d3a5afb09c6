"""The detection part of a crack study: POD, detectability map, carrier position (SI)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .carrier import CarrierStudy, MeshTiming, carrier_study
from .detectability import DetectabilityMap, detectability_map
from .options import DetectionOptions
from .pod import PodResult, pod_study


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

    def watched_modes(self, count: int = 3) -> np.ndarray:
        """Mode indices (0-based) to watch: the ones detecting the shallowest crack (ties:
        larger POD there), else the ones with the largest shift against the threshold at
        the deepest crack."""
        pod = self.pod
        depth = pod.detectable_depth()
        detectable = np.flatnonzero(~np.isnan(depth))
        if detectable.size:
            at = np.searchsorted(pod.depths, depth[detectable])
            order = np.lexsort((-pod.pod[at, detectable], depth[detectable]))
            return detectable[order][:count]
        margin = -pod.nominal.shift_hz[-1] / pod.threshold_hz
        return np.argsort(-margin, kind="stable")[:count]


def detection_study(model, options: DetectionOptions, timing: MeshTiming,
                    workers: int = 1) -> DetectionStudy:
    """POD at the model's mounting, the map against the mounting, spectra against the
    carrier position (``model``: a CrackModel)."""
    return DetectionStudy(options, timing, pod_study(model, options, timing, workers=workers),
                          detectability_map(model, options, timing, workers=workers),
                          carrier_study(model, timing, options.record_length))
