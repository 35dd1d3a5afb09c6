"""The crack study's tables: ``results.json`` and the CSV files, from its typed result.

Lengths are written in millimetres or metres as each key says, stiffnesses in N/m,
frequencies in Hz (the keys carry the units).
"""
from __future__ import annotations

import numpy as np

import math
from dataclasses import asdict
from pathlib import Path

from hubvib.detection.mesh_stiffness import family_depths, iso_c_rp
from hubvib.foundation.output import explained, write_csv, write_json
from hubvib.reports.answer import answer_line, lead
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
    if result.mode_map:
        files.append(write_csv(folder / "mode_map.csv", [p.row() for p in result.mode_map]))
    answers = [r for r in (result.rigid, result.elastic) if r is not None]
    if answers:
        files.append(write_csv(folder / "detection.csv",
                               [row for r in answers for row in r.rows()]))
    which = lead(result.rigid, result.elastic, result.elastic_validity)
    if study is not None:
        files += [write_csv(folder / "pod.csv", study.pod.rows()),
                  write_csv(folder / "pod_family.csv", study.pod.family_rows()),
                  write_csv(folder / "detectability_map.csv", study.map.rows())]
    files.append(write_json(folder / "results.json", json_safe(explained({
        "scene": scene.name, **provenance(), "parameters": result.model.params.to_dict(),
        "crack": explained({k: v for k, v in asdict(scene.crack).items() if k != "design"},
                           **{key: f"not set in the scene's [crack] table: the mounting the "
                                   f"study used is mounting.{key}_N_m"
                              for key in ("c_ru_mount", "c_r_mount")}),
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
            "watched_modes": [int(i) + 1 for i in study.watched_modes()],
            "answer": result.rigid.to_dict()},
        "short_answer": None if which.leader is None else explained({
            "ring": which.leader.ring, "line": answer_line(which),
            "comparison": None if which.other is None else which.other.ring,
            "comparison_why": which.reason or None},
            comparison=(f"only the {which.leader.ring} ring's answer: the other ring model "
                        "did not run, or the rigid ring's validity band is unknown"),
            comparison_why="no second ring model to compare with"),
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
        "mode_map": [p.row() for p in result.mode_map] or None,
        "load_sensitivity": [v.to_dict() for v in result.load_sensitivity] or None,
        "pad_variant": None if result.pad_variant is None else result.pad_variant.to_dict(),
        "elastic_map": None if result.elastic_map is None else result.elastic_map.rows()},
        detection="the scene runs no detection study",
        c_rp_methods="the lumped c_rp is the FE intact one: both methods agree",
        c_rp_other_method_family_pod=_other_reason(result.c_rp_comparison),
        elastic_ring="the scene's [elastic] ring is \"rigid\" (or its crack is no plane sweep)",
        mode_map="the elastic ring did not run",
        load_sensitivity="the elastic ring did not run on a mounted ring",
        pad_variant=result.pad_variant_reason,
        elastic_map=("the elastic ring did not run" if result.elastic is None else
                     "the scene's [elastic] map is false")))))
    if result.elastic is not None:
        files.append(write_csv(folder / "elastic_ring.csv", _elastic_csv(result.elastic)))
    return files


def _validity_record(band) -> dict:
    from hubvib.elastic.validity import validity_record

    return validity_record(band)


def _elastic_json(elastic) -> dict:
    """The elastic ring's answer for results.json."""
    from hubvib.detection.elastic_model import elastic_mode_rows

    detail = elastic.detail
    return explained({
        **elastic.to_dict(),
        "family_pod_nominal": {f"{t:g}": [float(p) for p in v]
                               for t, v in elastic.pod_nominal.items()},
        "scatter": None if not detail.scatter else dict(zip(
            ("masses", "stiffnesses", "mounting", "fe_change_error"), detail.scatter)),
        "k_rest_N_m": detail.k_rest, "ring_dofs": detail.ring_dofs,
        "foundation_N_m2": None if detail.foundation is None else {
            "normal": detail.foundation[0], "tangential": detail.foundation[1]},
        "sensor_angle_deg": math.degrees(detail.sensor_angle),
        "lowest_ring_mode": None if detail.lowest_ring_mode is None else {
            "frequency_hz": detail.lowest_ring_mode[0],
            "nodal_diameter": detail.lowest_ring_mode[1]},
        "crack_state": _crack_state_rows(elastic),
        "modes": elastic_mode_rows(elastic)},
        scatter="the answer was built without the detection study's scatter",
        foundation_N_m2="the ring is on no foundation: clamped on its support arcs, or free",
        lowest_ring_mode="no elastic mode of the ring's own in its basis",
        crack_state="the faces are taken open (no loaded crack)")


