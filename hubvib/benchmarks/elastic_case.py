"""Figure: one elastic-ring crack case (``hubvib.elastic.cases.elastic_case``: the coupled
spectra of the reduced ring, planet 1 away from and on the cracked tooth) beside the
whole-ring plane crack case of the same crack (``fem.estimate.estimate_crack_case`` with
``ring_mesh``: c_ru, c_r and the engaged c_rp on three levels), in the same run."""
from __future__ import annotations

import time

from hubvib.benchmarks.substructure import CRACK_DEPTH

#: why the elastic ring has no substructured figure of its own
ELASTIC_WHOLE_RING = ("the elastic ring is reduced from the whole ring's mesh "
                      "(fem.ring_body); its baseline is the whole-ring plane crack case")


def elastic_case_figures(depth: float = CRACK_DEPTH, progress=None) -> dict:
    """``elastic_case_seconds``: one elastic-ring crack case at ``depth`` [m] on the crack
    study's elastic scene, the fastest of two after a warm-up (the intact tooth curves);
    ``elastic_case_baseline_seconds``: the whole-ring plane crack case of the same crack,
    alternated with it; ``elastic_case_ratio``: the first over the second."""
    from hubvib.design import preset_design
    from hubvib.elastic.cases import elastic_case
    from hubvib.elastic.options import ElasticScene
    from hubvib.elastic.rest import rest_stiffness
    from hubvib.fem.estimate import estimate_crack_case
    from hubvib.meshing.crack import Crack
    from hubvib.meshing.ring_mesh import ring_mesh
    from hubvib.reducer.stages import gear_body, material, ring_gear

    design = preset_design("raba118")
    scene = ElasticScene(ring="elastic")
    crack = Crack(0, depth)
    k_rest = rest_stiffness(design, scene.options.rest)
    ring, planet = ring_gear(design), gear_body(design, "planet")
    runs = {"elastic": lambda: elastic_case(design, crack, scene, k_rest),
            "whole": lambda: estimate_crack_case(ring, planet, crack, mesher=ring_mesh,
                                                 material=material(design),
                                                 n_planets=design.n_planets)}
    for run in runs.values():
        run()
    timings: dict = {}
    for name in ("elastic", "whole", "elastic", "whole"):
        started = time.perf_counter()
        runs[name]()
        timings.setdefault(name, []).append(time.perf_counter() - started)
    ours, baseline = min(timings["elastic"]), min(timings["whole"])
    (progress or (lambda line: None))(
        f"elastic crack case {depth * 1e3:g} mm: {ours:.2f} s, whole-ring plane crack case "
        f"{baseline:.2f} s")
    return {"elastic_case_seconds": ours, "elastic_case_baseline_seconds": baseline,
            "elastic_case_ratio": ours / baseline, "elastic_case_baseline": ELASTIC_WHOLE_RING}
