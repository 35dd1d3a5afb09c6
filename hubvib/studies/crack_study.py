"""The crack-sensitivity study: ring crack depth -> FE c_ru, c_r, c_rp -> lumped spectrum (SI).

The ring's support enters as the scene's ``apply`` says (``series``: the
mounting in series with the FE ring body, :mod:`hubvib.detection.series`).  The
spectrum is the one at the instant planet 1 meshes with the cracked tooth: its
ring mesh gets the FE ratio of c_rp over that engagement (the other planets keep
the preset c_rp), so the crack breaks the cyclic symmetry and splits the
repeated frequencies.  The detection part (POD from physics, the map against
the mounting stiffness, the carrier position) is :mod:`hubvib.detection`.
"""
from __future__ import annotations

import datetime
import math
import time
from concurrent.futures import Future
from contextlib import ExitStack
from dataclasses import asdict, dataclass, field
from importlib import metadata
from pathlib import Path

import numpy as np

from hubvib.reducer.stages import ring_gear
from hubvib.detection import report as sections
from hubvib.detection.mesh_stiffness import family_depths, iso_c_rp, mesh_stiffness_section
from hubvib.detection.mode_names import mode_names, tracked, tracked_order
from hubvib.detection.model import CrackModel
from hubvib.detection.numbers import depth_mm, percent, sensitivity, shift_hz
from hubvib.detection.options import DetectionOptions
from hubvib.foundation.output import write_csv, write_json, write_text
from hubvib.lumped import Spectrum, frequency_sensitivity, natural_modes
from hubvib.meshing.levels import scaled_options
from hubvib.render.cache import array_digest, cached_render, is_cached
from hubvib.render.captions import figure_lines
from hubvib.render.html import write_html_reports
from hubvib.render.fe import render_fe, ring_fields
from hubvib.render.modes import render_modes
from hubvib.runtime.engines import EngineError, Execution, run_cases, submit
from hubvib.runtime.process_pool import worker_pool
from hubvib.runtime.progress import stage, working
from hubvib.runtime.stage_seconds import timed
from hubvib.cases.results import PlaneCase, typed_case
from hubvib.cases.runner import crack_cases
from hubvib.cases.sweep import ACCURACY, CrackSweep, crack_of
from hubvib.studies.crack_table import crack_model, parse_crack_table, refuse_sweep_keys
from hubvib.studies.kind_registry import Scene, Study
from hubvib.studies.validation_status import lumped_model_status

#: a mode "follows" a stiffness when its relative sensitivity exceeds this
SENSITIVE = 0.01
#: the stiffnesses a ring crack changes (c_rp: all planets' ring meshes together)
STIFFNESSES = ("c_ru", "c_r", "c_rp")


