"""Figure: peak memory of ``hubvib stiffness --solid`` and of the 3D solve alone, ours and
the previous path's (each in a fresh process)."""
from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

from hubvib.reducer import raba118
from hubvib.meshing.levels import SOLID_LEVELS, solid_options
from hubvib.meshing.ring_mesh_3d import ring_mesh_3d



def peak_memory_gb(argv: list[str]) -> float:
    """Peak resident memory [GB] of the command ``argv``, run alone in a fresh process
    (``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss`` of a wrapper, so that no other
    child of this process counts)."""
    wrapper = ("import resource, subprocess, sys; "
               "done = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL); "
               "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss "
               "if done.returncode == 0 else -done.returncode - 1)")
    out = subprocess.run([sys.executable, "-c", wrapper, *argv], capture_output=True,
                         text=True, check=True)
    kilobytes = int(out.stdout.strip().splitlines()[-1])
    if kilobytes < 0:
        raise RuntimeError(f"{' '.join(argv)} failed (exit {-kilobytes - 1}): {out.stderr[-400:]}")
    return kilobytes / 1e6


def memory_figures(progress=None) -> dict:
    """Peak memory of ``hubvib stiffness --solid`` and of the 3D solve alone, ours and the
    previous path's, on the default solid level (each in its own process)."""
    say = progress or (lambda line: None)
    out = {"solid_peak_memory_gb": peak_memory_gb(
        [sys.executable, "-m", "hubvib.cli", "stiffness", "--solid", "--json"])}
    say(f"hubvib stiffness --solid: peak {out['solid_peak_memory_gb']:.2f} GB")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "solid.npz"
        ring_mesh_3d(raba118.ring_gear(), None,
                     options=solid_options(*SOLID_LEVELS[-1])).save(path)
        for name, call in (("ours", "solid_race(mesh=mesh, calculix=False)"),
                           ("previous", "previous_ring_fe(ring_gear(), mesh, [0], "
                                        "translation=False)")):
            code = ("from hubvib.meshing.fe_mesh import FEMesh; "
                    "from hubvib.reducer.raba118 import ring_gear; "
                    "from hubvib.benchmarks.solid import solid_race; "
                    "from hubvib.validation.previous_fe import previous_ring_fe; "
                    f"mesh = FEMesh.load({str(path)!r}); {call}")
            out[f"solid_solve_peak_memory_gb{'' if name == 'ours' else '_previous'}"] = \
                peak_memory_gb([sys.executable, "-c", code])
    out["solid_solve_memory_ratio"] = (out["solid_solve_peak_memory_gb_previous"]
                                       / out["solid_solve_peak_memory_gb"])
    say(f"3D solve alone: peak {out['solid_solve_peak_memory_gb']:.2f} GB, previous path "
        f"{out['solid_solve_peak_memory_gb_previous']:.2f} GB")
    return out
