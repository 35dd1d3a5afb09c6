"""The crack study's PNG figures, each from the result cache when drawn before."""
from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["crack_plots", "pod_modes"]


def crack_plots(scene, result, study, folder: Path) -> list[Path]:
    """The study's PNG figures (each from the result cache when drawn before)."""
    from hubvib.detection import plots as figures
    from hubvib.detection.crack_detection import cached_plot

    name = scene.name
    plots = [cached_plot(folder / "frequency_vs_depth.png", figures.relative_shift_figure,
                         name, result.depths, result.omega, result.kind)]
    if study is not None:
        deepest = float(result.depths[-1])
        plots += [
            cached_plot(folder / "shift_vs_depth.png", figures.shift_threshold_figure,
                        name, study.pod),
            cached_plot(folder / "detectability_map.png", figures.map_figure, name,
                        study.map, deepest, float(result.depths[1])),
            cached_plot(folder / "pod.png", figures.pod_figure, name, study.pod,
                        pod_modes(study)),
            cached_plot(folder / "carrier_position.png", figures.carrier_figure, name,
                        study.carrier, result.kind)]
    if result.elastic_map is not None:
        from hubvib.reports.elastic_map_sections import map_figure

        plots.append(cached_plot(folder / "elastic_map.png", map_figure, name,
                                 result.elastic_map))
    return plots


def pod_modes(study) -> list[int]:
    """Modes drawn in the POD plot: the watched ones and any other reaching the required
    POD, at most four (with the three family curves, the threshold lines: at most eight
    curves)."""
    pod = study.pod
    reaching = np.flatnonzero((pod.pod >= pod.detection_probability).any(axis=0))
    modes = list(study.watched_modes())
    return (modes + [int(i) for i in reaching if i not in modes])[:4]