def _crack_state_rows(elastic) -> list[dict] | None:
    """Per cracked depth the loaded crack over the pitch: share of positions with the
    faces apart, largest open length [m] and gap [m], and each position's state."""
    rows = []
    for d, track in zip(elastic.depths, elastic.detail.tracks):
        states = getattr(track, "states", ()) if track is not None else ()
        if states:
            rows.append({"depth_m": float(d), "open_share": float(track.open_share),
                         "torque_N_m": float(track.torque_N_m),
                         "closure_gap_m": float(track.closure_gap_m),
                         "max_open_length_m": max(float(s.open_length_m) for s in states),
                         "max_gap_m": max(float(s.max_gap_m) for s in states),
                         "positions": [{"carrier_tooth": int(s.carrier_tooth),
                                        "open_length_m": float(s.open_length_m),
                                        "max_gap_m": float(s.max_gap_m)} for s in states]})
    return rows or None


def _elastic_csv(elastic) -> list[dict]:
    """One row per depth and coupled mode of the elastic ring."""
    from hubvib.detection.elastic_model import bilinear_hz

    detail, bilinear = elastic.detail, bilinear_hz(elastic)
    rows = []
    for k, depth in enumerate(elastic.depths):
        for i, f in enumerate(elastic.intact_hz):
            rows.append({"depth_mm": 1e3 * depth, "mode": elastic.labels[i],
                         "class": detail.kind[i],
                         "nodal_diameter": detail.nodal_diameter[i],
                         "intact_hz": float(f), "record_hz": float(elastic.frequency_hz[k, i]),
                         "open_hz": float(_open(elastic)[k, i]),
                         "instantaneous_min_hz": _track_value(elastic, k, i,
                                                              "instantaneous_min_hz"),
                         "instantaneous_max_hz": _track_value(elastic, k, i,
                                                              "instantaneous_max_hz"),
                         "slip_hz": _track_value(elastic, k, i, "slip_hz"),
                         "in_contact_hz": float(detail.in_contact_hz[k, i]),
                         "in_contact_intact_hz": float(detail.in_contact_hz[0, i]),
                         "bilinear_hz": float(bilinear[k, i]),
                         "split_pair": bool(detail.split_pair[k, i]),
                         "watched": i in elastic.watched,
                         "added_depth": depth in elastic.added_depths,
                         "family_pod": float(elastic.pod[elastic.record_length][k]),
                         "family_pod_nominal": float(
                             elastic.pod_nominal[elastic.record_length][k])})
    return rows


def _open(elastic) -> np.ndarray:
    """Faces open, planet 1 half a pitch away [Hz] (the record when it is the same)."""
    detail = elastic.detail
    return elastic.frequency_hz if detail.open_hz is None else detail.open_hz


def _track_value(elastic, k: int, i: int, name: str) -> float:
    """Mode ``i`` of depth ``k``'s loaded-crack track (``name``) [Hz]; NaN without one."""
    tracks = elastic.detail.tracks
    track = tracks[k] if k < len(tracks) else None
    values = None if track is None else getattr(track, name)
    return float(values[i]) if values is not None and i < len(values) else float("nan")


def _other_reason(comparison) -> str:
    """Why results.json would have no family POD under the other c_rp method."""
    if comparison is None:
        return "the lumped c_rp is the FE intact one: both methods agree"
    return "the detection study did not run"


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


