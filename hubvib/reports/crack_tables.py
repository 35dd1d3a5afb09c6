"""The crack study's tables: ``results.json`` and the CSV files, from its typed result.

Lengths are written in millimetres or metres as each key says, stiffnesses in N/m,
frequencies in Hz (the keys carry the units).
"""
from __future__ import annotations

import math
from dataclasses import asdict
from pathlib import Path

from hubvib.detection.mesh_stiffness import family_depths, iso_c_rp
from hubvib.foundation.output import write_csv, write_json
from hubvib.reports.provenance import json_safe, provenance

__all__ = ["write_crack_tables"]


def write_crack_tables(result, folder: Path) -> list[Path]:
    """``stiffness_vs_depth.csv``, ``frequency_vs_depth.csv``, ``modes.csv``, the detection
    study's CSV files (when it ran), ``results.json`` and ``elastic_ring.csv`` (when the
    elastic ring ran) of ``result`` (a ``studies.crack_study.CrackStudyResult``)."""
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
    return files


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


