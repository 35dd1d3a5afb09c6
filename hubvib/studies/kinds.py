"""The study registry: a scene's ``kind`` -> the study that runs it (``Study``).  A new
study kind is its module (table parse, run, outputs, report, summary) and one entry here."""
from __future__ import annotations

from hubvib.studies.crack_growth import CRACK_GROWTH
from hubvib.studies.crack_study import CRACK_STUDY
from hubvib.studies.study import Study
from hubvib.studies.sweep import SWEEP

STUDIES: dict[str, Study] = {study.kind: study for study in (SWEEP, CRACK_STUDY, CRACK_GROWTH)}


def study_of(scene) -> Study:
    """The registered study of the scene's kind."""
    return STUDIES[scene.kind]