@dataclass
class CrackStudyResult:
    """Per depth: the FE stiffnesses, the lumped parameters used and the tracked spectrum.

    ``omega[k, i]`` [rad/s] is mode i (numbered at depth 0) at ``depths[k]``;
    ``model`` is the crack as the lumped model sees it, ``detection`` the
    detection study (None when not run), ``c_rp_comparison`` the record shifts under
    the other c_rp method (``detection.mesh_stiffness``; None where the methods agree).
    """

    scene: Scene
    fe: list[PlaneCase]
    c_ru: np.ndarray
    c_r: np.ndarray
    c_rp_factor: np.ndarray
    spectra: list[Spectrum]
    omega: np.ndarray
    computed: int
    files: list[Path] = field(default_factory=list)
    model: CrackModel | None = None
    detection: object = None
    c_rp_comparison: object = None
    elastic: object = None  # hubvib.detection.elastic.ElasticDetection, when the scene asks
    half_length: float | None = None
    elastic_validity: object = None  # hubvib.elastic.validity.ValidityBand, with ``elastic``
    elastic_map: object = None  # hubvib.detection.elastic_map.ElasticMap, ``[elastic] map``

    @property
    def depths(self) -> np.ndarray:
        return np.array(self.scene.crack.depths)

    @property
    def kind(self) -> tuple[str, ...]:
        return self.spectra[0].kind

    @property
    def names(self) -> list[str]:
        """Per mode its name in every table and figure (split pairs named)."""
        return mode_names(self.omega[0])

    @property
    def percent(self) -> np.ndarray:
        return 100 * (self.omega / self.omega[0] - 1)

    def stiffness_rows(self) -> list[dict]:
        """Per depth the FE case (``PlaneCase``) beside the lumped values; the keys with units
        are the CSV / JSON boundary."""
        rows = []
        for case, cu, cr, fp in zip(self.fe, self.c_ru, self.c_r, self.c_rp_factor):
            f = case.estimate
            rows.append({
                "depth_mm": 1e3 * case.depth, "fe_c_ru_N_m": f.c_ru,
                "fe_c_ru_error_N_m": f.c_ru_error,
                "fe_c_ru_min_N_m": f.c_ru_min, "fe_c_ru_max_N_m": f.c_ru_max,
                "fe_c_r_N_m": f.c_r, "fe_c_r_error_N_m": f.c_r_error,
                "fe_c_rp_engaged_ratio": f.c_rp_engaged_ratio,
                "fe_c_rp_engaged_ratio_error": f.c_rp_engaged_ratio_error,
                "fe_c_rp_engaged_min_ratio": f.c_rp_engaged_min_ratio,
                "lumped_c_ru_N_m": float(cu), "lumped_c_r_N_m": float(cr),
                "lumped_c_rp_planet1_N_m": float(self.model.params.c_rp * fp),
                "fe_seconds": case.seconds_total,
                "fe_c_rp_engaged_intact_N_m": f.c_rp_engaged_intact,
                "lumped_c_rp_factor": float(fp),
                "lumped_c_rp_planet1_ratio_method_N_m": float(
                    self.model.params.c_rp * f.c_rp_engaged_ratio),
                "fe_c_rp_engaged_intact_window_N_m": f.c_rp_engaged_intact_window,
                "fe_c_ru_root_land_N_m": f.c_ru_root_land,
                "fe_c_r_root_land_N_m": f.c_r_root_land})
        return rows

    def frequency_rows(self) -> list[dict]:
        rows = []
        for k, depth in enumerate(self.depths):
            for i, kind in enumerate(self.kind):
                rows.append({"depth_mm": 1e3 * depth, "mode": i + 1,
                             "mode_name": self.names[i], "kind": kind,
                             "omega_rad_s": float(self.omega[k, i]),
                             "frequency_hz": float(self.omega[k, i] / (2 * math.pi)),
                             "shift_hz": float((self.omega[k, i] - self.omega[0, i]) / (2 * math.pi)),
                             "shift_percent": float(self.percent[k, i])})
        return rows

    def mode_rows(self) -> list[dict]:
        """Per mode: what it follows (c_ru, c_r, c_rp), its largest shift, the depth from
        which it detects the crack (Monte Carlo POD, ``detectable_depth_mm``) and, for
        comparison, the first depth shifting it by the flat ``[study]`` threshold."""
        params = self.model.params if self.model is not None else self.scene.params
        base = self.spectra[0]
        rel = {name: frequency_sensitivity(params, name, self.scene.method, base).relative
               for name in STIFFNESSES}
        pod = self.detection.pod if self.detection is not None else None
        detectable = pod.detectable_depth() if pod is not None else None
        rows = []
        for i, kind in enumerate(self.kind):
            hits = np.flatnonzero(np.abs(self.percent[:, i]) >= self.scene.threshold_percent)
            follows = [n for n in STIFFNESSES if abs(rel[n][i]) > SENSITIVE] or ["none"]
            row = {"mode": i + 1, "mode_name": self.names[i], "kind": kind,
                   "frequency_intact_hz": float(self.omega[0, i] / (2 * math.pi)),
                   "shift_at_deepest_hz": float((self.omega[-1, i] - self.omega[0, i])
                                                / (2 * math.pi)),
                   "shift_at_deepest_percent": float(self.percent[-1, i]),
                   **{f"sensitivity_{n}": float(rel[n][i]) for n in STIFFNESSES},
                   "follows": "+".join(follows),
                   "smallest_detectable_depth_mm":
                       float(1e3 * self.depths[hits[0]]) if len(hits) else None}
            if pod is not None:
                row |= {"record_shift_at_deepest_hz": float(pod.nominal.shift_hz[-1, i]),
                        "sigma_hz": float(pod.sigma_hz[i]),
                        "signal_in": str(pod.nominal.carried_by[-1, i]),
                        "pod_at_deepest": float(pod.pod[-1, i]),
                        "detectable_depth_mm": (None if math.isnan(detectable[i])
                                                else 1e3 * float(detectable[i]))}
            rows.append(row)
        return rows


def run_crack_study(scene: Scene, progress: bool = True, detection: bool = True,
                    workers: int = 2, pool=None, after_fe=None,
                    on_spectra=None) -> CrackStudyResult:
    """FE cases (cached; in ``pool``, a ``worker_pool``, when given), lumped spectra per
    depth, and the detection study; ``after_fe()`` is called when the FE cases are queued
    in the pool (if they are) and again when they are done, ``on_spectra`` as in
    ``crack_study_from_fe``."""
    with timed("fe"):
        fe, computed = crack_cases(scene.crack, progress,
                                   scene.tables.get("execution", Execution()), pool, after_fe)
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


