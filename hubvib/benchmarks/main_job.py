"""Figure: the main job (``hubvib run``, the default scene) in a subprocess from an empty
cache, then again with its FE cases and renders cached."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time

def main_job(progress=None) -> dict:
    """``hubvib run`` (the default scene) in a subprocess from an empty cache, then again
    with its FE cases and renders cached [s]."""
    say = progress or (lambda line: None)
    out = {"main_job_fresh_seconds": None, "main_job_cached_seconds": None}
    with tempfile.TemporaryDirectory() as folder:
        env = dict(os.environ, HUBVIB_CACHE=os.path.join(folder, "cache"))
        for name in ("fresh", "cached"):
            started = time.perf_counter()
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
    return out
