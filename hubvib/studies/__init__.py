"""What a scene or a command runs: the study kinds (``study``: what a kind is, the registry
and the scene, a tagged union of the kinds; ``kinds`` registers the shipped ones), the
lumped sweep (``sweep``), the plane crack study (``crack_study``; its result type
``crack_result``, the elastic ring beside it ``elastic_stage``), the solid crack growth
(``crack_growth``), the ``[crack]`` table both crack kinds own (``crack_table``; the FE
crack cases they share are ``hubvib.cases``), the scene file (``scene``: the common tables),
and a design's stiffness table (``stiffness``, what ``hubvib stiffness`` prints).  Every
name below is imported on first use (PEP 562)."""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .crack_growth import CrackGrowthResult, run_crack_growth
    from .lefm_path import CrackPathResult
    from .crack_study import CrackStudyResult, run_crack_study
    from .scene import load_scene, parse_scene, shipped_scenes
    from .stiffness import stiffness_table
    from .kind_registry import Scene, Study, register_study, select_study
    from .sweep import StudyResult, run_study

__all__ = [
    "Scene", "Study", "register_study", "select_study", "load_scene", "parse_scene",
    "shipped_scenes", "StudyResult", "run_study", "CrackStudyResult", "run_crack_study",
    "CrackGrowthResult", "run_crack_growth", "CrackPathResult", "stiffness_table",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
