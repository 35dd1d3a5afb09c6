"""Crack cases, the typed stage below the studies: the crack sweep and its accuracy presets
(``sweep``), one FE case typed (``results``: ``PlaneCase``, ``SolidCase``), the case runner
with its cache and worker plumbing (``runner``), and the predicted LEFM crack path a sweep
may follow (``path_growth``, ``predicted_path``).  The studies, detection and the signal
study build on it; it imports no layer above the runtime.  Every name below is imported on
first use (PEP 562)."""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .path_growth import grow_path
    from .predicted_path import predicted_crack
    from .results import PlaneCase, SolidCase
    from .runner import crack_cases, run_fe_cases
    from .sweep import ACCURACY, CrackSweep, crack_of

__all__ = ["CrackSweep", "ACCURACY", "crack_of", "PlaneCase", "SolidCase", "crack_cases",
           "run_fe_cases", "grow_path", "predicted_crack"]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
