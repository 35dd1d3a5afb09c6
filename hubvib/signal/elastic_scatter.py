"""Scatter of the elastic ring's modes identified from simulated records, against Au's law (SI).

``python -m hubvib.signal.elastic_scatter [--seeds N] [--record-s T] [--out FILE.json]``
simulates ``N`` records of the intact Raba reducer on the elastic ring (the carrier turning,
FE-free synthetic mesh curves, white ambient forces seeded 0 .. N-1; the scene
``raba118_elastic_signal``'s operating point and sensor), identifies the coupled modes in
each (:mod:`hubvib.identification.elastic_records`: bands of close modes fitted together) and
writes, per mode identified in every record, the mean and standard deviation of the
frequency over the seeds, the mean Cramer-Rao bound and Au's closed form
``sqrt(zeta f / (2 pi T))``, with the model's mean-stiffness frequency and the frequency the
running reducer shows (the Floquet mode over the mesh cycle,
:mod:`hubvib.signal.elastic_floquet`, averaged over eight carrier positions), from which the
bands and the fits start; :func:`scatter_table` renders it.
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

#: the shipped scene whose operating point and sensor the study uses
SCENE = "raba118_elastic_signal"


def elastic_scatter(seeds: int = 6, record_s: float = 10.0, progress=None) -> dict:
    """The scatter study (module docstring); JSON-ready."""
    from hubvib.elastic.rest import rest_stiffness
    from hubvib.identification.elastic_records import (identify_bands, mode_bands,
                                                       radial_visibility)
    from hubvib.identification.law import au_sigma_hz
    from hubvib.identification.records import Record
    from hubvib.lumped.elastic_ring import coupled_modes

    from dataclasses import replace

    from hubvib.elastic.cases import carrier_positions

    from .elastic_floquet import floquet_modes
    from .elastic_model import elastic_time_model
    from .elastic_record import depth_record, elastic_ring_all_teeth, sensor_polar_angle
    from .mesh_curves import synthetic_curves
    from .mesh_phase import design_phasing, design_teeth
    from .simulation import carrier_speed

    scene = _scene()
    design, options = scene.design, scene.signal
    teeth = design_teeth(design)
    carrier_hz = options.sun_speed_rpm / 60 * teeth["sun"] / (teeth["sun"] + teeth["ring"])
    options = replace(options, revolutions=round(record_s * carrier_hz), noise_level=0.05)
    k_rest = rest_stiffness(design, scene.elastic.options.rest)
    er = elastic_ring_all_teeth(design, None, scene.elastic, k_rest)
    curves = synthetic_curves(design).to_preset(er.params.c_sp, er.params.c_rp)
    away, _ = carrier_positions(design, scene.crack.tooth)
    modes = coupled_modes(er.params, er.operators, away, er.k_rest,
                          max_hz=scene.elastic.options.band_hz)
    angle = sensor_polar_angle(er.operators, scene.crack.tooth, scene.elastic.sensor_angle)
    vis = radial_visibility(modes.probe, angle)
    zeta = options.damping_ratio
    model = elastic_time_model(er.params, er.operators, er.k_rest, zeta,
                               options.sun_torque_N_m, 15e3)
    speed = carrier_speed(options, teeth["ring"], teeth["sun"])
    shown = np.mean([floquet_modes(model, curves, design_phasing(design), speed, p).record_hz()
                     for p in range(0, model.teeth, max(1, model.teeth // 8))], axis=0)
    record_hz = np.array(modes.frequency_hz, dtype=float)
    n = min(record_hz.size, shown.size)
    record_hz[:n] = shown[:n]
    bands, unseen = mode_bands(record_hz, vis, zeta)
    found, sigmas, seconds = {}, {}, []
    for seed in range(seeds):
        started = time.perf_counter()
        rec, _ = depth_record(design, er, curves, replace(options, ambient_seed=seed),
                              scene.elastic.sensor_angle, scene.crack.tooth, [seed, 0])
        seconds.append(time.perf_counter() - started)
        ident = identify_bands(Record(rec.values, rec.sample_rate), bands, unseen, zeta)
        for i, m in zip(ident.index, ident.modes):
            found.setdefault(i, []).append(m.frequency_hz)
            sigmas.setdefault(i, []).append(m.sigma_hz)
        if progress:
            progress(f"seed {seed}: {len(ident.index)} modes, {seconds[-1]:.1f} s")
    T = rec.values.size / rec.sample_rate
    rows = []
    for i in sorted(found):
        f = np.array(found[i])
        if f.size < seeds:
            continue
        rows.append({"mode": i + 1, "model_hz": float(modes.frequency_hz[i]),
                     "record_hz": float(record_hz[i]),
                     "visibility": float(vis[i]), "mean_hz": float(f.mean()),
                     "std_hz": float(f.std(ddof=1)) if f.size > 1 else None,
                     "cramer_rao_hz": float(np.mean(sigmas[i])),
                     "au_hz": float(au_sigma_hz(modes.frequency_hz[i], zeta, T))})
    return {"scene": SCENE, "seeds": seeds, "record_s": T, "damping_ratio": zeta,
            "sensor_angle_deg": math.degrees(scene.elastic.sensor_angle),
            "mesh_curves": "synthetic", "record_seconds": seconds, "modes": rows}


def _scene():
    """The shipped scene's design, ``[signal]``, ``[elastic]`` and cracked tooth (read here:
    the scene loader sits above this layer)."""
    import tomllib
    from importlib import resources
    from types import SimpleNamespace

    from hubvib.design import preset_design
    from hubvib.elastic.options import parse_elastic_table

    from .options import parse_signal_table

    text = resources.files("hubvib.scenes").joinpath(f"{SCENE}.toml").read_text("utf-8")
    data = tomllib.loads(text)
    return SimpleNamespace(design=preset_design(data["reducer"]["preset"]),
                           signal=parse_signal_table(data["signal"]),
                           elastic=parse_elastic_table(data["elastic"]),
                           crack=SimpleNamespace(tooth=int(data["crack"]["tooth"])))


def scatter_table(data: dict) -> str:
    """Markdown table of :func:`elastic_scatter`'s result."""
    lines = [f"{data['seeds']} records of {data['record_s']:.3g} s, damping "
             f"{100 * data['damping_ratio']:g} %, sensor {data['sensor_angle_deg']:g} deg from "
             "the cracked tooth (intact ring).", "",
             "| mode | model [Hz] | running (Floquet) [Hz] | seen [-] | mean identified [Hz] | "
             "std over seeds [Hz] | mean Cramer-Rao bound [Hz] | Au's law [Hz] |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in data["modes"]:
        std = "-" if r["std_hz"] is None else f"{r['std_hz']:.3g}"
        running = f"{r['record_hz']:.1f}" if "record_hz" in r else "-"
        lines.append(f"| {r['mode']} | {r['model_hz']:.1f} | {running} | {r['visibility']:.2f} | "
                     f"{r['mean_hz']:.1f} | {std} | {r['cramer_rao_hz']:.3g} | "
                     f"{r['au_hz']:.3g} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=6)
    parser.add_argument("--record-s", type=float, default=10.0)
    parser.add_argument("--out", type=Path)
    args = parser.parse_args(argv)
    data = elastic_scatter(args.seeds, args.record_s, progress=print)
    if args.out:
        args.out.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    print(scatter_table(data))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