def write_crack_study(result: CrackStudyResult, folder: Path,
                      begun: dict | None = None) -> CrackStudyResult:
    """Tables (CSV, JSON), plots, renders and ``report.md`` in ``folder``; ``begun``: the
    renders begun in workers (``"modes"``, ``"fe"``: each with ``result()``, the files)."""
    begun = begun or {}
    folder = Path(folder)
    scene = result.scene
    study = result.detection
    files = [write_csv(folder / "stiffness_vs_depth.csv", result.stiffness_rows()),
             write_csv(folder / "frequency_vs_depth.csv", result.frequency_rows()),
             write_csv(folder / "modes.csv", result.mode_rows())]
    if study is not None:
        files += [write_csv(folder / "pod.csv", study.pod.rows()),
                  write_csv(folder / "pod_family.csv", study.pod.family_rows()),
                  write_csv(folder / "detectability_map.csv", study.map.rows())]
    files.append(write_json(folder / "results.json", json_safe({
        "scene": scene.name, **provenance(), "parameters": result.model.params.to_dict(),
        "crack": {k: v for k, v in asdict(scene.crack).items() if k != "design"},
        "mounting": {"apply": result.model.apply, "c_ru_mount_N_m": result.model.c_ru_mount,
                     "c_r_mount_N_m": result.model.c_r_mount},
        "detection": None if study is None else {
            "options": study.options.to_dict(),
            # one number as before: the highest alarm level over the watched modes [Hz]
            "threshold_hz": float(study.pod.threshold_hz[study.pod.watched].max()),
            "threshold_hz_per_mode": [float(t) for t in study.pod.threshold_hz],
            "sigma_hz": [float(t) for t in study.pod.sigma_hz],
            "per_mode_false_alarm_rate": study.pod.per_mode_rate,
            "family_pod": {f"{T:g}": [float(p) for p in v]
                           for T, v in study.pod.family_pod.items()},
            "engaged_fraction": study.timing.engaged_fraction,
            "pass_seconds": study.timing.pass_seconds,
            "watched_modes": [int(i) + 1 for i in study.watched_modes()]},
        "stiffness": result.stiffness_rows(), "modes": result.mode_rows(),
        "frequencies": result.frequency_rows(),
        "mesh_stiffness": dict(result.model.mesh_stiffness(),
                               c_rp_iso6336_N_m=iso_c_rp(scene.crack.reducer),
                               c_rp_methods_differ=result.c_rp_comparison is not None),
        "c_rp_methods": (None if result.c_rp_comparison is None
                         else result.c_rp_comparison.rows()),
        "c_rp_other_method_family_pod": _other_family_pod(result.c_rp_comparison),
        "elastic_ring": None if result.elastic is None else dict(
            _elastic_json(result.elastic),
            validity=None if result.elastic_validity is None
            else _validity_record(result.elastic_validity)),
        "elastic_map": None if result.elastic_map is None else result.elastic_map.rows()})))
    if result.elastic is not None:
        files.append(write_csv(folder / "elastic_ring.csv", _elastic_csv(result.elastic)))
    plots = []
    if scene.plots:
        with timed("plots"):
            plots = _plots(scene, result, study, folder)
    renders, fe_renders = [], []
    if scene.renders:
        with timed("render"):
            renders = (_rendered(begun["modes"], "mode shapes") if "modes" in begun else
                       _render_modes(scene, result.spectra[0], folder / "renders"))
            # the FE render is of the plane ring; a solid study's crack is part-width
            fe_renders = ([] if scene.crack.model != "plane"
                          else _rendered(begun["fe"], "FE ring") if "fe" in begun
                          else _render_fe(scene, folder / "renders"))
    files += plots + renders + fe_renders

    def pictures(paths):
        return [p.relative_to(folder).as_posix() for p in paths if p.suffix == ".png"]

    files.append(write_text(folder / "report.md", crack_report(
        result, [p.name for p in plots], pictures(renders), pictures(fe_renders))))
    result.files = files
    return result


def _validity_record(band) -> dict:
    from hubvib.elastic.validity import validity_record

    return validity_record(band)


def _elastic_json(elastic) -> dict:
    """The elastic ring's answer for results.json."""
    return {"depths_mm": [1e3 * d for d in elastic.depths],
            "first_detectable_mm": {f"{t:g}": (None if elastic.first_detectable(t) is None
                                               else 1e3 * elastic.first_detectable(t))
                                    for t in elastic.pod},
            "family_pod": {f"{t:g}": [float(p) for p in v] for t, v in elastic.pod.items()},
            "family_pod_nominal": None if elastic.pod_nominal is None else {
                f"{t:g}": [float(p) for p in v] for t, v in elastic.pod_nominal.items()},
            "monte_carlo_samples": elastic.samples,
            "scatter": None if not elastic.scatter else dict(zip(
                ("masses", "stiffnesses", "mounting", "fe_change_error"), elastic.scatter)),
            "watched_modes": [i + 1 for i in elastic.watched],
            "k_rest_N_m": elastic.k_rest, "ring_dofs": elastic.ring_dofs,
            "foundation_N_m2": None if elastic.foundation is None else {
                "normal": elastic.foundation[0], "tangential": elastic.foundation[1]},
            "sensor_angle_deg": math.degrees(elastic.sensor_angle),
            "lowest_ring_mode": None if elastic.lowest_ring_mode is None else {
                "frequency_hz": elastic.lowest_ring_mode[0],
                "nodal_diameter": elastic.lowest_ring_mode[1]},
            "modes": elastic.rows()}


def _elastic_csv(elastic) -> list[dict]:
    """One row per depth and coupled mode of the elastic ring."""
    rows = []
    for k, depth in enumerate(elastic.depths):
        for i, f in enumerate(elastic.intact_hz):
            rows.append({"depth_mm": 1e3 * depth, "mode": i + 1, "class": elastic.kind[i],
                         "nodal_diameter": elastic.nodal_diameter[i],
                         "intact_hz": float(f), "open_hz": float(elastic.open_hz[k, i]),
                         "in_contact_hz": float(elastic.in_contact_hz[k, i]),
                         "in_contact_intact_hz": float(elastic.in_contact_hz[0, i]),
                         "bilinear_hz": float(elastic.bilinear_hz[k, i]),
                         "split_pair": bool(elastic.split_pair[k, i]),
                         "watched": i in elastic.watched,
                         "family_pod": float(elastic.pod[elastic.record_length][k]),
                         "family_pod_nominal": (
                             None if elastic.pod_nominal is None else
                             float(elastic.pod_nominal[elastic.record_length][k]))})
    return rows


