"""The study reports apart from their computation: ``report.md`` assembled once from a
study's typed result (``crack_report.crack_report``), its tables (``crack_tables``:
``results.json`` and the CSV files, with ``provenance.provenance``), its figures
(``crack_figures``) and console lines (``crack_summary``), the report sections of the
detection study, the elastic ring and the mesh stiffness (``detection_sections``,
``elastic_sections``, ``elastic_map_sections``, ``mesh_stiffness_section``), and the
folder written once (``crack_files``).  SI inside; millimetres and hertz only in the
written text.  Every name below is imported on first use (PEP 562)."""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .crack_files import write_crack_study
    from .crack_summary import crack_lines
    from .crack_tables import write_crack_tables
    from .provenance import json_safe
    from .validation_status import lumped_model_status

__all__ = [
    "write_crack_study", "crack_lines", "write_crack_tables", "json_safe",
    "lumped_model_status",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
