"""The 3D crack-growth study: semi-elliptic root cracks over depth and half-length (SI).

Each crack is a semi-elliptic surface crack at the critical fillet point of the
ring tooth, centred on the face width: depth ``a`` at its deepest point, mouth
``2 c`` long on the fillet.  The solid ring gives ``c_ru`` (mean over every
carrier position of one planet pitch) and ``c_r`` with their error estimates
(``fem.estimate.estimate_ring``).  The same factorisations give the cracked
tooth's compliance under a line load across the face width at the plane tooth
curve's flank radii (``fem.tooth_solid``); its ratio to the intact tooth's
scales the plane intact curve, and the pair and mesh-cycle machinery of the
plane study gives the c_rp ratio over the cracked tooth's engagement
(``fem.engaged_solid``): the ``c_rp`` of the rows (``SolidRow``).  For comparison the
slice method (the face width cut into independent slices in parallel, each
with the plane c_rp ratio at its local depth ``a(z)``; Z. Chen, Y. Shao,
Engineering Failure Analysis 18 (2011) 2149-2164) carries the plane cases of
the same depths over to the part-width crack (the rows' ``sliced``).  Slices
that do not hold each other up are softer than the solid tooth, so the slice
ratio overstates the crack's effect on c_rp.

Per half-length the lumped and detection stages and the report are those of the
plane study (``hubvib.studies.crack_study``), in a folder of their own.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from hubvib.reducer.stages import gear_body, material, ring_gear
from hubvib.design.presets import raba118
from hubvib.fem.engaged_solid import solid_engaged_mesh
from hubvib.detection.numbers import percent
from hubvib.fem.estimate import USABLE_QUALITY, CrackCaseEstimate, RingEstimate
from hubvib.foundation.errors import SceneError
from hubvib.foundation.output import save_figure, write_csv, write_json, write_text
from hubvib.render.captions import figure_lines
from hubvib.render.html import write_html_reports
from hubvib.runtime.progress import stage, working
from hubvib.reports.crack_files import write_crack_study
from hubvib.reports.provenance import json_safe, provenance
from hubvib.studies.crack_study import CrackStudyResult, crack_study_from_fe
from hubvib.meshing.levels import scaled_options
from hubvib.cases.results import PlaneCase, SolidCase
from hubvib.cases.runner import case_label, crack_cases
from hubvib.cases.sweep import ACCURACY, CrackSweep
from hubvib.studies.crack_table import crack_model, parse_crack_table, refuse_sweep_keys
from hubvib.studies.kind_registry import Scene, Study

#: slices of the face width in the slice method
SLICES = 512
#: what the tests measured about the poorly shaped cells of the Raba 118/76 ring
RABA_POOR_CELLS = (" On this ring, halving or doubling them moves c_ru itself by less than its "
                   "error estimate (test `test_poor_cells_do_not_move_c_ru`).")


def slice_ratio(depth: float, half_length: float, face_width: float, plane_depths,
                plane_ratios) -> float:
    """The part-width crack's c_rp ratio by the slice method [-].

    The mean over the face width ``face_width`` [m] of the plane ratio at the local
    depth ``depth * sqrt(1 - ((z - z_c) / half_length)^2)`` [m], linear between the
    ``plane_depths`` [m] (ascending from 0, where the ratio is 1), 1 outside the mouth.
    It is linear in the ratios: ``1 - slice_ratio(..., 1 - errors)`` carries plane
    errors over.
    """
    plane_depths = np.asarray(plane_depths, dtype=float)
    if plane_depths[0] != 0 or np.any(np.diff(plane_depths) <= 0):
        raise ValueError(f"plane_depths = {plane_depths.tolist()!r}: allowed ascending "
                         "values from 0 [m]")
    if not 0 <= depth <= plane_depths[-1]:
        raise ValueError(f"depth {depth!r} m outside the plane cases "
                         f"0..{plane_depths[-1]:g} m")
    if not 0 <= 2 * half_length <= face_width:
        raise ValueError(f"half_length {half_length!r} m, allowed 0..{face_width / 2:g} m")
    # slices at z - z_c = c sin(theta), equal steps in theta: the local depth a cos(theta)
    # has no square-root end point to spoil the midpoint rule
    # (dz = c cos(theta) d theta; the weights are normalised so a constant is exact)
    weight = np.cos(((np.arange(SLICES) + 0.5) / SLICES - 0.5) * math.pi)
    inside = np.interp(depth * weight, plane_depths, plane_ratios) @ weight / weight.sum()
    return float(1 - 2 * half_length / face_width * (1 - inside))


@dataclass(frozen=True)
class CrpRatios:
    """The cracked tooth pair's c_rp against the intact pair's [-]: the mean over the cracked
    tooth's engagement, the lowest over it, and the mean's error estimate."""

    mean: float
    min: float
    error: float


#: the intact tooth's ratios
INTACT_RATIOS = CrpRatios(1.0, 1.0, 0.0)


@dataclass(frozen=True)
class StiffnessChange:
    """The change of a ring body stiffness against the intact ring [-]: its value (fine
    level), its error (fine against coarse level) and how far it moves with the poorly
    shaped cells at half stiffness."""

    value: float
    error: float
    poor_cells: float


@dataclass(frozen=True)
class SolidRow:
    """One solid case with the c_rp the lumped stages use (``c_rp``: the 3D ratios or the
    slice method's), the slice method's (``sliced``), the intact tooth pair's engaged c_rp
    [N/m] of the plane study (mean, lowest, over the contact window) and the changes of c_ru
    and c_r against the intact ring."""

    case: SolidCase
    c_rp: CrpRatios
    sliced: CrpRatios
    c_rp_intact: float
    c_rp_intact_min: float
    c_rp_intact_window: float
    c_ru_change: StiffnessChange
    c_r_change: StiffnessChange

    def plane_case(self) -> PlaneCase:
        """The row read as a plane study's case: the solid ring's c_ru and c_r (their
        root-land readings too) with the c_rp carried over; the case's wall time."""
        e, seconds = self.case.estimate, float(self.case.seconds_total)
        estimate = CrackCaseEstimate(
            c_ru=float(e.c_ru), c_ru_error=float(e.c_ru_error), c_ru_min=float(e.c_ru_min),
            c_ru_max=float(e.c_ru_max), c_r=float(e.c_r), c_r_error=float(e.c_r_error),
            c_rp_engaged_ratio=float(self.c_rp.mean),
            c_rp_engaged_ratio_error=float(self.c_rp.error),
            c_rp_engaged_min_ratio=float(self.c_rp.min),
            c_rp_engaged_intact=float(self.c_rp_intact),
            c_rp_engaged_intact_min=float(self.c_rp_intact_min),
            c_rp_engaged_intact_window=float(self.c_rp_intact_window),
            dofs=e.dofs, solver=e.solver, seconds_mesh=float(e.seconds_mesh),
            seconds_fe=float(e.seconds_fe), seconds_total=seconds,
            c_ru_root_land=float(e.c_ru_root_land),
            c_ru_root_land_error=float(e.c_ru_root_land_error),
            c_r_root_land=float(e.c_r_root_land), c_r_root_land_error=float(e.c_r_root_land_error))
        return PlaneCase(estimate, float(self.case.depth), seconds)


def solid_c_rp(sweep, solid: list[SolidCase]) -> list[CrpRatios]:
    """The 3D c_rp ratios of the solid cases (``sweep.cases`` order, the intact first) [-]:
    on the fine level, the error the fine level's mean ratio against the coarse level's
    (``fem.engaged_solid``)."""
    design = sweep.reducer
    ring, planet, steel = ring_gear(design), gear_body(design, "planet"), material(design)
    options = scaled_options(ACCURACY[sweep.accuracy])
    intact = solid[0].estimate
    out = [INTACT_RATIOS]
    for case in solid[1:]:
        e = case.estimate
        fine, coarse = (solid_engaged_mesh(planet, ring, e.tooth_radii, getattr(e, name),
                                           getattr(intact, name), options, steel, sweep.tooth)
                        for name in ("tooth_compliance", "tooth_compliance_coarse"))
        out.append(CrpRatios(fine.mean_ratio, fine.min_ratio,
                             abs(fine.mean_ratio - coarse.mean_ratio)))
    return out


def _change(case: RingEstimate, intact: RingEstimate, name: str) -> StiffnessChange:
    """The change of ``name`` (``c_ru`` or ``c_r``) of ``case`` against ``intact`` [-]."""
    value = getattr(intact, name)
    fine = getattr(case, name) - value
    coarse = getattr(case, f"{name}_coarse") - getattr(intact, f"{name}_coarse")
    halved = getattr(case, f"{name}_poor_half") - getattr(intact, f"{name}_poor_half")
    return StiffnessChange(fine / value, abs(fine - coarse) / value, (halved - fine) / value)


def solid_rows(sweep, solid: list[SolidCase], plane: list[PlaneCase],
               three_d: list[CrpRatios] | None = None) -> list[SolidRow]:
    """The solid cases (``sweep.cases`` order) with the c_rp of the plane study's cases and
    the change of c_ru and c_r against the intact ring [-]: its error (fine against coarse
    level) and how far it moves with the poorly shaped cells at half stiffness.

    ``sliced`` is the slice method's c_rp; ``c_rp`` is ``three_d``'s (``solid_c_rp``), or
    the slice method's when ``three_d`` is None."""
    width = sweep.reducer.face_width
    depths = [case.depth for case in plane]
    ratios = [case.estimate.c_rp_engaged_ratio for case in plane]
    minima = [case.estimate.c_rp_engaged_min_ratio for case in plane]
    errors = [case.estimate.c_rp_engaged_ratio_error for case in plane]
    intact = solid[0].estimate
    # the intact tooth pair's engaged c_rp [N/m] does not depend on the crack: the plane
    # study's intact case gives it to every solid case
    tooth = plane[0].estimate
    rows = []
    for i, case in enumerate(solid):
        depth, half = case.depth, case.half_length
        sliced = CrpRatios(
            slice_ratio(depth, half, width, depths, ratios),
            slice_ratio(depth, half, width, depths, minima),
            1 - slice_ratio(depth, half, width, depths, 1 - np.asarray(errors)))
        rows.append(SolidRow(case, sliced if three_d is None else three_d[i], sliced,
                             tooth.c_rp_engaged_intact, tooth.c_rp_engaged_intact_min,
                             tooth.c_rp_engaged_intact_window,
                             _change(case.estimate, intact, "c_ru"),
                             _change(case.estimate, intact, "c_r")))
    return rows


@dataclass
class CrackGrowthResult:
    """The solid cases with their c_rp (``rows``), the plane cases of the same depths
    (``plane``), and per half-length [m] the study of the plane report (``studies``)."""

    scene: Scene
    rows: list[SolidRow]
    plane: list[PlaneCase]
    studies: dict[float, CrackStudyResult]
    computed: int
    files: list[Path] = field(default_factory=list)

    def through(self, row: SolidRow) -> tuple[CrackCaseEstimate, CrackCaseEstimate]:
        """The plane cases through the face width at ``row``'s depth and intact."""
        plane = {case.depth: case.estimate for case in self.plane}
        return plane[row.case.depth], plane[0.0]

    def grid_rows(self) -> list[dict]:
        """The rows of ``stiffness_3d.csv`` and of the ``grid`` of ``results.json``."""
        out = []
        for row in self.rows:
            through, intact = self.through(row)
            solid, e = row.case, row.case.estimate
            out.append({
                "depth_mm": 1e3 * solid.depth, "half_length_mm": 1e3 * solid.half_length,
                "c_ru_N_m": e.c_ru, "c_ru_error_N_m": e.c_ru_error,
                "c_ru_change_percent": 100 * row.c_ru_change.value,
                "c_ru_change_error_percent": 100 * row.c_ru_change.error,
                "c_ru_change_poor_cells_percent": 100 * row.c_ru_change.poor_cells,
                "c_ru_min_N_m": e.c_ru_min, "c_ru_max_N_m": e.c_ru_max,
                "c_r_N_m": e.c_r, "c_r_error_N_m": e.c_r_error,
                "c_r_change_percent": 100 * row.c_r_change.value,
                "c_r_change_error_percent": 100 * row.c_r_change.error,
                "c_r_change_poor_cells_percent": 100 * row.c_r_change.poor_cells,
                "plane_through_c_ru_change_percent":
                    100 * (through.c_ru / intact.c_ru - 1),
                "c_rp_3d_ratio": row.c_rp.mean,
                "c_rp_3d_ratio_error": row.c_rp.error,
                "c_rp_3d_min_ratio": row.c_rp.min,
                "c_rp_slice_ratio": row.sliced.mean,
                "c_rp_slice_ratio_error": row.sliced.error,
                "plane_through_c_rp_ratio": through.c_rp_engaged_ratio,
                "min_sicn": e.min_quality, "poor_cells": e.poor_cells,
                "dofs": e.dofs, "fe_seconds": solid.seconds_total})
        return out


def run_crack_growth(scene: Scene, progress: bool = True, detection: bool = True,
                     workers: int = 2) -> CrackGrowthResult:
    """Plane cases of the sweep's depths, then the solid cases (both cached, on the scene's
    engine), then the lumped and detection stages per half-length."""
    sweep = scene.crack
    execution = scene.execution
    plane, computed_plane = crack_cases(replace(sweep, model="plane", half_lengths=()),
                                        progress, execution)
    solid, computed_solid = crack_cases(sweep, progress, execution)
    rows = solid_rows(sweep, solid, plane, solid_c_rp(sweep, solid))
    studies = {}
    for half in sweep.half_lengths:
        # each half-length's study: the solid ring's c_ru and c_r with the c_rp carried
        # over, read as the plane study's cases
        fe = [row.plane_case() for row, case in zip(rows, solid)
              if case is solid[0] or case.half_length == half]
        studies[half] = crack_study_from_fe(scene, fe, detection=detection, workers=workers,
                                            half_length=half)
    return CrackGrowthResult(scene, rows, plane, studies, computed_plane + computed_solid)


def folder_name(half_length: float) -> str:
    return f"half_length_{1e3 * half_length:g}mm"


def write_crack_growth(result: CrackGrowthResult, folder: Path) -> CrackGrowthResult:
    """Per half-length the plane study's files in ``folder/half_length_*mm``; the grid as
    CSV and JSON, its plot and ``report.md`` in ``folder``."""
    folder = Path(folder)
    scene = result.scene
    files = []
    for half, study in result.studies.items():
        files += write_crack_study(study, folder / folder_name(half)).files
    grid = result.grid_rows()
    files.append(write_csv(folder / "stiffness_3d.csv", grid))
    files.append(write_json(folder / "results.json", json_safe({
        "scene": scene.name, **provenance(), "crack": {
            "tooth": scene.crack.tooth, "start": scene.crack.start, "model": "solid",
            "depths_m": list(scene.crack.depths), "half_lengths_m": list(scene.crack.half_lengths)},
        "grid": grid, "modes": {folder_name(h): s.mode_rows() for h, s in
                                result.studies.items()}})))
    plots = []
    if scene.plots:
        plots.append(save_figure(change_figure(scene.name, grid), folder / "c_ru_change.png"))
    files += plots
    files.append(write_text(folder / "report.md", growth_report(result,
                                                                [p.name for p in plots])))
    result.files = files
    return result


def change_figure(name: str, grid: list[dict]):
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    halves = sorted({r["half_length_mm"] for r in grid if r["depth_mm"] > 0})
    for ax, key in zip(axes, ("c_ru", "c_r")):
        for i, half in enumerate(halves):
            rows = [grid[0]] + [r for r in grid if r["half_length_mm"] == half]
            ax.errorbar([r["depth_mm"] for r in rows],
                        [r[f"{key}_change_percent"] for r in rows],
                        yerr=[max(r[f"{key}_change_error_percent"],
                                  abs(r[f"{key}_change_poor_cells_percent"])) for r in rows],
                        marker="o",
                        capsize=3, label=f"semi-elliptic, half-length {half:g} mm")
        if key == "c_ru":
            depths = sorted({r["depth_mm"] for r in grid})
            through = {r["depth_mm"]: r["plane_through_c_ru_change_percent"] for r in grid}
            ax.plot(depths, [through[d] for d in depths], "k--",
                    label="plane, through the face width")
        ax.set_xlabel("crack depth at the deepest point [mm]")
        ax.set_ylabel(f"change of {key} against the intact ring [%]")
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"{name}: solid ring body stiffness against crack size (bars: the larger of "
                 "the level difference and the poor-cell effect)")
    return fig


