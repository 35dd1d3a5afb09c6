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

    def watched_modes(self, count: int | None = None) -> np.ndarray:
        """Mode indices (0-based) of the alarm family: the modes whose deepest-crack shift
        is largest against their identification scatter (:func:`.pod.watched`)."""
        return self.pod.watched[:count]


def detection_study(model, options: DetectionOptions, timing: MeshTiming,
                    workers: int = 1) -> DetectionStudy:
    """POD at the model's mounting, the map against the mounting, spectra against the
    carrier position (``model``: a CrackModel)."""
    return DetectionStudy(options, timing, pod_study(model, options, timing, workers=workers),
                          detectability_map(model, options, timing, workers=workers),
                          carrier_study(model, timing, options.record_length))
