"""Figure: 3D c_ru of the Raba ring, ours against CalculiX 2.20 and against the previous FE
path, same mesh and nodal loads."""
from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from hubvib.reducer import raba118
from hubvib.fem.elasticity import supported
from hubvib.fem.ring_stiffness import mesh_force_load, planet_teeth, reduced_torsional_stiffness
from hubvib.fem.solid import solid_model
from hubvib.meshing.levels import SOLID_LEVELS, solid_options
from hubvib.meshing.ring_mesh_3d import ring_mesh_3d
from hubvib.validation import calculix as ccx
from hubvib.validation.previous_fe import previous_ring_fe

def solid_race(options=None, crack=None, folder=None, mesh=None, calculix=True,
               previous=False) -> dict:
    """3D c_ru of the Raba ring (planet 1 on tooth 0) by scikit-fem and by CalculiX on the
    same mesh and nodal loads: times per stage and the agreement of the displacements.
    ``mesh`` (a solid ring mesh) skips the meshing; ``previous`` also times the previous
    FE path on it.  ``speedup`` = CalculiX's time / ours (model, loads, solve, c_ru)."""
    ring = raba118.ring_gear()
    started = time.perf_counter()
    mesh = mesh or ring_mesh_3d(ring, crack, options=options)
    meshed = time.perf_counter()
    model = solid_model(mesh)
    assembled = time.perf_counter()
    teeth = planet_teeth(ring, 0, 3)
    f = mesh_force_load(model, ring, teeth, 1.0)
    loaded = time.perf_counter()
    system = supported(model, ["supports"])
    factorised = time.perf_counter()
    u = system.solve(f).u
    system.release()
    solved = time.perf_counter()
    c_ru = reduced_torsional_stiffness(model, ring, teeth, u)
    measured = time.perf_counter()
    row = {"dofs": model.ndofs, "c_ru": c_ru, "mesh_s": meshed - started,
           "assembly_s": assembled - meshed, "loads_s": loaded - assembled,
           "factor_s": factorised - loaded, "solve_s": solved - factorised,
           "measure_s": measured - solved, "solver": system.method,
           "skfem_s": measured - meshed}
    if previous:
        before = time.perf_counter()
        old = previous_ring_fe(ring, mesh, carrier_teeth=[0], translation=False)
        row.update(previous_s=time.perf_counter() - before,
                   previous_seconds={k: v for k, v in old["seconds"].items()},
                   previous_speedup=(time.perf_counter() - before) / row["skfem_s"],
                   previous_rel_difference=abs(float(old["c_ru"][0]) / c_ru - 1))
        del old
    if calculix and ccx.available():
        node, component = ccx.node_of_dof(mesh, model.basis)
        forces = np.zeros((len(mesh.points), 3))
        np.add.at(forces, (node, component), f)
        fixed = np.unique(mesh.boundaries["supports"])
        with tempfile.TemporaryDirectory() as tmp:
            work = Path(folder or tmp)
            deck = ccx.write_deck(work / "ring.inp", mesh, fixed, forces,
                                  model.material.E, model.material.nu)
            displacement, seconds = ccx.run(deck)
        v = displacement[node, component]
        row.update(ccx_s=seconds, ccx_c_ru=reduced_torsional_stiffness(model, ring, teeth, v),
                   max_rel_difference=float(np.abs(v - u).max() / np.abs(u).max()),
                   speedup=seconds / row["skfem_s"])
    return row


def solid_figures(progress=None) -> dict:
    """The 3D race on the default solid level: ours against CalculiX and against the
    previous FE path, same mesh and loads; ours and CalculiX twice, interleaved, each the
    faster of its two runs."""
    say = progress or (lambda line: None)
    mesh = ring_mesh_3d(raba118.ring_gear(), None, options=solid_options(*SOLID_LEVELS[-1]))
    first = solid_race(mesh=mesh, calculix=True, previous=True)
    second = solid_race(mesh=mesh, calculix=True)
    ours = min(first["skfem_s"], second["skfem_s"])
    say(f"3D c_ru, {first['dofs']} DOFs: ours {first['skfem_s']:.1f} / {second['skfem_s']:.1f} s,"
        f" CalculiX {first.get('ccx_s', 0):.1f} / {second.get('ccx_s', 0):.1f} s, previous path "
        f"{first['previous_s']:.1f} s")
    out = {"solid_dofs": first["dofs"], "solid_seconds": ours,
           "solid_previous_seconds": first["previous_s"],
           "solid_previous_speedup": first["previous_s"] / ours,
           "solid_assembly_seconds": min(first["assembly_s"], second["assembly_s"]),
           "solid_previous_assembly_seconds": first["previous_seconds"]["assembly"],
           "solid_factor_solve_seconds": min(first["factor_s"] + first["solve_s"],
                                             second["factor_s"] + second["solve_s"]),
           "solid_previous_solve_seconds": first["previous_seconds"]["solve"],
           "solid_c_ru_N_m": first["c_ru"],
           "solid_previous_rel_difference": first["previous_rel_difference"]}
    if "ccx_s" in first:
        calculix = min(first["ccx_s"], second["ccx_s"])
        out.update(calculix_seconds=calculix, calculix_speedup=calculix / ours,
                   calculix_max_rel_difference=first["max_rel_difference"],
                   calculix_c_ru_rel_difference=abs(first["ccx_c_ru"] / first["c_ru"] - 1))
    return out