def _plots(scene: Scene, result: CrackStudyResult, study, folder: Path) -> list[Path]:
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
                        _pod_modes(study)),
            cached_plot(folder / "carrier_position.png", figures.carrier_figure, name,
                        study.carrier, result.kind)]
    if result.elastic_map is not None:
        from hubvib.detection.elastic_map_report import map_figure

        plots.append(cached_plot(folder / "elastic_map.png", map_figure, name,
                                 result.elastic_map))
    return plots


def _other_family_pod(comparison) -> dict | None:
    """The watched family's POD per record length [s] and depth under the other c_rp
    method (results.json), None where the methods agree or detection did not run."""
    if comparison is None or comparison.other_pod is None:
        return None
    pod = comparison.other_pod
    return {"c_rp_method": comparison.other,
            "family_pod": {f"{T:g}": [float(p) for p in v] for T, v in pod.family_pod.items()},
            "family_detectable_depth_m": {
                f"{T:g}": (None if math.isnan(d) else d)
                for T, d in family_depths(pod).items()}}


def _image(name: str, plots: list[str]) -> list[str]:
    """Markdown lines showing ``name`` when it was written."""
    return figure_lines(name) if name in plots else []


def _pod_modes(study) -> list[int]:
    """Modes drawn in the POD plot: the watched ones and any other reaching the required
    POD, at most four (with the three family curves, the threshold lines: at most eight
    curves)."""
    pod = study.pod
    reaching = np.flatnonzero((pod.pod >= pod.detection_probability).any(axis=0))
    modes = list(study.watched_modes())
    return (modes + [int(i) for i in reaching if i not in modes])[:4]


