"""Scripted checks of hubvib against published data, exact and high-precision references.

The face below is what a user of the validation stage imports: the Raba 118 check
against the published spectrum (``validate``, ``RabaValidation``, its report), the
mesh-convergence study of the FE stiffnesses against exact and handbook values
(``run_study``), the multiplicity pattern of planetary modes from theory
(``TheoryCheck``), the eigensolvers' stability table (``StabilityRow``), the
high-precision reference eigenvalues (mpmath) and the CalculiX cross-check.  Every name
is imported on first use (PEP 562): ``import hubvib.validation`` loads no FE stage.
"""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .calculix import CalculixError
    from .convergence import run_study, study_note
    from .raba118 import RabaValidation, format_report, validate, write_report
    from .reference import reference_eigenvalues
    from .stability import StabilityRow, format_table
    from .theory import TheoryCheck, expected_pattern

__all__ = [
    "validate", "RabaValidation", "format_report", "write_report",
    "run_study", "study_note", "TheoryCheck", "expected_pattern",
    "StabilityRow", "format_table", "reference_eigenvalues", "CalculixError",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
