"""The elastic ring's closed loop from records: housing records simulated at depths between
the sweep's, with seeds no shipped record and no calibration used, identified and diagnosed
as ``hubvib diagnose --ring elastic --record R --baseline-record B`` does them (SI inside).

``python -m hubvib.studies.record_loop [--scene S] [--depths-mm 1.5,4.5] [--records N]
[--intact N] [--workers W] [--out FILE.json]``

Every record is a ``[signal]`` record of the scene's elastic ring (``hubvib.signal.
elastic_record``: the carrier turning, the FE mesh cycles, broadband forces, noise) with the
ambient seed ``(SEED_BASE, depth in 0.1 um, k)``; its baseline is the intact record of seed
``(SEED_BASE + 1, 0, k)``, so no two records share their forces or noise.  Per cracked
record: the verdict, the estimate and whether the interval holds the true depth; per intact
record (against the baseline of another seed): whether a crack is indicated, a false alarm.
Each row is a result cache entry (``runtime.result_cache``): an interrupted run keeps the
rows it finished, a rerun computes only the rest, and a row is trusted only when its
checksum, type and source key hold.
"""
from __future__ import annotations

import argparse
import math
import sys
from dataclasses import asdict, dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from hubvib.foundation.output import finite_or_none, json_text, write_text

__all__ = ["LoopRow", "SEED_BASE", "loop_rows", "summary"]

#: first ambient seed of the loop's records (the shipped records use the scene's, 0)
SEED_BASE = 7919
#: the scene the shipped elastic records come from
DEFAULT_SCENE = "raba118_elastic_signal"


@dataclass(frozen=True)
class LoopRow:
    """One record's diagnosis.  ``depth_m``: the true depth [m] (0: intact); ``k``: the
    record's number (its seeds, :func:`record_seed`); ``verdict``; ``estimate_m``,
    ``low_m``, ``high_m``: the estimate and interval [m] (None when the diagnosis gives
    none); ``confidence``: the interval's probability [-]; ``modes``: the coupled modes
    used (1-based)."""

    depth_m: float
    k: int
    verdict: str
    estimate_m: float | None
    low_m: float | None
    high_m: float | None
    confidence: float
    modes: tuple

    @property
    def alarm(self) -> bool:
        return self.verdict == "crack indicated"

    @property
    def covered(self) -> bool | None:
        """The interval holds the true depth (None: no interval)."""
        if self.low_m is None or self.high_m is None:
            return None
        return self.low_m <= self.depth_m <= self.high_m


def record_seed(depth: float, k: int, baseline: bool = False) -> tuple:
    """The ambient seed of the loop's ``k``-th record at ``depth`` [m] (``baseline``: the
    ``k``-th intact baseline)."""
    return (SEED_BASE + 1, 0, k) if baseline else (SEED_BASE, int(round(depth * 1e7)), k)


@lru_cache(maxsize=None)
def _scene(name: str):
    from hubvib.studies.scene import load_scene

    return load_scene(name)


@lru_cache(maxsize=2)
def _ring(name: str, depth: float):
    from hubvib.cases.sweep import crack_of
    from hubvib.elastic.rest import rest_stiffness
    from hubvib.signal.elastic_record import elastic_ring_all_teeth

    scene = _scene(name)
    elastic = scene.elastic
    crack = crack_of(scene.crack, depth) if depth > 0 else None
    return elastic_ring_all_teeth(scene.design, crack, elastic,
                                  rest_stiffness(scene.design, elastic.options.rest))


@lru_cache(maxsize=None)
def _curves(name: str):
    from hubvib.cases.sweep import ACCURACY
    from hubvib.signal.mesh_curves import fe_mesh_curves

    scene = _scene(name)
    sweep = scene.crack
    fe = fe_mesh_curves((0.0,), sweep.start, sweep.angle, ACCURACY[sweep.accuracy], None,
                        scene.design)[0]
    return fe.to_preset(scene.params.c_sp, scene.params.c_rp)


def simulate(name: str, depth: float, seed: tuple) -> np.ndarray:
    """The scene's elastic-ring record at ``depth`` [m] with ambient seed ``seed``
    (float32 [m/s^2]; the noise ``noise_level`` times the record's own RMS)."""
    from hubvib.signal.elastic_record import depth_record

    scene = _scene(name)
    rec, _ = depth_record(scene.design, _ring(name, depth), _curves(name), scene.signal,
                          scene.elastic.sensor_angle, scene.crack.tooth, list(seed))
    return rec.values.astype(np.float32)


