"""Companion analyses of neighbouring planetary transmissions (the seed papers).

Three studies, each a few modules: the efficiency of a planetary gear train and its
optimum design (``efficiency*``), the kinematic-error harmonics of a gear train
(``harmonics``) and the torus-screw (toroidal worm) gear with its N_x scatter
(``torus_screw*``, ``track_geometry``, ``nx_scatter``).  Every name below is imported on
first use (PEP 562); matplotlib only where a figure is drawn.
"""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .efficiency.core import Losses, Optimum, loss_curve, losses, optimum
    from .harmonics import GearTrain, HarmonicAnalysis, analyse, kinematic_error
    from .torus_screw.nx_scatter import ScatterInterval, scatter_interval
    from .torus_screw.gear import OperatingPoint, TorusScrewGear, roller_forces
    from .torus_screw.run import TorusScrewRun, run_torus_screw
    from .efficiency.track_geometry import TrackGeometry

__all__ = [
    "Losses", "losses", "loss_curve", "Optimum", "optimum",
    "GearTrain", "kinematic_error", "HarmonicAnalysis", "analyse",
    "TorusScrewGear", "OperatingPoint", "roller_forces", "TorusScrewRun",
    "run_torus_screw", "TrackGeometry", "ScatterInterval", "scatter_interval",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
