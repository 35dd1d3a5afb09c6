"""Figure: one plane crack case on the ring by substructures (only the crack's block meshed
and factorised) against the whole ring meshed and factorised, in the same run."""
from __future__ import annotations

import time

from hubvib.reducer import raba118
from hubvib.fem.estimate import estimate_crack_case
from hubvib.meshing.ring_pieces import ring_pieces
from hubvib.meshing.crack import Crack
from hubvib.meshing.ring_mesh import ring_mesh

#: crack depth of the figure [m]
CRACK_DEPTH = 12e-3


def substructure_speedup(scale: float = 1.0, depth: float = CRACK_DEPTH, progress=None) -> dict:
    """A crack case (c_ru, c_r, engaged c_rp ratio on both levels) by substructures against
    the whole-ring path (``mesher=ring_mesh``), alternated twice after one warm-up each (the
    intact pieces and the intact tooth curves, shared by every case of a sweep); the
    fastest of each.  ``substructure_max_rel_difference``: the largest relative difference
    of c_ru and c_r between the two discretisations, beside their own error estimates."""
    ring, planet = raba118.ring_gear(), raba118.gear_body("planet")
    crack = Crack(0, depth)
    runs = {"substructured": lambda: estimate_crack_case(ring, planet, crack, scale,
                                                         mesher=ring_pieces),
            "whole": lambda: estimate_crack_case(ring, planet, crack, scale, mesher=ring_mesh)}
    values = {name: run() for name, run in runs.items()}
    timings: dict = {}
    for name in ("substructured", "whole", "substructured", "whole"):
        started = time.perf_counter()
        values[name] = runs[name]()
        timings.setdefault(name, []).append(time.perf_counter() - started)
    ours, theirs = values["substructured"], values["whole"]
    difference = max(abs(ours.c_ru / theirs.c_ru - 1), abs(ours.c_r / theirs.c_r - 1))
    fast, slow = min(timings["substructured"]), min(timings["whole"])
    (progress or (lambda line: None))(
        f"crack case {depth * 1e3:g} mm at scale {scale:g}: substructured {fast:.2f} s, "
        f"whole ring {slow:.2f} s")
    return {"substructure_seconds_plane": fast, "substructure_previous_seconds_plane": slow,
            "substructure_speedup_plane": slow / fast,
            "substructure_max_rel_difference": difference,
            "substructure_rel_error_estimate": max(ours.c_ru_error / ours.c_ru,
                                                   ours.c_r_error / ours.c_r)}