def json_safe(value):
    """JSON-safe: NaN and infinity become None (standard JSON)."""
    if isinstance(value, dict):
        return {k: json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def provenance() -> dict:
    """hubvib version and the date of the run (UTC)."""
    try:
        version = metadata.version("hubvib")
    except metadata.PackageNotFoundError:
        from hubvib import __version__ as version
    return {"hubvib_version": version,
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")}


def rendered_depth(sweep) -> float:
    """The deepest crack of the sweep that still has a tip (not through the rim) [m]."""
    ring = ring_gear(sweep.reducer)
    open_ended = [d for d in sweep.depths if d > 0 and not crack_of(sweep, d).is_through(ring)]
    return max(open_ended, default=max(sweep.depths))


#: the entry modules of the two renders (their cache entries are keyed on the source of
#: every hubvib module these import: the FE ring's includes the FE stage it solves)
MODES_SOURCE = (render_modes.__module__,)
FE_SOURCE = (render_fe.__module__,)


def _render_modes(scene: Scene, spectrum, folder: Path) -> list[Path]:
    """Every elastic lumped mode (``render.render_modes``), from the render cache when the
    same spectrum was rendered before."""
    return render_mode_shapes(scene.params, spectrum, scene.gif, scene.vtm, folder)


def _mode_render_inputs(params, spectrum, gif: bool, vtm: bool) -> dict:
    """The render cache's inputs of the lumped mode pictures."""
    return {"params": params.to_dict(), "omega": array_digest(spectrum.omega),
            "shapes": array_digest(spectrum.shapes), "kind": list(spectrum.kind),
            "gif": gif, "vtm": vtm}


def render_mode_shapes(params, spectrum, gif: bool, vtm: bool, folder: Path) -> list[Path]:
    """``_render_modes`` from picklable arguments (it may run in a worker)."""
    def render(target):
        return render_modes(params, spectrum, target, gif=gif, vtm=vtm)

    return cached_render("modes", _mode_render_inputs(params, spectrum, gif, vtm), folder,
                         render, MODES_SOURCE)


def _render_fe(scene: Scene, folder: Path) -> list[Path]:
    """The FE ring at the rendered depth (``fe_render``), from the render cache when the
    same design, crack and mesh were rendered by this FE stage before."""
    return render_fe_ring(scene.crack, scene.vtm, folder)


def _fe_render_case(sweep: CrackSweep, vtm: bool) -> tuple:
    """The crack and mesh options the FE ring is rendered with, and the render cache's
    inputs (everything that decides the pictures)."""
    depth = rendered_depth(sweep)
    crack = crack_of(sweep, depth) if depth > 0 else None
    options = scaled_options(ACCURACY[sweep.accuracy])
    inputs = {"design": sweep.reducer.fingerprint(),
              "crack": None if crack is None else asdict(crack), "options": asdict(options),
              "vtu": vtm}
    return crack, options, inputs


def render_fe_ring(sweep: CrackSweep, vtm: bool, folder: Path) -> list[Path]:
    """``_render_fe`` from the sweep alone (picklable arguments: it may run in a worker,
    ``fe_render_beside``)."""
    crack, options, inputs = _fe_render_case(sweep, vtm)

    def render(target):
        return render_fe(ring_fields(sweep.reducer, crack, options), target, vtu=vtm)

    return cached_render("fe-ring", inputs, folder, render, FE_SOURCE)


def _rendered(future, what: str) -> list[Path]:
    """The files of a render run on a pool worker; a worker that died or failed there is
    one line naming the render, as a failed FE case is (``EngineError``)."""
    try:
        return future.result()
    except Exception as exc:  # noqa: BLE001 - the worker's error, reported as the case's
        raise EngineError(f"the {what} render failed on a pool worker: "
                          f"{type(exc).__name__}: {exc}") from None


def begin_renders(scene: Scene, folder: Path, pool, begun: dict, spectrum=None) -> None:
    """Submit to ``pool`` (a ``worker_pool``) the renders that the render cache does not
    hold: the FE ring's (``spectrum`` None: it needs only the scene) or the lumped modes'
    (of ``spectrum``, the intact one), into ``folder / "renders"``; ``begun`` gets their
    futures (``write_crack_study``; one already begun is not submitted again).  Queued
    behind the FE cases, they run on the pool's workers as the cases leave them idle,
    beside this process's detection stage and plots."""
    kind = "fe" if spectrum is None else "modes"
    if not scene.renders or pool is None or kind in begun:
        return
    target = Path(folder) / "renders"
    if spectrum is not None:
        inputs = _mode_render_inputs(scene.params, spectrum, scene.gif, scene.vtm)
        if not is_cached("modes", inputs, MODES_SOURCE):
            begun["modes"] = submit(pool, render_mode_shapes, scene.params, spectrum,
                                    scene.gif, scene.vtm, target)
    elif scene.crack.model == "plane" and not is_cached(
            "fe-ring", _fe_render_case(scene.crack, scene.vtm)[2], FE_SOURCE):
        begun["fe"] = submit(pool, render_fe_ring, scene.crack, scene.vtm, target)


def crack_report(result: CrackStudyResult, plots: list[str], renders: list[str],
                 fe_renders: list[str] = ()) -> str:
    scene, sweep, model, study = result.scene, result.scene.crack, result.model, result.detection
    intact = result.fe[0].estimate
    info = provenance()
    lines = [f"# {scene.name}: ring-crack sensitivity study", "",
             f"hubvib {info['hubvib_version']}, {info['date']}. Ring crack at tooth "
             f"{sweep.tooth} ({sweep.start}, "
             + ("along the predicted LEFM path of `hubvib crack-path`), "
                if sweep.path == "predicted" else
                f"{math.degrees(sweep.angle):g} deg from radial), ")
             + f"depths {', '.join(f'{1e3 * d:.3g}' for d in sweep.depths)} mm"
             + ("." if sweep.model == "plane" else
                f" at the deepest point of a semi-elliptic crack of half-length "
                f"{1e3 * result.half_length:g} mm in the solid ring."), ""]
    sources = {key: scene.lumped_source(key) for key in ("c_ru", "c_r")}
    if study is not None:
        lines += sections.short_answer(scene.name, model, study, sources)
    if result.elastic is not None:
        from hubvib.detection.elastic_report import side_by_side

        lines += ([] if study is not None else ["## Short answer", ""])
        lines += side_by_side(study, result.elastic)
    if study is not None:
        lines += ["## Detectability against the ring mounting", "",
                  "The mounting is swept log-spaced in series with the FE ring body (whatever "
                  "the scene's `apply`); each point is a Monte Carlo POD. Smallest detectable "
                  "depth over all modes (`detectability_map.csv` has every mode, with the "
                  "stiffness carrying its signal):", "", *sections.map_table(study.map), ""]
        lines += _image("detectability_map.png", plots)
        lines += sections.pod_section(study) + _image("pod.png", plots)
        lines += ["Files: `pod.csv` (every mode and depth: shift, its 5-95 % range over the "
                  "scatter, carrying stiffness, FE error, identification scatter, threshold, "
                  "POD with both baselines), `pod_family.csv` (the watched modes together, "
                  "per record length).", ""]
        lines += sections.carrier_section(study) + _image("carrier_position.png", plots)
    else:
        lines += [sections.mounting_sentence(model, sources), ""]
    if result.elastic is not None:
        from hubvib.detection.elastic_report import elastic_section

        lines += elastic_section(result.elastic, result.elastic_validity)
    if result.elastic_map is not None:
        from hubvib.detection.elastic_map_report import map_section

        lines += map_section(result.elastic_map) + _image("elastic_map.png", plots)
    watched = (list(study.watched_modes()) if study is not None
               else list(np.argsort(-np.abs(result.omega[-1] - result.omega[0]))[:4]))
    lines += mesh_stiffness_section(model, iso_c_rp(sweep.reducer), result.c_rp_comparison,
                                    watched, None if study is None else study.pod)
    lines += [
        "## Assumptions", "",
        f"- Design `{sweep.reducer.name}`: "
        + "; ".join(getattr(sweep.reducer, "notes", ()) or ("see hubvib.design",)) + ".",
        f"- Ring support: {sections.mounting_sentence(model, sources)}",
        f"- The FE ring body alone gives c_ru = {intact.c_ru:.4g} N/m and c_r = "
        f"{intact.c_r:.4g} N/m against the reducer's c_ru {scene.params.c_ru:.4g} N/m "
        f"({sources['c_ru']}) and c_r {scene.params.c_r:.4g} N/m ({sources['c_r']}). These "
        "are the work-conjugate rim parts: the work of each loaded tooth's forces on the "
        "rigid motion of its root lands (fem/ring_work.py). "
        "The lumped model puts the ring body in series with the tooth pair c_rp, whose ring "
        "tooth is measured relative to that same rigid motion, so each compliance is counted "
        "once. The whole work-conjugate c_ru would count the ring tooth twice, and the "
        "root-land reading is not work-conjugate to the flank loads: where the crack mouth "
        "cuts a root land it hides most of a shallow crack's effect. The root-land readings "
        "stay beside them (`fe_c_ru_root_land_N_m`, `fe_c_r_root_land_N_m`).",
        "- c_rp: FE tooth compliance of planet and ring tooth (crack moved to tooth 0) with "
        "Hertz contact added analytically and the load shared over the path of contact; the "
        "ratio cracked/intact is the mean while the cracked tooth is in contact (its minimum "
        "is in `fe_c_rp_engaged_min_ratio`), the intact mean over the mesh cycle is "
        "`fe_c_rp_engaged_intact_N_m` and over the cracked tooth's contact window "
        "`fe_c_rp_engaged_intact_window_N_m` (c_rp_FE, the ratio's denominator). The crack's "
        "extra compliance (1/ratio - 1)/c_rp_FE "
        f"enters planet 1's lumped c_rp by the method `{model.c_rp_method}` (see Ring-planet "
        "mesh stiffness). Only planet 1's ring mesh changes, so "
        "the crack splits the repeated (translational) frequencies."
        + ("" if sweep.model == "plane" else
           f" Solid study, semi-elliptic crack of half-length "
           f"{1e3 * result.half_length:g} mm: the ring body's c_ru and c_r are "
           "the solid ring's; c_rp is the plane ratio carried over by the slice method "
           "(see the study's top report)."), "",
        "## Validation status", "",
        "- FE c_ru: annulus against the exact k_theta (curved P2 to 1e-7), error of each "
        "value estimated against "
        + ("a mesh twice as coarse" if sweep.model == "plane" else
           "the solid level before the default (`hubvib.meshing.levels.SOLID_LEVELS`; the "
           "top report gives the error of each change)")
        + " (column `fe_c_ru_error_N_m`).",
        "- Series composition: tends to the FE values when the mounting stiffens and to the "
        "mounting alone when the body does (tests).",
        f"- Lumped model: {lumped_model_status()}; eigensolver checked against 50-digit "
        "arithmetic (`hubvib stability`); batched Monte Carlo solves agree with it to 1e-10 "
        "(tests).", "",
        f"FE cases: {len(result.fe)} ({result.computed} computed now, "
        f"{len(result.fe) - result.computed} from the cache).", "",
        "## FE stiffness against crack depth", "",
        "| depth [mm] | FE c_ru [N/m] | ± | FE c_r [N/m] | ± | FE c_rp ratio | ± "
        "| lumped c_ru | lumped c_r | lumped c_rp planet 1 |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in result.stiffness_rows():
        lines.append(f"| {r['depth_mm']:.3g} | {r['fe_c_ru_N_m']:.5e} | "
                     f"{r['fe_c_ru_error_N_m']:.1e} | {r['fe_c_r_N_m']:.5e} | "
                     f"{r['fe_c_r_error_N_m']:.1e} | {r['fe_c_rp_engaged_ratio']:.4f} | "
                     f"{r['fe_c_rp_engaged_ratio_error']:.1e} | {r['lumped_c_ru_N_m']:.7g} | "
                     f"{r['lumped_c_r_N_m']:.7g} | {r['lumped_c_rp_planet1_N_m']:.5g} |")
    lines += ["", "## Modes: sensitivity and detection", "",
              "Instantaneous shift: at the instant planet 1 meshes with the cracked tooth; "
              "record shift: the time-averaged shift a record sees (what the POD uses). "
              "Sensitivities are per relative change of the whole stiffness (c_rp: every "
              "planet's ring mesh); *follows*: a sensitivity above 0.01; *signal in*: the "
              "stiffness whose crack-induced change alone moves the mode most at the deepest "
              "crack, record-averaged (sensitivity times change; the same rule as in "
              "`detectability_map.csv`). Detectable from: this mode alone, Monte Carlo POD "
              "at the family-corrected rate.", "",
              "| mode | type | f intact [Hz] | instantaneous shift at deepest [Hz] | [%] "
              "| record shift at deepest [Hz] | (dω/ω)/(dc_ru/c_ru) "
              "| (dω/ω)/(dc_r/c_r) | (dω/ω)/(dc_rp/c_rp) | follows | signal in "
              "| detectable from [mm] |",
              "|---:|---|---:|---:|---:|---:|---:|---:|---:|---|---|---:|"]
    for r in result.mode_rows():
        depth = r.get("detectable_depth_mm")
        f0 = r["frequency_intact_hz"]
        lines.append(f"| {r['mode_name']} | {r['kind']} | {r['frequency_intact_hz']:.3f} | "
                     f"{shift_hz(r['shift_at_deepest_hz'], r['frequency_intact_hz'])} | "
                     f"{percent(r['shift_at_deepest_percent'])} | "
                     f"{shift_hz(r.get('record_shift_at_deepest_hz'), f0)} | "
                     f"{sensitivity(r['sensitivity_c_ru'])} | "
                     f"{sensitivity(r['sensitivity_c_r'])} | "
                     f"{sensitivity(r['sensitivity_c_rp'])} | {r['follows']} | "
                     f"{r.get('signal_in', '-')} | "
                     f"{'not detectable' if depth is None else depth_mm(depth / 1e3)} |")
    shown = {"detectability_map.png", "pod.png", "carrier_position.png"}
    rest = [n for n in plots if n not in shown]
    if rest:
        lines += ["", "## Plots", ""] + [x for n in rest for x in figure_lines(n)]
    if renders:
        lines += ["", "## Mode shapes (intact)", ""] + [x for n in renders
                                                          for x in figure_lines(n)]
    if fe_renders:
        shown, deepest = rendered_depth(sweep), max(sweep.depths)
        why = ("" if math.isclose(shown, deepest) else
               f" The deepest crack of the sweep ({1e3 * deepest:.3g} mm) cuts through the rim: "
               "it has no tip left to show, so the render shows the deepest crack that still "
               "has one.")
        lines += ["", f"## FE ring with the {1e3 * shown:.3g} mm crack", "",
                  f"Rendered depth: {1e3 * shown:.3g} mm.{why} Under the "
                  f"{sweep.reducer.n_planets} planet mesh forces of the design's "
                  f"{sweep.reducer.sun_torque:g} N m sun torque (planet 1 on the cracked "
                  "tooth), von Mises stress; then its lowest modes on the clamped supports "
                  "(plane stress, deformation magnified).", ""]
        lines += [x for n in fe_renders for x in figure_lines(n)]
    return "\n".join(lines) + "\n"


def _run(scene: Scene, staged: Path) -> CrackStudyResult:
    """FE cases, lumped and detection stages, files.  With the local engine and more than
    one worker, one pool serves the FE cases and then the renders (the FE ring's needs only
    the scene, the modes' the intact spectrum): they run on its warm workers beside the
    detection stage and the plots here."""
    execution = scene.tables.get("execution", Execution())
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
                result.elastic = finish_elastic(scene, elastic_cases)
                result.elastic_validity, result.elastic_map = elastic_band_and_map(
                    scene, result.elastic)
            stage(f"elastic ring ({len(result.elastic.depths)} depths)", started)
        started = time.perf_counter()
        if "signal" in scene.tables:  # the vibration signature beside the frequency study
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
            write_crack_study(result, staged, begun)
    with timed("write"):
        if "signal" in scene.tables:
            report = staged / "report.md"
            write_text(report, report.read_text(encoding="utf-8") + SIGNAL_SECTION)
            result.files += [staged / "signal" / f for f in signal_files]
        result.files += [p for p in write_html_reports(staged) if p not in result.files]
    stage("tables, plots, renders and report", started)
    return result


def _elastic_scene(scene: Scene):
    table = scene.tables.get("elastic")
    return table if table is not None and table.elastic and scene.crack.model == "plane" \
        else None


def begin_elastic(scene: Scene, pool):
    """The elastic ring's crack cases as futures, or their arguments to compute in this
    process (no pool); None when the scene runs the rigid ring only.

    With a pool every case is queued there, behind what is queued already, and this
    process takes back the cases no worker has started, the deepest first, and computes
    them here (as a worker would: one BLAS thread) until the workers reach the rest: while
    they run the FE cases ahead, it would only wait for them.  The validity band
    (``elastic_band_and_map``) goes first the same way, into the result cache, where the
    band's own call then finds it."""
    elastic = _elastic_scene(scene)
    if elastic is None:
        return None
    from hubvib.detection.elastic import cached_case, case_arguments
    from hubvib.elastic.validity import cached_validity_band

    sweep = scene.crack
    depths = elastic_depths(sweep)
    arguments = case_arguments(sweep.reducer, depths, lambda d: crack_of(sweep, d), elastic)
    if pool is None:
        return arguments
    work = [(cached_case, a, f"elastic ring at {1e3 * d:g} mm")
            for a, d in zip(arguments, depths)]
    work.append((cached_validity_band, _validity_band_arguments(scene),
                 "the rigid-ring model's validity band"))
    futures = [submit(pool, function, *a) for function, a, _ in work]
    for k in reversed(range(len(futures))):
        if not futures[k].cancel():  # a worker has it: the earlier ones are theirs too
            break
        futures[k] = _computed_here(*work[k])
    return futures[:len(arguments)]  # the band's result stays in the result cache


def _computed_here(function, arguments: tuple, label: str) -> Future:
    """``function(*arguments)`` run in this process as on a pool worker
    (``runtime.engines.run_cases`` with one worker), as a finished future (its failure as
    the future's ``EngineError``)."""
    done = Future()
    try:
        run_cases(lambda _: function(*arguments), [label],
                  lambda _, result: done.set_result(result), Execution(), 1)
    except EngineError as error:
        done.set_exception(error)
    return done


def finish_elastic(scene: Scene, begun):
    """The elastic ring's detection answer from the cases ``begin_elastic`` began."""
    from hubvib.detection.elastic import cached_case, elastic_detection
    from hubvib.detection.options import detection_options

    cases = [b.result() if hasattr(b, "result") else cached_case(*b) for b in begun]
    sweep = scene.crack
    return elastic_detection(sweep.reducer, elastic_depths(sweep),
                             lambda d: crack_of(sweep, d), _elastic_scene(scene),
                             detection_options(scene), cases)


def elastic_band_and_map(scene: Scene, elastic) -> tuple:
    """The rigid-ring model's computed validity band on the scene's mounting (planet 1 where
    the detection's statistic has it) and, when ``[elastic] map`` asks, the elastic ring's
    detectability against the foundation scale; both through the result cache."""
    from hubvib.elastic.validity import cached_validity_band

    es = _elastic_scene(scene)
    sweep = scene.crack
    band = cached_validity_band(*_validity_band_arguments(scene))
    if not es.map:
        return band, None
    from hubvib.detection.elastic import family_pod
    from hubvib.detection.elastic_map import elastic_map
    from hubvib.detection.options import detection_options

    emap = elastic_map(sweep.reducer, elastic_depths(sweep), lambda d: crack_of(sweep, d), es,
                       detection_options(scene), pod=family_pod, k_rest=elastic.k_rest)
    return band, emap


def _validity_band_arguments(scene: Scene) -> tuple:
    """The arguments of ``cached_validity_band`` for the scene: its design and elastic
    options, planet 1 away from the cracked tooth."""
    from hubvib.elastic.cases import carrier_positions

    sweep = scene.crack
    away = carrier_positions(sweep.reducer, crack_of(sweep, sweep.depths[-1]).tooth)[0]
    return sweep.reducer, _elastic_scene(scene).options, away


def elastic_depths(sweep) -> tuple:
    """The sweep's depths the elastic ring is solved at: all but a crack through the rim
    (it opens the ring; its modes no longer continue the intact ring's)."""
    ring = ring_gear(sweep.reducer)
    return tuple(d for d in sweep.depths if d == 0 or not crack_of(sweep, d).is_through(ring))


#: the report section that links the vibration signature (scenes with a [signal] table)
SIGNAL_SECTION = ("\n## Vibration signature\n\nThe signal a sensor on the ring records, its "
                  "order spectrum, spectrogram and condition indicators against crack depth: "
                  "[signal/report.md](signal/report.md).\n")


def _summary(scene: Scene, result: CrackStudyResult, folder: Path, files: list) -> dict:
    return {"scene": scene.name, "folder": str(folder), "files": [str(f) for f in files],
            "fe_cases_computed": result.computed, "modes": result.mode_rows()}


def _lines(scene: Scene, result: CrackStudyResult, folder: Path) -> list[str]:
    out = [f"scene {scene.name!r}: ring crack depths "
           f"{', '.join(f'{1e3 * d:.3g}' for d in result.depths)} mm "
           f"({result.computed} FE cases computed, {len(result.fe) - result.computed} cached)"]
    rows = result.mode_rows()
    physical = "detectable_depth_mm" in rows[0]
    if physical:
        pod = scene.tables.get("detection", DetectionOptions()).detection_probability
        last = f"detectable from (POD >= {pod:g}), via"
    else:
        last = f"smallest crack shifting >= {scene.threshold_percent:g} %"
    out.append(f"{'mode':>4} {'type':<13} {'f intact [Hz]':>13} {'inst. shift [%]':>15} "
               + (f"{'record shift [Hz]':>17} {'sigma [Hz]':>10} " if physical else "")
               + f"{'follows':>10}  {last}")
    for r in rows:
        depth = r["detectable_depth_mm"] if physical else r["smallest_detectable_depth_mm"]
        where = f" ({r['signal_in']})" if physical and depth is not None else ""
        record = (f"{r['record_shift_at_deepest_hz']:>+17.3g} {r['sigma_hz']:>10.3g} "
                  if physical else "")
        out.append(f"{r['mode']:>4} {r['kind']:<13} {r['frequency_intact_hz']:>13.3f} "
                   f"{percent(r['shift_at_deepest_percent']):>15} {record}{r['follows']:>10}  "
                   f"{'not detectable' if depth is None else f'{depth:.3g} mm'}{where}")
    out.append("inst. shift: at the deepest crack with planet 1 on the cracked tooth"
               + ("; record shift: the time-averaged shift a record sees there; sigma: "
                  "standard deviation of one identified frequency; detectable: on this mode "
                  "alone at the family-corrected false-alarm rate" if physical else "")
               + "; follows: relative sensitivity above 0.01")
    if physical and result.detection is not None:
        pod_result = result.detection.pod
        parts = [f"{T:g} s: " + ("none" if math.isnan(d) else f"from {1e3 * d:.3g} mm")
                 for T in sorted(pod_result.family_pod)
                 for d in [pod_result.family_detectable_depth(T)]]
        out.append(f"watched modes {', '.join(str(int(i) + 1) for i in pod_result.watched)} "
                   f"together (family-wise false-alarm rate {pod_result.false_alarm_rate:g}), "
                   f"crack detectable (POD >= {pod:g}) with records of " + "; ".join(parts))
    out.append(f"\nreport: {folder / 'report.md'} (in a browser: {folder / 'report.html'})")
    return out


def parse_plane(data: dict, design, params) -> CrackSweep:
    """The plane crack study's ``[crack]`` table (and no lumped-sweep keys)."""
    sweep = parse_crack_table(data["crack"], design)
    refuse_sweep_keys(data)
    return sweep


#: the plane crack study: a scene with [crack] (model = "plane", the default)
CRACK_STUDY = Study("crack", _run, _summary, _lines, parse_plane, tables=frozenset({"crack"}),
                    selects=lambda data: crack_model(data) != "solid",
                    selection='[crack] with model = "plane"', fe=True, renders=True)
