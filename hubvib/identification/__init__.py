"""Natural frequencies identified from vibration records, and how uncertain they are (SI).

``law`` (Au's uncertainty law and the Cramer-Rao bound of the shipped method),
``records`` (simulated ambient records of known modes), ``bfft`` (single-mode
Bayesian-FFT / Whittle identification of a frequency from one record), ``modes`` (every
identifiable mode of a record), ``readers`` (a measured record from a file) and
``montecarlo`` (the law checked against identified simulated records).  numpy and scipy
only; every name below is imported on first use (PEP 562).
"""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .bfft import IdentificationError, IdentifiedMode, identify_mode
    from .law import au_sigma_hz, fisher_sigma_hz
    from .modes import ModeIdentification, identify_modes
    from .montecarlo import Scatter, scatter
    from .readers import RecordError, read_record
    from .records import Record, simulate

__all__ = [
    "au_sigma_hz", "fisher_sigma_hz", "Record", "simulate", "IdentifiedMode",
    "IdentificationError", "identify_mode", "ModeIdentification", "identify_modes",
    "RecordError", "read_record", "Scatter", "scatter",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
