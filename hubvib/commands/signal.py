"""``hubvib signal SCENE``: vibration signature of a cracked ring at a fixed sensor."""
from __future__ import annotations

import sys
import time
from pathlib import Path


def add_parser(sub) -> None:
    p = sub.add_parser("signal", help="vibration signature of a ring crack: sensor signal "
                                      "(CSV, WAV), order spectrum, spectrogram, indicators")
    p.add_argument("scene", help="scene TOML file with [crack] and [signal] tables, or a "
                   "shipped scene's name (raba118_signal)")
    p.add_argument("--out", type=Path, help="output folder (default: the scene's folder)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(handler=run)


def run(args) -> int:
    from hubvib.foundation.output import json_text, output_set
    from hubvib.runtime.cache_check import sweep_cache
    from hubvib.runtime.progress import stage
    from hubvib.studies.scene import load_scene
    from hubvib.signal.indicators import INDICATORS
    from hubvib.signal.report import write_signal_study
    from hubvib.signal.signature_study import run_signal_study

    scene = load_scene(args.scene)
    folder = Path(args.out or scene.folder)
    sweep_cache()  # what a killed run left in the cache, before this one adds to it
    started = time.perf_counter()
    ring = scene.elastic.ring
    if ring in ("elastic", "both"):
        elastic = _elastic_records(scene, folder, "signal" if ring == "elastic" else
                                   "signal_elastic", args.json and ring == "elastic",
                                   quiet=args.json and ring == "both")
        if ring == "elastic":
            return elastic
    # every input error (the time step needs the model) is raised here, before any file
    study = run_signal_study(scene, progress=lambda m: print(f"hubvib: {m}", file=sys.stderr))
    stage(f"signals of {len(study.depths)} crack depth(s)", started)
    with output_set(folder) as staged:
        data = write_signal_study(study, staged, plots=scene.plots)
    data = dict(data, folder=str(folder), files=[str(folder / f) for f in data["files"]])
    data["tacho_csv"] = str(folder / data["tacho_csv"])
    for d in data["depths"]:
        d["signal_csv"], d["signal_wav"] = (str(folder / d[k]) for k in ("signal_csv",
                                                                          "signal_wav"))
    if args.json:
        print(json_text(data))
        return 0
    print(f"scene {scene.name!r}: carrier {study.carrier_hz:.4g} Hz, mesh {study.mesh_hz:.4g} "
          f"Hz, {study.options.sample_rate_hz:g} samples/s, h = {study.step:.3g} s "
          f"({study.steps_per_revolution} steps per revolution)")
    names = INDICATORS
    print(f"{'depth [mm]':>10} " + " ".join(f"{n:>12}" for n in names))
    for d in data["depths"]:
        print(f"{d['depth_mm']:>10.3g} "
              + " ".join(f"{d['indicators'][n]['mean']:>12.4g}" for n in names))
    monotone = data["monotone_indicators"]
    print("monotone with depth: " + (", ".join(f"{m['indicator']} ({m['direction']})"
                                              for m in monotone) or "none"))
    print(f"\nreport: {folder / 'report.md'} (in a browser: {folder / 'report.html'})")
    return 0



def _elastic_records(scene, folder: Path, prefix: str, as_json: bool, quiet: bool = False
                     ) -> int:
    """One record per crack depth from the elastic ring (``hubvib.signal.elastic_record``):
    ``{prefix}_{depth}.csv`` and ``.wav`` and ``{prefix}_records.json`` in ``folder``;
    ``quiet``: print nothing (the rigid study's JSON follows on stdout)."""
    from hubvib.foundation.output import json_text, output_set, write_json
    from hubvib.runtime.progress import stage
    from hubvib.signal.elastic_files import records_json, write_elastic_records
    from hubvib.signal.elastic_record import scene_records

    started = time.perf_counter()
    records = scene_records(scene, progress=lambda m: print(f"hubvib: {m}", file=sys.stderr))
    stage(f"elastic-ring records of {len(records)} crack depth(s)", started)
    with output_set(folder) as staged:
        files = write_elastic_records(records, staged, prefix)
        data = records_json(records, [folder / f.name for f in files], scene.name,
                            scene.signal, scene.elastic.sensor_angle)
        write_json(staged / f"{prefix}_records.json", data)
    if as_json:
        print(json_text(data))
        return 0
    if quiet:
        return 0
    print(f"scene {scene.name!r}: elastic ring, {scene.signal.sample_rate_hz:g} samples/s, "
          f"{scene.signal.revolutions:g} carrier revolutions")
    print(f"{'depth [mm]':>10} {'RMS [m/s^2]':>12} {'modes':>6} {'seconds':>8}  file")
    for d, f in zip(data["depths"], data["files"][::2]):
        print(f"{d['depth_mm']:>10.3g} {d['rms_m_s2']:>12.4g} {d['modes']:>6d} "
              f"{d['seconds']:>8.1f}  {f}")
    return 0
