"""The shipped study kinds, registered (``hubvib.studies.kind_registry.STUDIES``): the lumped sweep,
the plane crack study and the solid crack growth.  A new study kind is its module (tables,
parse, run, outputs, report, summary) and one ``register_study`` line here, or a call
wherever it is defined."""
from __future__ import annotations

from hubvib.studies.crack_growth import CRACK_GROWTH
from hubvib.studies.crack_study import CRACK_STUDY
from hubvib.studies.kind_registry import STUDIES, Study, register_study, study_of
from hubvib.studies.sweep import SWEEP

for _study in (SWEEP, CRACK_STUDY, CRACK_GROWTH):
    register_study(_study)

__all__ = ["STUDIES", "Study", "register_study", "study_of"]
