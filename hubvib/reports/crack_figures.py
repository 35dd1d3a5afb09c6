"""The crack study's PNG figures, each from the result cache when drawn before, and the
pictures of the elastic ring's watched coupled modes (from the render cache)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["both_models_arguments", "crack_plots", "elastic_mode_label", "pod_modes"]

#: the rigid ring's modes drawn beside the elastic ring's when no detection study watched
#: any (the modes that move most)
RIGID_SHOWN = 4


def crack_plots(scene, result, study, folder: Path) -> list[Path]:
    """The study's PNG figures (each from the result cache when drawn before); with the
    elastic ring, its figures and (``scene.renders``) its watched modes' pictures.

    The elastic figures: the watched modes open (half a pitch away), record-averaged
    (the loaded crack over the pitch) and closed (intact) against depth
    (``elastic_states.png``) and the crack's open length over the pitch per depth
    (``crack_state.png``), from ``result.elastic.detail``."""
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
    if result.elastic is not None:
        plots += _elastic_plots(scene, result, study, folder)
    if result.elastic_map is not None:
        from hubvib.reports.elastic_map_sections import map_figure

        plots.append(cached_plot(folder / "elastic_map.png", map_figure, name,
                                 result.elastic_map))
    return plots


def elastic_mode_label(elastic, i: int) -> str:
    """A watched elastic mode in a legend: its one identity (model, nodal diameters, class,
    intact frequency)."""
    return elastic.labels[i]


def both_models_arguments(name: str, result, study) -> tuple:
    """The arguments of ``render.elastic_figures.both_models_figure``: the rigid ring's
    watched modes (record-averaged change of the detection study; without one the
    instantaneous change of the modes that move most) and the elastic ring's, each with
    the words for what its change is (the elastic ring's: a record's under the load cycle
    when its tracks were computed, else the crack held open)."""
    from hubvib.detection.mode_names import mode_names, rigid_curve_label
    from hubvib.render.elastic_figures import ELASTIC_OPEN, ELASTIC_RECORD, RIGID_RECORD

    if study is not None:
        pod = study.pod
        rigid = [int(i) for i in study.watched_modes()]
        f0 = pod.nominal.frequency_hz[0]
        names = mode_names(f0)
        rigid_change = pod.nominal.shift_hz[:, rigid]
        rigid_depths = np.asarray(pod.depths, dtype=float)
        rigid_labels = [rigid_curve_label(names[i], f0[i], pod.kind[i]) for i in rigid]
        rigid_statistic = RIGID_RECORD
    else:
        hz = np.asarray(result.omega, dtype=float) / (2 * np.pi)
        change = hz - hz[0]
        rigid = [int(i) for i in np.argsort(-np.abs(change[-1]), kind="stable")[:RIGID_SHOWN]]
        names = mode_names(hz[0])
        rigid_change = change[:, rigid]
        rigid_depths = np.asarray(result.depths, dtype=float)
        rigid_labels = [rigid_curve_label(names[i], hz[0, i], result.kind[i])
                        + " (instantaneous)" for i in rigid]
        rigid_statistic = "instantaneous change, planet 1 on the cracked tooth"
    elastic = result.elastic
    watched = list(elastic.watched)
    detail = getattr(elastic, "detail", None)
    loaded = (detail is not None and detail.open_hz is not None
              and any(t is not None for t in detail.tracks))
    return (name, rigid_depths, rigid_change, rigid_labels,
            np.asarray(elastic.depths, dtype=float), elastic.shift_hz[:, watched],
            [elastic_mode_label(elastic, i) for i in watched],
            ELASTIC_RECORD if loaded else ELASTIC_OPEN, rigid_statistic)


def _elastic_plots(scene, result, study, folder: Path) -> list[Path]:
    from hubvib.detection.crack_detection import cached_plot
    from hubvib.render import elastic_figures as figures

    name, elastic = scene.name, result.elastic
    watched = list(elastic.watched)
    plots = [cached_plot(folder / "frequency_both_models.png", figures.both_models_figure,
                         *both_models_arguments(name, result, study))]
    detail = elastic.detail
    reference = elastic.frequency_hz if detail.open_hz is None else detail.open_hz
    if watched:
        # the record's change drawn from the reference intact frequency: the three lines
        # start together and differ by what the load cycle does to the change
        averaged = (None if detail.open_hz is None else
                    reference[0] + elastic.frequency_hz - elastic.frequency_hz[0])
        plots.append(cached_plot(
            folder / "elastic_states.png", figures.crack_states_figure, name,
            np.asarray(elastic.depths, dtype=float), reference[0][watched],
            reference[:, watched], [elastic_mode_label(elastic, i) for i in watched],
            None if averaged is None else np.asarray(averaged)[:, watched]))
    states = detail.crack_states if detail.tracks else None
    if states is not None:
        shown = [(d, s) for d, s in zip(elastic.depths, states) if s is not None]
        if shown:
            plots.append(cached_plot(
                folder / "crack_state.png", figures.open_length_figure, name,
                np.array([d for d, _ in shown]), [s for _, s in shown]))
    if scene.renders and watched:
        from hubvib.render.schedule import render_elastic_modes

        plots += render_elastic_modes(scene.crack.reducer, scene.elastic, watched,
                                      reference[0][watched], detail.k_rest, folder,
                                      scene.crack.tooth)
    return plots


def pod_modes(study) -> list[int]:
    """Modes drawn in the POD plot: the watched ones and any other reaching the required
    POD, at most four (with the three family curves, the threshold lines: at most eight
    curves)."""
    pod = study.pod
    reaching = np.flatnonzero((pod.pod >= pod.detection_probability).any(axis=0))
    modes = list(study.watched_modes())
    return (modes + [int(i) for i in reaching if i not in modes])[:4]
