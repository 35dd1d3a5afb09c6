"""The crack-sensitivity study: ring crack depth -> FE c_ru, c_r, c_rp -> lumped spectrum (SI).

The ring's support enters as the scene's ``apply`` says (``series``: the
mounting in series with the FE ring body, :mod:`hubvib.detection.series`).  The
spectrum is the one at the instant planet 1 meshes with the cracked tooth: its
ring mesh gets the FE ratio of c_rp over that engagement (the other planets keep
the preset c_rp), so the crack breaks the cyclic symmetry and splits the
repeated frequencies.  The detection part (POD from physics, the map against
the mounting stiffness, the carrier position) is :mod:`hubvib.detection`; the tables,
figures and report :mod:`hubvib.reports`, the renders' scheduling
:mod:`hubvib.render.schedule`.
"""
from __future__ import annotations

import time
from contextlib import ExitStack
from pathlib import Path

import numpy as np

from hubvib.cases.results import typed_case
from hubvib.cases.runner import crack_cases
from hubvib.cases.sweep import CrackSweep
from hubvib.detection.mode_names import tracked, tracked_order
from hubvib.detection.model import CrackModel
from hubvib.lumped import natural_modes
from hubvib.render.html import write_html_reports
from hubvib.render.schedule import begin_renders
from hubvib.reports.crack_files import write_crack_study
from hubvib.reports.crack_summary import crack_lines
from hubvib.runtime.process_pool import worker_pool
from hubvib.runtime.progress import stage, working
from hubvib.runtime.stage_seconds import timed
from hubvib.studies.crack_result import CrackStudyResult
from hubvib.studies.crack_table import crack_model, parse_crack_table, refuse_sweep_keys
from hubvib.studies.elastic_stage import (begin_elastic, elastic_load_sensitivity,
                                          elastic_map_of, elastic_pad_variant,
                                          finish_elastic)
from hubvib.studies.kind_registry import Scene, Study

__all__ = ["CRACK_STUDY", "CrackStudyResult", "crack_study_from_fe", "run_crack_study"]


def run_crack_study(scene: Scene, progress: bool = True, detection: bool = True,
                    workers: int = 2, pool=None, after_fe=None,
                    on_spectra=None) -> CrackStudyResult:
    """FE cases (cached; in ``pool``, a ``worker_pool``, when given), lumped spectra per
    depth, and the detection study; ``after_fe()`` is called when the FE cases are queued
    in the pool (if they are) and again when they are done, ``on_spectra`` as in
    ``crack_study_from_fe``."""
    with timed("fe"):
        fe, computed = crack_cases(scene.crack, progress,
                                   scene.execution, pool, after_fe)
    if after_fe is not None:
        after_fe()
    return crack_study_from_fe(scene, fe, computed, detection=detection, workers=workers,
                               on_spectra=on_spectra)


def crack_study_from_fe(scene: Scene, fe: list, computed: int = 0,
                        detection: bool = True, timing=None,
                        workers: int = 1, on_spectra=None,
                        half_length: float | None = None) -> CrackStudyResult:
    """The lumped and detection stages from the FE cases (``cases.results.PlaneCase``, or
    their dict form read once with ``typed_case``).  ``half_length`` [m]: the solid
    study's crack these cases stand for (``None``: cracks through the face width).

    ``timing`` (a ``detection.carrier.MeshTiming``) defaults to the scene's design at
    the ``[detection]`` carrier speed; ``on_spectra(spectra)`` is called with the lumped
    spectra before the detection stage.
    """
    fe = [typed_case(case) for case in fe]
    with timed("lumped"):
        model = CrackModel.from_fe(scene.params, scene.crack, fe, scene.method,
                                   c_rp_given=scene.c_rp_given)
        c_ru, c_r = model.c_ru, model.c_r
        c_rp_factor = np.asarray(model.c_rp_factor())
        spectra = [natural_modes(model.parameters(k), scene.method) for k in range(len(fe))]
        omega = tracked(np.array([s.omega for s in spectra]), tracked_order(spectra))
    if on_spectra is not None:
        on_spectra(spectra)
    with timed("detection"):
        study, comparison = _detection(scene, model, detection, timing, workers)
    return CrackStudyResult(scene, fe, c_ru, c_r, c_rp_factor, spectra, omega, computed,
                            model=model, detection=study, c_rp_comparison=comparison,
                            half_length=half_length)


