"""Figure: the main job (``hubvib run``, the default scene) in a subprocess from an empty
cache, then again with its FE cases and renders cached; where the fresh run's time goes
(``main_job_stage_seconds``); and the default scene with the rigid ring only
(``[elastic] ring = "rigid"``) from an empty cache, right after the fresh run, so that
``elastic_ring_time_ratio`` is the whole job over the job without the elastic-ring study,
in the same run, and with the crack's faces open (``[elastic] crack_load = "open"``), so that
``loaded_crack_time_ratio`` is what the contact states over the pitch add.
``elastic_ring_cpu_ratio`` is the same ratio of CPU seconds (the run's
process and its workers): on shared cores the wall times follow the other users' load,
the CPU seconds much less."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time

from hubvib.runtime.stage_seconds import ENV

#: the parts of the fresh run in ``main_job_stage_seconds`` (wall seconds in the main
#: process; the FE ring's render runs in a worker beside lumped/detection/plots, and
#: ``render`` is the time the run spends on the renders itself, waiting included)
STAGES = ("fe", "lumped", "detection", "plots", "render", "write", "other")


def main_job(progress=None) -> dict:
    """``hubvib run`` (the default scene) in a subprocess from an empty cache, then again
    with its FE cases and renders cached [s]; the fresh run's parts [s] (``STAGES``:
    ``write`` the tables, report and HTML, ``other`` the rest of the wall time: start-up,
    imports, scene)."""
    say = progress or (lambda line: None)
    out = {"main_job_fresh_seconds": None, "main_job_cached_seconds": None,
           "main_job_stage_seconds": None}
    ratio = {"main_job_rigid_ring_seconds": None, "elastic_ring_time_ratio": None,
             "elastic_ring_cpu_ratio": None, "main_job_open_crack_seconds": None,
             "loaded_crack_time_ratio": None, "loaded_crack_cpu_ratio": None}
    with tempfile.TemporaryDirectory() as folder:
        env = dict(os.environ, HUBVIB_CACHE=os.path.join(folder, "cache"))
        for name in ("fresh", "cached"):
            env[ENV] = os.path.join(folder, f"{name}-stages.json")
            started, cpu = time.perf_counter(), children_cpu_seconds()
            run = subprocess.run([sys.executable, "-m", "hubvib.cli", "run", "--json", "--out",
                                  os.path.join(folder, name)], env=env, capture_output=True,
                                 text=True)
            if run.returncode != 0:
                last = (run.stderr.strip().splitlines() or ["no message"])[-1]
                return dict(out, main_job_skipped=f"hubvib run ({name}) failed: {last}")
            computed = json.loads(run.stdout)["fe_cases_computed"]
            if name == "cached" and computed:
                return dict(out, main_job_skipped=f"the rerun computed {computed} FE cases")
            out[f"main_job_{name}_seconds"] = time.perf_counter() - started
            say(f"main job, {name}: {out[f'main_job_{name}_seconds']:.1f} s")
            if name == "fresh":
                fresh_cpu = _spent(cpu)
                with open(env[ENV], encoding="utf-8") as parts:
                    out["main_job_stage_seconds"] = stage_breakdown(
                        json.load(parts), out["main_job_fresh_seconds"])
                # the baseline next to the fresh run, before the machine's load moves on
                rigid = rigid_ring_seconds(folder, env)
                if rigid is not None:
                    say(f"main job, rigid ring only, empty cache: {rigid[0]:.1f} s")
                    ratio = {"main_job_rigid_ring_seconds": rigid[0],
                             "elastic_ring_time_ratio": out["main_job_fresh_seconds"] / rigid[0],
                             "elastic_ring_cpu_ratio": (None if None in (fresh_cpu, rigid[1])
                                                        else fresh_cpu / rigid[1])}
                opened = open_crack_seconds(folder, env)
                if opened is not None:
                    say(f"main job, crack faces open, empty cache: {opened[0]:.1f} s")
                    ratio |= {"main_job_open_crack_seconds": opened[0],
                              "loaded_crack_time_ratio":
                                  out["main_job_fresh_seconds"] / opened[0],
                              "loaded_crack_cpu_ratio": (None if None in (fresh_cpu, opened[1])
                                                         else fresh_cpu / opened[1])}
    return out | ratio


def children_cpu_seconds() -> float | None:
    """User + system CPU seconds of this process's finished children (and theirs) [s];
    None where the platform does not count them (no ``resource`` module)."""
    try:
        import resource
    except ImportError:
        return None
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _spent(before: float | None) -> float | None:
    now = children_cpu_seconds()
    return None if before is None or now is None else now - before


def rigid_ring_seconds(folder: str, env: dict) -> tuple[float, float | None] | None:
    """The default scene with ``[elastic] ring = "rigid"`` from an empty cache: wall and
    CPU seconds [s] (None when it fails; the CPU seconds None where not counted)."""
    return variant_seconds(folder, env, "rigid", 'ring = "both"', 'ring = "rigid"')


def open_crack_seconds(folder: str, env: dict) -> tuple[float, float | None] | None:
    """The default scene with ``[elastic] crack_load = "open"`` (no contact states: the
    faces free at every moment) from an empty cache: wall and CPU seconds [s]."""
    return variant_seconds(folder, env, "open", 'ring = "both"',
                           'ring = "both"\ncrack_load = "open"')


def variant_seconds(folder: str, env: dict, name: str, old: str, new: str
                    ) -> tuple[float, float | None] | None:
    """The default scene with ``old`` replaced by ``new`` from an empty cache of its own:
    wall and CPU seconds [s] (None when the scene has no ``old`` or the run fails; the
    CPU seconds None where not counted)."""
    from hubvib.studies.scene import DEFAULT_SCENE, shipped_scene_text

    text = shipped_scene_text(DEFAULT_SCENE)
    if old not in text:
        return None
    scene = os.path.join(folder, f"{name}.toml")
    with open(scene, "w", encoding="utf-8") as out:
        out.write(text.replace(old, new))
    env = dict(env, HUBVIB_CACHE=os.path.join(folder, f"cache-{name}"))
    env.pop(ENV, None)
    started, cpu = time.perf_counter(), children_cpu_seconds()
    run = subprocess.run([sys.executable, "-m", "hubvib.cli", "run", scene, "--json", "--out",
                          os.path.join(folder, name)], env=env, capture_output=True, text=True)
    if run.returncode != 0:
        return None
    return time.perf_counter() - started, _spent(cpu)


def stage_breakdown(parts: dict, total: float) -> dict:
    """The run's timed parts (``hubvib.runtime.stage_seconds``; ``write`` holds ``plots``
    and ``render``) as the disjoint ``STAGES`` that add up to ``total`` [s]."""
    get = parts.get
    write = get("write", 0.0)
    out = {"fe": get("fe", 0.0), "lumped": get("lumped", 0.0),
           "detection": get("detection", 0.0), "plots": get("plots", 0.0),
           "render": get("render", 0.0),
           "write": write - get("plots", 0.0) - get("render", 0.0)}
    out["other"] = total - out["fe"] - out["lumped"] - out["detection"] - write
    return {key: round(out[key], 2) for key in STAGES}
