"""The crack study's folder: tables, figures, renders and ``report.md``, each written once."""
from __future__ import annotations

from pathlib import Path

from hubvib.foundation.output import write_text
from hubvib.render.schedule import study_renders
from hubvib.reports.crack_figures import crack_plots
from hubvib.reports.crack_report import crack_report
from hubvib.reports.crack_tables import write_crack_tables
from hubvib.runtime.stage_seconds import timed

__all__ = ["write_crack_study"]


def write_crack_study(result, folder: Path, begun: dict | None = None,
                      signal: bool = False):
    """Tables (CSV, JSON), plots, renders and ``report.md`` of ``result`` (a
    ``studies.crack_study.CrackStudyResult``, returned with its ``files`` and ``report``,
    the text) in ``folder``;
    ``begun``: the renders begun in workers (``render.schedule.begin_renders``);
    ``signal``: the report links the signal study's (in ``folder / "signal"``)."""
    begun = begun or {}
    folder = Path(folder)
    scene = result.scene
    files = write_crack_tables(result, folder)
    plots = []
    if scene.plots:
        with timed("plots"):
            plots = crack_plots(scene, result, result.detection, folder)
    renders, fe_renders = [], []
    if scene.renders:
        with timed("render"):
            renders, fe_renders = study_renders(scene, result.spectra[0], folder, begun)
    files += plots + renders + fe_renders

    def pictures(paths):
        return [p.relative_to(folder).as_posix() for p in paths if p.suffix == ".png"]

    result.report = crack_report(result, [p.name for p in plots], pictures(renders),
                                 pictures(fe_renders), signal)
    files.append(write_text(folder / "report.md", result.report))
    result.files = files
    return result