def _detection(scene: Scene, model: CrackModel, detection: bool, timing, workers: int):
    """The detection study (if ``detection``) and the comparison of the c_rp methods (where
    they differ), each from its result cache."""
    study = comparison = None
    if detection or model.c_rp_differs:
        from hubvib.detection.carrier import mesh_timing
        from hubvib.detection.options import detection_options
        from hubvib.detection.crack_detection import cached_compare_methods, cached_detection_study

        options = detection_options(scene)
        timing = timing or mesh_timing(scene.crack.reducer, options.carrier_speed)
        if detection:
            study = cached_detection_study(model, options, timing, workers=workers)
        if model.c_rp_differs:
            comparison = cached_compare_methods(model, timing, options.record_length,
                                                options if detection else None,
                                                workers=workers)
    return study, comparison


def _run(scene: Scene, staged: Path) -> CrackStudyResult:
    """FE cases, lumped and detection stages, files.  With the local engine and more than
    one worker, one pool serves the FE cases and then the renders (the FE ring's needs only
    the scene, the modes' the intact spectrum): they run on its warm workers beside the
    detection stage and the plots here."""
    execution = scene.execution
    with_signal = scene.given("signal") is not None
    workers = execution.workers or scene.crack.workers
    with ExitStack() as beside:
        pool = (beside.enter_context(worker_pool(workers))
                if execution.engine == "local" and workers > 1 else None)
        begun, elastic = {}, {}

        def after_fe():
            begin_renders(scene, staged, pool, begun)
            # the elastic cases queue behind the FE cases and the FE ring's render; this
            # process, idle until the FE cases are done, computes those no worker starts
            if not elastic:
                elastic["cases"] = begin_elastic(scene, pool)

        def on_spectra(spectra):
            begin_renders(scene, staged, pool, begun, spectra[0])

        started = time.perf_counter()
        with working("FE stage and lumped spectra"):
            result = run_crack_study(scene, pool=pool, after_fe=after_fe,
                                     on_spectra=on_spectra)
        elastic_cases = elastic["cases"]
        stage(f"FE stage ({result.computed} of {len(result.fe)} cases computed) and lumped "
              "spectra", started)
        if elastic_cases is not None:
            started = time.perf_counter()
            with working("elastic ring"), timed("elastic"):
                result.elastic, result.elastic_validity, cases = finish_elastic(
                    scene, elastic_cases, pool=pool)
                result.mode_map = _mode_map(result, cases[0])
                result.load_sensitivity = elastic_load_sensitivity(scene, result.elastic,
                                                                   cases)
                result.pad_variant, result.pad_variant_reason = elastic_pad_variant(
                    scene, result.elastic)
                result.elastic_map = elastic_map_of(scene, result.elastic)
            stage(f"elastic ring ({len(result.elastic.depths)} depths)", started)
        started = time.perf_counter()
        if with_signal:  # the vibration signature beside the frequency study
            from hubvib.signal.report import write_signal_study
            from hubvib.signal.signature_study import run_signal_study

            with working("signals"):
                study = run_signal_study(scene)
            stage(f"signals of {len(study.depths)} crack depth(s)", started)
            with working("signal tables and plots"):
                signal_files = write_signal_study(study, staged / "signal",
                                                  plots=scene.plots)["files"]
            started = time.perf_counter()
        with working("tables, plots, renders and report"), timed("write"):
            write_crack_study(result, staged, begun, signal=with_signal)
    with timed("write"):
        if with_signal:
            result.files += [staged / "signal" / f for f in signal_files]
        pages = write_html_reports(staged, {staged / "report.md": result.report})
        result.files += [p for p in pages if p not in result.files]
    stage("tables, plots, renders and report", started)
    return result


def _mode_map(result: CrackStudyResult, intact) -> tuple:
    """Each elastic-ring mode's rigid-ring counterpart by shape (``detection.mode_map``)."""
    from hubvib.detection.mode_map import mode_map

    return mode_map(result.spectra[0], result.labels, intact.away.modes,
                    result.elastic.labels)


def _summary(scene: Scene, result: CrackStudyResult, folder: Path, files: list) -> dict:
    return {"scene": scene.name, "folder": str(folder), "files": [str(f) for f in files],
            "fe_cases_computed": result.computed, "modes": result.mode_rows()}



def parse_plane(data: dict, design, params) -> CrackSweep:
    """The plane crack study's ``[crack]`` table (and no lumped-sweep keys)."""
    sweep = parse_crack_table(data["crack"], design)
    refuse_sweep_keys(data)
    return sweep


#: the plane crack study: a scene with [crack] (model = "plane", the default)
CRACK_STUDY = Study("crack", _run, _summary, crack_lines, parse_plane,
                    tables=frozenset({"crack"}),
                    selects=lambda data: crack_model(data) != "solid",
                    selection='[crack] with model = "plane"', fe=True, renders=True)
