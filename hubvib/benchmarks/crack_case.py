"""Figure: one crack case of the sweep with one factorisation per level against separate
ones (same meshes, same intact reference curves)."""
from __future__ import annotations

import functools
import time

from hubvib.reducer import raba118
from hubvib.fem.estimate import (PLANE_LEVELS, estimate_crack_case, estimate_ring,
                                 level_error, level_ratios)
from hubvib.fem.tooth_stiffness import engaged_ring_mesh
from hubvib.meshing.crack import Crack
from hubvib.meshing.levels import scaled_options
from hubvib.meshing.ring_mesh import ring_mesh

#: crack depth of the crack-case figure [m]
CRACK_DEPTH = 10e-3


def crack_case(scale: float = 1.0, depth: float = CRACK_DEPTH, progress=None) -> dict:
    """A crack case of the sweep (c_ru, c_r, engaged c_rp ratio; three levels) with
    one factorisation per level against separate ones, same meshes (made beforehand) and
    the same intact reference curves (computed beforehand)."""
    ring, planet = raba118.ring_gear(), raba118.gear_body("planet")
    crack = Crack(0, depth)
    mesher = functools.lru_cache(maxsize=4)(ring_mesh)

    def separate():
        # the crack case's c_ru, c_r: the work-conjugate rim parts
        ring_part = estimate_ring(ring, crack, scale, mesher=mesher, definition="rim")
        options = [scaled_options(factor * scale) for factor in PLANE_LEVELS]
        levels = [engaged_ring_mesh(planet, ring, crack, o, mesher=mesher) for o in options]
        ratios = tuple(level.mean_ratio for level in levels)
        return (ring_part.c_ru, ring_part.c_r, levels[-1].mean_ratio, levels[-1].min_ratio,
                level_error(ratios, level_ratios(options)).error)

    def shared():
        e = estimate_crack_case(ring, planet, crack, scale, mesher=mesher)
        return (e.c_ru, e.c_r, e.c_rp_engaged_ratio, e.c_rp_engaged_min_ratio,
                e.c_rp_engaged_ratio_error)

    separate()  # meshes and intact curves, so that both timings are FE only
    timings = {}
    for name, run in (("shared", shared), ("separate", separate), ("shared", shared),
                      ("separate", separate)):
        started = time.perf_counter()
        values = run()
        timings.setdefault(name, []).append(time.perf_counter() - started)
        if name == "shared":
            ours = values
        else:
            theirs = values
    difference = max(abs(a / b - 1) for a, b in zip(ours[:4], theirs[:4]))
    (progress or (lambda line: None))(
        f"crack case {depth * 1e3:g} mm at scale {scale:g}: shared {min(timings['shared']):.2f} s,"
        f" separate {min(timings['separate']):.2f} s")
    return {"crack_case_seconds": min(timings["shared"]),
            "crack_case_previous_seconds": min(timings["separate"]),
            "crack_case_speedup": min(timings["separate"]) / min(timings["shared"]),
            "crack_case_max_rel_difference": difference, "crack_case_scale": scale}
