"""The crack study's ``report.md`` text, assembled once from its typed result.

Depths are written in millimetres, frequencies in hertz, stiffnesses in N/m.
"""
from __future__ import annotations

import math

import numpy as np

from hubvib.reports import detection_sections as sections
from hubvib.detection.mesh_stiffness import iso_c_rp
from hubvib.detection.numbers import depth_mm, percent, sensitivity, shift_hz
from hubvib.render.captions import figure_lines
from hubvib.render.schedule import rendered_depth
from hubvib.reports.answer import lead, lead_lines
from hubvib.reports.mesh_stiffness_section import mesh_stiffness_section
from hubvib.reports.provenance import provenance
from hubvib.reports.validation_status import lumped_model_status

__all__ = ["SIGNAL_SECTION", "crack_report"]

#: the report section that links the vibration signature (scenes with a [signal] table)
SIGNAL_SECTION = ["", "## Vibration signature", "",
                  "The signal a sensor on the ring records, its order spectrum, spectrogram "
                  "and condition indicators against crack depth: "
                  "[signal/report.md](signal/report.md)."]


def crack_report(result, plots: list[str], renders: list[str], fe_renders: list[str] = (),
                 signal: bool = False) -> str:
    """``report.md`` of ``result`` (a ``studies.crack_study.CrackStudyResult``) showing the
    figures ``plots`` (file names) and ``renders``, ``fe_renders`` (paths relative to the
    report); ``signal``: with the section linking the signal study's report."""
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
    which = lead(result.rigid, result.elastic, result.elastic_validity)
    if study is not None:
        lines += sections.short_answer(scene.name, model, study, sources,
                                       lead_lines(which))
    if result.elastic is not None:
        from hubvib.reports.elastic_sections import side_by_side

        lines += ([] if study is not None else ["## Short answer", "", *lead_lines(which)])
        lines += side_by_side(result.rigid, result.elastic, result.elastic_validity)
    if result.mode_map:
        lines += mode_map_lines(result.mode_map)
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
        from hubvib.reports.elastic_sections import elastic_section

        lines += elastic_section(result.elastic, result.elastic_validity)
        from hubvib.reports.elastic_sections import load_sensitivity_lines

        lines += load_sensitivity_lines(result.load_sensitivity, result.elastic.record_length)
        from hubvib.reports.pad_sections import pad_variant_lines

        lines += pad_variant_lines(result.pad_variant, result.elastic)
    if result.elastic_map is not None:
        from hubvib.reports.elastic_map_sections import map_section

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
        + ("three mesh levels (the default, twice and four times as coarse: Richardson with "
           "the observed order where it lies in 0.5..4, else the larger level difference)"
           if sweep.model == "plane" else
           "the three solid levels (the same rule (`hubvib.meshing.levels.SOLID_LEVELS`; the "
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
                  "tooth), von Mises stress; then its lowest elastic modes of its own on the "
                  "elastic ring's mounting (its Winkler foundation on the support arcs unless "
                  "the scene sets another; plane stress, deformation magnified).", ""]
        lines += [x for n in fe_renders for x in figure_lines(n)]
    if signal:
        lines += SIGNAL_SECTION
    return "\n".join(lines) + "\n"



def mode_map_lines(pairs) -> list[str]:
    """The table mapping each elastic-ring mode to the rigid-ring mode its lumped bodies
    move like (``detection.mode_map``; ``mode_map.csv`` has every mode)."""
    lines = ["**Which mode is which.** Mode numbers mean different modes in the two models; "
             "each elastic-ring mode below is paired with the rigid-ring mode whose motion of "
             "the lumped bodies (sun, carrier, planets) it resembles most (mass-weighted MAC "
             "on those coordinates; lumped share: the elastic mode's kinetic energy in the "
             "lumped bodies, small for a mode of the ring's own):", "",
             "| elastic ring | rigid ring | MAC | lumped share |", "|---|---|---:|---:|"]
    for pair in pairs:
        lines.append(f"| {pair.elastic} | {pair.rigid} | {pair.mac:.2f} | "
                     f"{pair.lumped_share:.2f} |")
    return lines + [""]


def _image(name: str, plots: list[str]) -> list[str]:
    """Markdown lines showing ``name`` when it was written."""
    return figure_lines(name) if name in plots else []


