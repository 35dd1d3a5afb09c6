"""Files of the elastic-ring records: one CSV and WAV per depth and their summary (SI).

Apart from :mod:`.elastic_record` so that the model's import graph (the result caches'
key) does not reach the report's plotting modules.
"""
from __future__ import annotations

import math

import numpy as np

from .elastic_record import DepthRecord
from .options import SignalOptions


def write_elastic_records(records: list[DepthRecord], folder, prefix: str = "signal",
                          wav: bool = True) -> list:
    """``{prefix}_{depth}.csv`` (columns ``time_s, acceleration_m_s2``) and, with ``wav``,
    ``.wav`` (32-bit float, peak 1) of every record in ``folder``; returns the paths."""
    from pathlib import Path

    from .accelerometer import write_signal_csv, write_wav
    from .report import depth_name

    folder = Path(folder)
    paths = []
    for rec in records:
        name = f"{prefix}_{depth_name(rec.depth)}"
        paths.append(write_signal_csv(folder / f"{name}.csv", rec.time, rec.values))
        if wav:
            paths.append(write_wav(folder / f"{name}.wav", rec.values, rec.sample_rate))
    return paths


def records_json(records: list[DepthRecord], files, scene_name: str, options: SignalOptions,
                 sensor_angle: float) -> dict:
    """The summary of an elastic-ring record run (JSON-ready)."""
    return {"scene": scene_name, "ring": "elastic", "sample_rate_hz": options.sample_rate_hz,
            "revolutions": options.revolutions, "sensor_angle_deg": math.degrees(sensor_angle),
            "ambient_force_psd_N2_Hz": options.ambient_force_psd_N2_Hz,
            "ambient_seed": options.ambient_seed, "damping_ratio": options.damping_ratio,
            "depths": [{"depth_mm": 1e3 * r.depth, "samples": int(r.values.size),
                        "rms_m_s2": float(np.sqrt(np.mean(r.values ** 2))),
                        "peak_m_s2": float(np.max(np.abs(r.values))),
                        "seconds": r.seconds, "integration_seconds": r.integration_seconds,
                        "steps": r.steps, "modes": r.modes} for r in records],
            "files": [str(f) for f in files]}