def _is_raba(design) -> bool:
    return design.fingerprint() == raba118().fingerprint()


def growth_report(result: CrackGrowthResult, plots: list[str]) -> str:
    scene, sweep = result.scene, result.scene.crack
    info = provenance()
    width = sweep.reducer.face_width
    worst = min(result.rows, key=lambda r: r.case.estimate.min_quality)
    intact = result.rows[0].case.estimate
    lines = [
        f"# {scene.name}: 3D ring-crack growth study", "",
        f"hubvib {info['hubvib_version']}, {info['date']}. Semi-elliptic root cracks in ring "
        f"tooth {sweep.tooth}, centred on the {1e3 * width:g} mm face width: depths "
        f"{', '.join(f'{1e3 * d:.3g}' for d in sweep.depths if d > 0)} mm at the deepest point "
        f"x half-lengths {', '.join(f'{1e3 * c:.3g}' for c in sweep.half_lengths)} mm along "
        "the width.", "",
        "## Short answer", ""]
    for half, study in result.studies.items():
        rows = study.mode_rows()
        top = max(rows, key=lambda r: abs(r["shift_at_deepest_percent"]))
        found = [r["detectable_depth_mm"] for r in rows if r.get("detectable_depth_mm")]
        detect = (f"detectable from {min(found):.3g} mm" if found else
                  "no crack of the sweep detectable" if "detectable_depth_mm" in rows[0] else
                  "detection not run")
        lines.append(f"- half-length {1e3 * half:g} mm: largest shift at "
                     f"{1e3 * sweep.depths[-1]:.3g} mm depth in mode {top['mode']} "
                     f"({top['frequency_intact_hz']:.1f} Hz, "
                     f"{percent(top['shift_at_deepest_percent'])} %); {detect} "
                     f"([report]({folder_name(half)}/report.md)).")
    lines += ["", "## Solid ring body against crack size", "",
              "Change of the solid ring body's stiffness against the intact ring; ± is the "
              "change's own error estimate, (fine - fine intact) - (coarse - coarse intact): "
              "most of each level's error is common to the cracked and the intact ring, so it "
              "is far below the error of the values themselves (column `c_ru_error_N_m` of "
              "`stiffness_3d.csv`). *½ poor* is how far "
              f"the change moves when every cell with min SICN < {USABLE_QUALITY:g} has half "
              "its stiffness (see Mesh quality below); take the larger of the two as the "
              "change's uncertainty. The plane column is the crack through the whole face "
              "width at the same depth (plane stress), the limit of a long crack.", "",
              "| depth [mm] | half-length [mm] | c_ru [N/m] | change [%] | ± | ½ poor | plane, "
              "through [%] | c_r change [%] | ± | ½ poor | c_rp ratio (3D, used) | ± | "
              "c_rp ratio (slices) | plane c_rp "
              "ratio | min SICN | cells < 0.1 | DOFs | time [s] |",
              "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
              "---:|---:|"]
    for row in result.rows:
        case, e = row.case, row.case.estimate
        through, plane_intact = result.through(row)
        lines.append(
            f"| {1e3 * case.depth:.3g} | {1e3 * case.half_length:.3g} | {e.c_ru:.5e} | "
            f"{100 * row.c_ru_change.value:+.3f} | {100 * row.c_ru_change.error:.3f} | "
            f"{100 * row.c_ru_change.poor_cells:+.3f} | "
            f"{100 * (through.c_ru / plane_intact.c_ru - 1):+.3f} | "
            f"{100 * row.c_r_change.value:+.3f} | "
            f"{100 * row.c_r_change.error:.3f} | {100 * row.c_r_change.poor_cells:+.3f} | "
            f"{row.c_rp.mean:.4f} | {row.c_rp.error:.4f} | "
            f"{row.sliced.mean:.4f} | "
            f"{through.c_rp_engaged_ratio:.4f} | {e.min_quality:.3g} | "
            f"{e.poor_cells} | {e.dofs} | {case.seconds_total:.0f} |")
    lines += [""] + [x for p in plots for x in figure_lines(p)]
    lines += [
        "## Assumptions", "",
        "- Solid ring: curved quadratic tetrahedra, supports clamped, every planet's mesh "
        "force spread over its tooth's load surface across the face; c_ru is the mean over "
        "every carrier position of one planet pitch, c_ru and c_r the work-conjugate rim "
        "parts as in the plane study (the root-land readings in "
        "`c_ru_root_land_N_m`, `c_r_root_land_N_m`); error estimate: the default solid level against the one before it "
        "(`hubvib.meshing.levels.SOLID_LEVELS`).",
        "- c_rp of the cracked tooth (used by the lumped and detection stages): from the "
        "solid ring, with the factorisations of c_ru. The tooth is loaded by 1 N along the "
        "line of action spread uniformly across the face width (a spur pair's contact line) "
        "at the plane tooth curve's flank radii; each strip z = const is read as the plane "
        "model reads its section (rigid motion of the section through the load point, the "
        "root lands' rigid motion subtracted), and the deflection is the load-weighted mean "
        "over the width. The cracked/intact ratio at each radius scales the plane intact "
        "ring-tooth curve, which enters the plane study's pair and mesh-cycle model (planet "
        "tooth and Hertz in series, load shared over the path of contact): the 3D column "
        "is the mean over the cracked tooth's engagement; ± is the fine level's ratio "
        "against the coarse level's.",
        "- For comparison, the slice method (Chen & Shao 2011): the face width in "
        f"{SLICES} independent slices in parallel, each with the plane c_rp ratio at its local "
        "depth, linear between the plane cases of the sweep's depths. Independent slices "
        "are softer than the solid tooth, so the slices overstate the crack's effect on "
        "c_rp; the plane column is the crack through the width (plane stress).",
        "- The crack is not moved: the mean over carrier positions includes the positions "
        "where a planet loads the cracked tooth.",
        f"- Mesh quality: the worst cell of the sweep has min SICN "
        f"{worst.case.estimate.min_quality:.3g} "
        f"({case_label((worst.case.depth, worst.case.half_length))}). The intact "
        f"ring's mesh has {intact.poor_cells} cells below {USABLE_QUALITY:g} too (min "
        f"{intact.min_quality:.3g}): they come with root lands and fillets narrower than the "
        "elements, and a finer mesh there costs several times the DOFs. They sit where c_ru "
        "is read (the root lands), so every case is solved once more with them at half "
        "stiffness: the *½ poor* columns." + (RABA_POOR_CELLS if _is_raba(sweep.reducer) else ""),
        "",
        f"FE cases: {len(result.rows)} solid and {len(result.plane)} plane "
        f"({result.computed} computed now, the others from the cache).", ""]
    return "\n".join(lines) + "\n"