class _Diagnoser:
    """What every record's diagnosis shares: the elastic reference, the intact case, the
    Floquet shift of the record frequencies, the sensor angle."""

    def __init__(self, name: str):
        from hubvib.detection.diagnosis import scene_reference
        from hubvib.signal.elastic_record import scene_floquet_shift

        self.scene = scene = _scene(name)
        self.ref, self.options = scene_reference(scene, progress=False, ring="elastic")
        self.shift = scene_floquet_shift(scene, _curves(name))

    def row(self, depth: float, k: int, values, baseline) -> LoopRow:
        from hubvib.detection.diagnosis import diagnose
        from hubvib.detection.from_records import elastic_measured
        from hubvib.identification.records import Record

        rate = self.scene.signal.sample_rate_hz
        measured, _ = elastic_measured(self.scene, Record(np.asarray(values, float), rate),
                                       Record(np.asarray(baseline, float), rate), self.shift)
        if measured is None:
            return LoopRow(depth, k, "not identified", None, None, None, math.nan, ())
        d = diagnose(measured, self.ref, self.options)
        return LoopRow(depth, k, d.verdict, d.depth, d.depth_low, d.depth_high,
                       float(d.confidence), tuple(int(m) for m in d.modes))


def loop_rows(name: str, depths, records: int, intact: int, workers: int = 2,
              progress=None) -> list[LoopRow]:
    """The rows of ``records`` records per depth of ``depths`` [m] (> 0) and ``intact``
    intact ones, each from the result cache or computed (records simulated on ``workers``
    processes, diagnosed here)."""
    from concurrent.futures import as_completed

    from hubvib.detection.options import detection_options
    from hubvib.runtime.engines import submit
    from hubvib.runtime.process_pool import worker_pool
    from hubvib.runtime.result_cache import cached_entry, cached_result

    say = progress or (lambda line: None)
    scene = _scene(name)
    items = [(0.0, k) for k in range(intact)] + [(float(d), k) for d in depths
                                                  for k in range(records)]
    # everything a row depends on: the design, the lumped model the mesh curves are scaled
    # to ([reducer.parameters] overrides included), the record, ring, sweep and detection
    key = (scene.design.fingerprint(), scene.params, scene.signal, scene.elastic,
           scene.crack, detection_options(scene))

    def inputs(depth, k):
        return key + (depth, record_seed(depth, k), record_seed(0.0, k, baseline=True))

    rows = {item: cached_entry("record-loop", inputs(*item), (__name__,), LoopRow)
            for item in items}
    todo = [item for item in items if rows[item] is None]
    if todo:
        say(f"{len(items) - len(todo)} of {len(items)} rows cached; simulating "
            f"{len(todo)} records and their baselines")
        with worker_pool(max(1, workers)) as pool:
            baselines = {k: submit(pool, simulate, name, 0.0,
                                   record_seed(0.0, k, baseline=True))
                         for k in sorted({k for _, k in todo})}
            nows = {submit(pool, simulate, name, depth, record_seed(depth, k)): (depth, k)
                    for depth, k in todo}
            diagnoser = _Diagnoser(name)  # while the workers simulate
            for future in as_completed(nows):
                item = nows[future]
                values, baseline = future.result(), baselines[item[1]].result()
                rows[item] = cached_result(
                    "record-loop", inputs(*item), (__name__,),
                    lambda: diagnoser.row(*item, values, baseline), LoopRow)
                say(f"record {1e3 * item[0]:g} mm #{item[1]}: {rows[item].verdict}")
    return [rows[item] for item in items]


def summary(rows: list[LoopRow], family_rate: float) -> dict:
    """Coverage of the intervals over the cracked records (a record without an interval,
    "not explained by a ring crack" or not identified, does not hold its depth) and false
    alarms over the intact ones, each with its binomial 95 % interval (Wilson); per depth
    the same counts."""
    cracked = [r for r in rows if r.depth_m > 0]
    intact = [r for r in rows if r.depth_m == 0]
    covered = sum(bool(r.covered) for r in cracked)  # no interval: the depth not held
    alarms = sum(r.alarm for r in intact)
    per_depth = []
    for depth in sorted({r.depth_m for r in cracked}):
        at = [r for r in cracked if r.depth_m == depth]
        est = [r.estimate_m for r in at if r.estimate_m is not None]
        per_depth.append({
            "depth_m": depth, "records": len(at),
            "crack_indicated": sum(r.alarm for r in at),
            "with_interval": sum(r.covered is not None for r in at),
            "covered": sum(bool(r.covered) for r in at),
            "median_estimate_m": float(np.median(est)) if est else None,
            "median_high_m": (float(np.median([r.high_m for r in at if r.high_m is not None]))
                              if any(r.high_m is not None for r in at) else None)})
    return {"records": len(rows), "cracked": len(cracked), "intact": len(intact),
            "coverage": covered / len(cracked) if cracked else None,
            "coverage_interval": wilson(covered, len(cracked)),
            "covered": covered,
            "verdicts": {v: sum(r.verdict == v for r in cracked)
                         for v in sorted({r.verdict for r in cracked})},
            "false_alarms": alarms, "false_alarm_rate": alarms / len(intact) if intact else None,
            "false_alarm_interval": wilson(alarms, len(intact)),
            "family_rate": family_rate, "per_depth": per_depth}


