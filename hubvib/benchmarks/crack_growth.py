"""Figure: the shipped 3D crack-growth scene (``raba118_crack_3d``) in a subprocess from an
empty cache [s], with the share of its time in the solid FE cases."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time

SCENE = "raba118_crack_3d"


def crack_growth_3d(progress=None) -> dict:
    """``hubvib run raba118_crack_3d`` from an empty cache: wall time [s] and the sum of its
    solid FE cases' own times [s] (``fe_seconds`` of the grid; the cases run in parallel,
    so the sum may exceed the wall time)."""
    say = progress or (lambda line: None)
    out = {"crack_growth_3d_seconds": None}
    with tempfile.TemporaryDirectory() as folder:
        env = dict(os.environ, HUBVIB_CACHE=os.path.join(folder, "cache"))
        started = time.perf_counter()
        run = subprocess.run([sys.executable, "-m", "hubvib.cli", "run", SCENE, "--json",
                              "--out", os.path.join(folder, "out")], env=env,
                             capture_output=True, text=True)
        seconds = time.perf_counter() - started
    if run.returncode != 0:
        last = (run.stderr.strip().splitlines() or ["no message"])[-1]
        return dict(out, crack_growth_3d_skipped=f"hubvib run {SCENE} failed: {last}")
    grid = json.loads(run.stdout)["grid"]
    out.update(crack_growth_3d_seconds=seconds, crack_growth_3d_solid_cases=len(grid),
               crack_growth_3d_solid_case_seconds=sum(r["fe_seconds"] for r in grid))
    say(f"3D crack-growth scene: {seconds:.0f} s ({len(grid)} solid cases, "
        f"{out['crack_growth_3d_solid_case_seconds']:.0f} s of case time)")
    return out
