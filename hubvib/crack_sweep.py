"""FE stage of a crack sweep: c_ru, c_r and c_rp of the cracked ring, one case per depth (SI).

``c_rp`` is the ring-planet mesh stiffness averaged over the engagement of
the cracked tooth, as a ratio to the same window intact; the tooth model
loads tooth 0, so the crack is moved there (the tooth's compliance relative
to its root lands does not depend on where the supports are).

Every case is cached as JSON under ``$HUBVIB_CACHE/stiffness`` by a hash of
what defines it (ring, crack, mesh accuracy, mesher version), written
atomically when it finishes.  A sweep killed at any point resumes without
losing or recomputing a finished case.  Cases run in worker processes.
"""
from __future__ import annotations

import json
import math
import sys
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import asdict, dataclass
from multiprocessing import get_context
from pathlib import Path

from .output import write_json

STARTS = ("root", "rim")
APPLY = ("series", "ratio", "direct")
#: mesh size multiplier of each accuracy setting (1.0: c_ru to ~0.3 %, see README)
ACCURACY = {"default": 1.0, "fast": 2.0}


@dataclass(frozen=True)
class CrackSweep:
    """Crack depths to analyse in the ring gear of the reducer.

    Parameters
    ----------
    depths : tuple of float
        Crack depths [m] along the path, ascending, starting at 0 (the intact ring).
    tooth, start, angle
        Tooth index, ``"root"`` or ``"rim"``, direction from the radial [rad].
    apply : str
        How FE enters the lumped model: ``"series"`` puts the ring mounting in series
        with the FE ring body, ``1/c = 1/c_mount + 1/c_body(depth)``; ``"ratio"`` scales
        the preset's ``c_ru`` and ``c_r`` by FE(depth) / FE(0) (the paper's hypothesis:
        the whole compliance is the ring body, an upper bound of the effect);
        ``"direct"`` uses the FE values themselves (a rigid mounting).
    c_ru_mount, c_r_mount : float or None
        With ``"series"``: the mounting's torsional and radial stiffness [N/m]; ``None``
        identifies it so that the intact total equals the preset's ``c_ru`` / ``c_r``.
    accuracy : str
        ``"default"`` or ``"fast"`` (element sizes doubled).
    workers : int
        Worker processes for the FE cases (1 = in this process).
    """

    depths: tuple[float, ...]
    tooth: int = 0
    start: str = "root"
    angle: float = 0.0
    apply: str = "series"
    accuracy: str = "default"
    workers: int = 2
    c_ru_mount: float | None = None
    c_r_mount: float | None = None


def case_key(sweep: CrackSweep, depth: float) -> str:
    from hubvib.meshing import cache, raba118

    return cache.key("ring-stiffness", raba118.ring_gear(), crack_of(sweep, depth),
                     ACCURACY[sweep.accuracy], "c_rp engaged")


def crack_of(sweep: CrackSweep, depth: float):
    from hubvib.meshing.crack import Crack

    return Crack(sweep.tooth, float(depth), sweep.angle, sweep.start)


def fe_case(sweep: CrackSweep, depth: float) -> dict:
    """c_ru, c_r, c_rp with error estimate and timing for one depth (runs in a worker).

    c_ru and the cracked tooth's c_rp are computed on the same ring meshes."""
    import functools
    import time

    from hubvib.meshing import raba118
    from hubvib.meshing.ring_mesh import ring_mesh

    from hubvib.fem.estimate import estimate_ring

    started = time.perf_counter()
    scale = ACCURACY[sweep.accuracy]
    mesher = functools.lru_cache(maxsize=2)(ring_mesh)
    result = dict(estimate_ring(raba118.ring_gear(), crack_of(sweep, depth), scale,
                                mesher=mesher).to_dict(),
                  depth_m=float(depth))
    engaged = {"c_rp_engaged_ratio": 1.0, "c_rp_engaged_ratio_error": 0.0,
               "c_rp_engaged_min_ratio": 1.0}
    if depth > 0:
        from dataclasses import replace

        from hubvib.fem.tooth_stiffness import engaged_ring_mesh

        from hubvib.meshing.levels import scaled_options

        crack = replace(crack_of(sweep, depth), tooth=0)
        planet, ring = raba118.gear_body("planet"), raba118.ring_gear()
        fine = engaged_ring_mesh(planet, ring, crack, scaled_options(scale), mesher=mesher)
        coarse = engaged_ring_mesh(planet, ring, crack, scaled_options(2 * scale),
                                   mesher=mesher)
        engaged = {"c_rp_engaged_ratio": fine.mean_ratio,
                   "c_rp_engaged_ratio_error": abs(fine.mean_ratio - coarse.mean_ratio),
                   "c_rp_engaged_min_ratio": fine.min_ratio}
    return result | engaged | {"seconds_total": time.perf_counter() - started}


def cache_folder() -> Path:
    from hubvib.meshing.cache import root_folder

    return root_folder() / "stiffness"


def run_fe_cases(sweep: CrackSweep, progress: bool = True) -> tuple[list[dict], int]:
    """Every depth's FE result, from the cache or computed; returns them and how many ran."""
    folder = cache_folder()
    paths = {d: folder / f"{case_key(sweep, d)}.json" for d in sweep.depths}
    todo = [d for d, p in paths.items() if not _readable(p)]
    bar = _progress(len(sweep.depths), len(sweep.depths) - len(todo), progress)
    try:
        if sweep.workers == 1 or len(todo) <= 1:
            for depth in todo:
                _store(paths[depth], sweep, fe_case(sweep, depth))
                bar.update(1)
        else:
            with ProcessPoolExecutor(min(sweep.workers, len(todo)),
                                     mp_context=get_context("spawn")) as pool:
                futures = {pool.submit(fe_case, sweep, d): d for d in todo}
                for future in as_completed(futures):
                    _store(paths[futures[future]], sweep, future.result())
                    bar.update(1)
    finally:
        bar.close()
    return [json.loads(paths[d].read_text()) for d in sweep.depths], len(todo)


def _store(path: Path, sweep: CrackSweep, result: dict) -> None:
    write_json(path, dict(result, sweep=asdict(sweep) | {"depths": None, "c_ru_mount": None,
                                                         "c_r_mount": None}))


def _readable(path: Path) -> bool:
    try:
        data = json.loads(path.read_text())
    except (OSError, ValueError):
        return False
    return all(math.isfinite(data.get(key, math.nan))
               for key in ("c_ru_N_m", "c_rp_engaged_ratio"))


def _progress(total: int, done: int, enabled: bool):
    from tqdm import tqdm

    return tqdm(total=total, initial=done, desc="FE crack cases", unit="case",
                disable=not enabled or not sys.stderr.isatty(), file=sys.stderr)