def wilson(successes: int, n: int, z: float = 1.959964) -> list | None:
    """Wilson score interval of a binomial proportion (95 % by default) [-]."""
    if n == 0:
        return None
    p = successes / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return [max(0.0, centre - half), min(1.0, centre + half)]


def loop_table(data: dict) -> str:
    """Markdown of :func:`main`'s JSON: per true depth the verdicts and the intervals that
    hold it, then the coverage and the false alarms with their binomial intervals."""
    s = data["summary"]
    rows = data["rows"]

    def mm(x):
        return "-" if x is None else f"{1e3 * x:.2f}"

    def share(count, n, interval):
        if not n:
            return f"{count} of {n}"
        return (f"{count} of {n} ({100 * count / n:.0f} %, 95 % binomial interval "
                f"{100 * interval[0]:.0f}-{100 * interval[1]:.0f} %)")

    lines = ["| true depth [mm] | records | crack indicated | interval holds the depth | "
             "median estimate [mm] | median upper bound [mm] |",
             "|---:|---:|---:|---:|---:|---:|"]
    for depth in sorted({r["depth_m"] for r in rows}):
        at = [r for r in rows if r["depth_m"] == depth]
        est = [r["estimate_m"] for r in at if r["estimate_m"] is not None]
        high = [r["high_m"] for r in at if r["high_m"] is not None]
        lines.append(f"| {mm(depth)} | {len(at)} | "
                     f"{sum(r['verdict'] == 'crack indicated' for r in at)} | "
                     f"{sum(bool(r['covered']) for r in at)} | "
                     f"{mm(float(np.median(est)) if est else None)} | "
                     f"{mm(float(np.median(high)) if high else None)} |")
    levels = sorted({r["confidence"] for r in rows if r["confidence"] is not None})
    claimed = "/".join(f"{100 * c:g} %" for c in levels) or "no"
    verdicts = ", ".join(f"{n} {v}" for v, n in s["verdicts"].items())
    return "\n".join(lines) + (
        f"\n\nCracked records: the interval holds the true depth in "
        f"{share(s['covered'], s['cracked'], s['coverage_interval'])}, against the "
        f"{claimed} the intervals claim; verdicts: {verdicts or 'none'}. Intact records "
        f"against the intact baseline of another seed: "
        f"{share(s['false_alarms'], s['intact'], s['false_alarm_interval'])} called a crack "
        f"(the family-wise false-alarm rate is {100 * s['family_rate']:g} %). The records "
        f"of one number k at every depth share their baseline record, so the rows are not "
        f"independent and the binomial intervals are somewhat narrow.\n")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=DEFAULT_SCENE)
    parser.add_argument("--depths-mm", default="1.5,4.5")
    parser.add_argument("--records", type=int, default=10, help="records per depth")
    parser.add_argument("--intact", type=int, default=10, help="intact records")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", type=Path)
    args = parser.parse_args(argv)
    try:
        depths = [round(1e-3 * float(x), 7) for x in args.depths_mm.split(",") if x.strip()]
    except ValueError:
        depths = []
    if not depths or min(depths) <= 0 or len(set(depths)) != len(depths):
        parser.exit(2, f"--depths-mm = {args.depths_mm!r}: allowed distinct crack depths "
                       "> 0 mm, comma-separated (the intact records are --intact)\n")
    if args.records < 0 or args.intact < 0 or args.workers < 1:
        parser.exit(2, "--records and --intact: allowed >= 0; --workers: allowed >= 1\n")
    rows = loop_rows(args.scene, depths, args.records, args.intact, args.workers,
                     progress=lambda line: print(line, file=sys.stderr, flush=True))
    from hubvib.detection.options import detection_options

    options = detection_options(_scene(args.scene))
    data = {"scene": args.scene, "depths_m": depths, "seed_base": SEED_BASE,
            "summary": summary(rows, options.false_alarm_rate),
            "rows": [_row_dict(r) for r in rows]}
    text = json_text(data)
    if args.out:
        write_text(args.out, text + "\n")
    print(text)
    return 0


def _row_dict(row: LoopRow) -> dict:
    out = asdict(row) | {"covered": row.covered}
    out["confidence"] = finite_or_none(row.confidence)
    out["modes"] = list(row.modes)
    return out


if __name__ == "__main__":
    raise SystemExit(main())
