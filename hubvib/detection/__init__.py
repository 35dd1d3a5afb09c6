"""Detectability of a ring crack from natural-frequency shifts (SI inside).

One concept per module: ``options`` (the scene's ``[detection]`` table),
``spectrum_model`` (what detection and diagnosis need of a ring model: the rigid ring,
``RigidSpectrum`` over ``model`` / ``series`` / ``uncertainty`` / ``carrier``, and the
elastic ring, ``elastic_model``, implement it), ``pod`` (probability of detection and its
Monte Carlo, one rule for every model), ``result`` (one detection answer per ring model),
``resolution`` (where the POD crosses the required probability, and the depth a sweep
adds next), ``detectability`` and ``elastic_map`` (smallest detectable depth against the
mounting), ``mode_names`` and ``mode_map`` (one identity per mode, and which rigid mode an
elastic one is), ``measured`` (a CSV of identified frequencies), ``diagnosis`` (crack
depth from measured frequencies), ``numbers`` (round-off prints as 0) and ``plots`` (the
report sections: :mod:`hubvib.reports`).  Nothing heavy is imported here; matplotlib only
in ``plots``.  Every name below is imported on first use (PEP 562).
"""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .carrier import CarrierStudy, MeshTiming, carrier_study, mesh_timing
    from .detectability import DetectabilityMap, detectability_map
    from .diagnosis import Diagnosis, diagnose, diagnose_scene
    from .measured import Measured, MeasuredError, read_measured
    from .model import CrackModel
    from .options import DetectionOptions, parse_detection_table
    from .pod import PodResult, pod_study
    from .series import identify_mount, ring_support
    from .crack_detection import DetectionStudy, detection_study
    from .resolution import Bracket, bracket
    from .result import DetectionResult, rigid_result

__all__ = [
    "DetectionOptions", "parse_detection_table", "CrackModel", "identify_mount",
    "ring_support", "MeshTiming", "mesh_timing", "CarrierStudy", "carrier_study",
    "PodResult", "pod_study", "DetectabilityMap", "detectability_map", "DetectionStudy",
    "detection_study", "Measured", "MeasuredError", "read_measured", "Diagnosis",
    "diagnose", "diagnose_scene", "DetectionResult", "rigid_result", "Bracket", "bracket",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