def _run(scene: Scene, staged: Path) -> CrackGrowthResult:
    started = time.perf_counter()
    with working("FE stage and lumped spectra"):
        result = run_crack_growth(scene)
    stage(f"FE stage ({result.computed} of {len(result.rows) + len(result.plane)} cases "
          f"computed) and lumped spectra of {len(result.studies)} half-lengths", started)
    started = time.perf_counter()
    with working("tables, plots and reports"):
        write_crack_growth(result, staged)
        result.files += [p for p in write_html_reports(staged) if p not in result.files]
    stage("tables, plots and reports", started)
    return result


def _summary(scene: Scene, result: CrackGrowthResult, folder: Path, files: list) -> dict:
    return {"scene": scene.name, "folder": str(folder), "files": [str(f) for f in files],
            "fe_cases_computed": result.computed, "grid": result.grid_rows()}


def _lines(scene: Scene, result: CrackGrowthResult, folder: Path) -> list[str]:
    grid = result.grid_rows()
    out = [f"scene {scene.name!r}: semi-elliptic ring root cracks, {len(grid) - 1} solid cases "
           f"({result.computed} FE cases computed, the others cached)",
           f"{'depth [mm]':>10} {'half-length [mm]':>16} {'c_ru change [%]':>16} {'+-':>7} "
           f"{'1/2 poor':>8} {'plane through [%]':>17} {'c_rp 3D':>8} {'slices':>7}"]
    for r in grid[1:]:
        out.append(f"{r['depth_mm']:>10.3g} {r['half_length_mm']:>16.3g} "
                   f"{r['c_ru_change_percent']:>+16.3f} {r['c_ru_change_error_percent']:>7.3f} "
                   f"{r['c_ru_change_poor_cells_percent']:>+8.3f} "
                   f"{r['plane_through_c_ru_change_percent']:>+17.3f} "
                   f"{r['c_rp_3d_ratio']:>8.4f} {r['c_rp_slice_ratio']:>7.4f}")
    out.append("+-: fine minus coarse level; 1/2 poor: the change with the cells of min SICN "
               "< 0.1 at half stiffness (take the larger); c_rp 3D: the solid tooth's ratio "
               "over the engagement (used), slices: the slice method's (compared)")
    out.append(f"\nreport: {folder / 'report.md'} (in a browser: {folder / 'report.html'})")
    return out


def parse_solid(data: dict, design, params) -> CrackSweep:
    """The solid crack growth's ``[crack]`` table (and no lumped-sweep keys, no [signal])."""
    sweep = parse_crack_table(data["crack"], design)
    refuse_sweep_keys(data)
    if "signal" in data:
        raise SceneError("[signal] needs a plane crack study: the tooth curves of the signal "
                         "are plane (remove [signal] or set [crack] model = \"plane\")")
    return sweep


#: the solid crack growth: [crack] model = "solid"
CRACK_GROWTH = Study("growth", _run, _summary, _lines, parse_solid, tables=frozenset({"crack"}),
                     selects=lambda data: crack_model(data) == "solid",
                     selection='[crack] with model = "solid"', fe=True, renders=True)
