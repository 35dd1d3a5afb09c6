"""Benchmark of the FE chain: every timing a ratio against a baseline run in the same process.

    hubvib benchmark [--json] [--quick]      # the figures (``run_benchmark``)
    python -m hubvib.validation.benchmark    # the README's tables of error / size vs time

The machine's cores are shared, so absolute seconds drift by 2-3x from one
minute to the next; each figure is therefore measured beside its baseline,
interleaved, and the ratio is the figure to trust.  Baselines:

- CalculiX 2.20 (``ccx``, SPOOLES, 2 threads) on the same solid mesh and nodal loads;
- the previous FE path (``previous_ring_fe``: an eagerly evaluated scikit-fem basis,
  stiffness triplets sorted and summed by scipy, facet bases by scikit-fem's Newton
  inversion, one facet basis per carrier position, ``K[free][:, free]``, pypardiso's
  CSR interface in 3D), on the same mesh;
- for a crack case, c_ru / c_r and the cracked tooth's compliance assembled and
  factorised separately (``estimate_ring`` + ``engaged_ring_mesh``, as the crack
  sweep did) against one shared factorisation (``estimate_crack_case``);
- the lumped and signal stages report their own baselines
  (``hubvib.lumped.batch.benchmark_batch``, ``hubvib.signal.benchmark_signal``);
- the main job (``hubvib run``, the default scene) run again with its FE cases and
  renders cached, against the same job from an empty cache; the README's test command
  (from a source checkout) is timed beside it.

Timings are measured here, never asserted in tests.
"""
from __future__ import annotations

import math
import time

import numpy as np

#: the 2D c_ru level of the headline figure (``levels.ring_options``): the cheapest found
#: that keeps c_ru within 0.1 % of the finest level
C_RU_2D_SCALE = math.sqrt(2)
#: levels whose finest gives the 2D reference (finer than every level the FE stage uses)
REFERENCE_SCALES = (1 / math.sqrt(2), 0.5, 1 / (2 * math.sqrt(2)))
#: --quick: the default level alone (the error is then a lower bound, and labelled so)
QUICK_REFERENCE_SCALES = (1.0,)
#: crack depth of the crack-case figure [m]
CRACK_DEPTH = 10e-3


# ---- the previous FE path (the baseline) ------------------------------------------------

def previous_assembly(basis, lam: float, mu: float):
    """Elasticity stiffness [N/m] as assembled before the node-block assembly: one
    (row, column, value) triplet per element-matrix entry, sorted and summed by scipy."""
    import scipy.sparse as sp
    import skfem

    scalar = skfem.CellBasis(basis.mesh, basis.elem.elem, quadrature=basis.quadrature)
    dim = basis.mesh.dim()
    n = scalar.Nbfun
    grads = np.stack([scalar.basis[a][0].grad for a in range(n)]).transpose(2, 3, 0, 1)
    dofs = basis.element_dofs.T.reshape(-1, n, dim).astype(np.int32)
    eye = np.eye(dim)
    size = (n * dim) ** 2
    rows = np.empty(basis.mesh.nelements * size, dtype=np.int32)
    cols = np.empty_like(rows)
    data = np.empty(len(rows))
    chunk = 20_000
    for start in range(0, basis.mesh.nelements, chunk):
        block = slice(start, start + chunk)
        g, w = grads[block], scalar.dx[block]
        outer = np.einsum("eqai,eqbj->eaibj", g * w[:, :, None, None], g)
        dot = np.einsum("eaibi->eab", outer)
        k = lam * outer + mu * outer.transpose(0, 1, 4, 3, 2)
        k += mu * dot[:, :, None, :, None] * eye[None, None, :, None, :]
        d = dofs[block]
        out = slice(start * size, start * size + k.size)
        rows[out] = np.broadcast_to(d[:, :, :, None, None], k.shape).ravel()
        cols[out] = np.broadcast_to(d[:, None, None, :, :], k.shape).ravel()
        data[out] = k.ravel()
    return sp.coo_matrix((data, (rows, cols)), shape=(basis.N, basis.N)).tocsr()


def previous_ring_fe(ring, mesh, carrier_teeth=None, n_planets: int = 3,
                     translation: bool = True) -> dict:
    """c_ru at the carrier positions (and c_r) [N/m] on ``mesh`` by the previous FE path,
    with its wall times [s] per stage (``assembly``, ``loads``, ``solve``, ``measure``)."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    import skfem

    from hubvib.fem.material import Material
    from hubvib.fem.ring_stiffness import default_carrier_teeth, planet_teeth
    from hubvib.meshing.to_skfem import to_skfem

    material = Material()
    dim, order = mesh.dim, mesh.order
    carrier_teeth = (default_carrier_teeth(ring, n_planets) if carrier_teeth is None
                     else carrier_teeth)
    t0 = time.perf_counter()
    fe, _ = to_skfem(mesh)
    if dim == 2:
        lam, mu = material.lame("stress")
        thickness = ring.gear.face_width
        scalar, intorder = (skfem.ElementTriP2() if order == 2 else skfem.ElementTriP1(),
                            2 * order)
    else:
        lam, mu = material.lame("strain")
        thickness = 1.0
        scalar, intorder = (skfem.ElementTetP2() if order == 2 else skfem.ElementTetP1(),
                            2 if order == 2 else 1)
    basis = skfem.Basis(fe, skfem.ElementVector(scalar, dim), intorder=intorder)
    K = thickness * previous_assembly(basis, lam, mu)
    t1 = time.perf_counter()

    def facet_basis(groups):
        facets = np.concatenate([fe.boundaries[g] for g in groups])
        return skfem.FacetBasis(fe, basis.elem, facets=facets, intorder=2 * order)

    z = ring.teeth
    groups = [f"tooth{k}_load" for k in range(z)]
    patch = facet_basis(groups)
    owner = np.repeat(np.arange(z), [len(fe.boundaries[g]) for g in groups])
    size = skfem.Functional(lambda w: 1.0 + 0.0 * w.x[0])
    patch_size = np.bincount(owner, size.elemental(patch)) * thickness
    per_facet = []
    for i in range(dim if dim == 2 else 3):
        form = skfem.LinearForm(lambda v, w, i=i: thickness * v[i])
        coo = form.coo_data(patch)
        facet = np.tile(np.arange(patch.nelems), patch.Nbfun)
        per_facet.append(sp.csr_matrix((coo.data, (coo.indices[0], facet)),
                                       shape=(basis.N, patch.nelems)))
    unit = [np.array([b @ ((owner == j) / patch_size[j]) for b in per_facet[:2]])
            for j in range(z)]
    loaded = [planet_teeth(ring, int(s), n_planets) for s in carrier_teeth]
    columns = [sum(ring.load_point(k)[1] @ unit[k] for k in teeth) for teeth in loaded]
    if translation:
        columns += [sum(f[axis] for f in unit) / z for axis in (0, 1)]
    f = np.column_stack(columns)
    t2 = time.perf_counter()
    fixed = np.unique(basis.get_dofs("supports").flatten())
    free = np.setdiff1d(np.arange(basis.N), fixed)
    Kf = K[free][:, free]
    u = np.zeros_like(f)
    if dim == 2:
        u[free] = spla.splu(sp.csc_matrix(Kf), permc_spec="COLAMD").solve(f[free])
    else:
        import pypardiso

        solver = pypardiso.PyPardisoSolver(mtype=2)
        upper = sp.triu(Kf, format="csr")
        solver.factorize(upper)
        u[free] = solver.solve(upper, f[free]).reshape(f[free].shape)
        solver.free_memory(everything=True)
    t3 = time.perf_counter()

    def means(groups, u):
        b = facet_basis(groups)

        @skfem.Functional
        def integrals(w):
            x, y = w.x[0], w.x[1]
            ux, uy = w["u"][0], w["u"][1]
            return np.array([1.0 + 0 * x, ux, uy, (-y * ux + x * uy) / (x * x + y * y)])

        length, *values = integrals.assemble(b, u=b.interpolate(u))
        return [float(v) / length for v in values]

    rb = ring.gear.base_diameter / 2
    c_ru = np.array([len(teeth) * rb / -means([f"tooth{k}_root" for k in teeth],
                                               u[:, column])[2] / rb ** 2
                     for column, teeth in enumerate(loaded)])
    c_r = None
    if translation:
        roots = [f"tooth{k}_root" for k in range(z)]
        c_r = float(np.mean([1.0 / means(roots, u[:, -2])[0],
                             1.0 / means(roots, u[:, -1])[1]]))
    t4 = time.perf_counter()
    return {"c_ru": c_ru, "c_r": c_r, "u": u, "dofs": basis.N,
            "seconds": {"assembly": t1 - t0, "loads": t2 - t1, "solve": t3 - t2,
                        "measure": t4 - t3}}


# ---- the figures of ``hubvib benchmark`` -------------------------------------------------

def ring_2d(scale: float = C_RU_2D_SCALE, reference_scales=REFERENCE_SCALES,
            repeats: int = 2, progress=None) -> dict:
    """2D c_ru of the Raba ring on ``levels.ring_options(scale)``: seconds (mesh + FE, the FE
    the faster of ``repeats`` runs) against the previous FE path on the same mesh,
    interleaved; its error against the reference from the uniform levels
    ``reference_scales`` (``convergence.reference_value``)."""
    from hubvib.fem.ring_stiffness import ring_stiffness
    from hubvib.build import raba118
    from hubvib.meshing.levels import ring_options
    from hubvib.meshing.ring_mesh import ring_mesh

    from .convergence import compute_level, reference_value

    say = progress or (lambda line: None)
    ring = raba118.ring_gear()
    started = time.perf_counter()
    mesh = ring_mesh(ring, None, ring_options(scale))
    mesh_seconds = time.perf_counter() - started
    new, old = [], []
    for _ in range(repeats):
        started = time.perf_counter()
        result = ring_stiffness(ring, mesh)
        new.append(time.perf_counter() - started)
        started = time.perf_counter()
        previous = previous_ring_fe(ring, mesh)
        old.append(time.perf_counter() - started)
    say(f"2D c_ru at scale {scale:.3f}: FE {min(new):.2f} s, previous FE path {min(old):.2f} s")
    levels = []
    for s in reference_scales:
        levels.append(compute_level("c_ru", s))
        say(f"2D c_ru reference level {s:.3f}: {levels[-1]['dofs']} DOFs, "
            f"{levels[-1]['value']:.8e} N/m")
    reference, how = reference_value([r["value"] for r in levels], math.sqrt(2))
    return {
        "c_ru_2d_seconds": mesh_seconds + min(new),
        "c_ru_2d_previous_seconds": mesh_seconds + min(old),
        "c_ru_2d_speedup": (mesh_seconds + min(old)) / (mesh_seconds + min(new)),
        "c_ru_2d_fe_speedup": min(old) / min(new),
        "c_ru_2d_mesh_seconds": mesh_seconds,
        "c_ru_2d_scale": scale, "c_ru_2d_dofs": result.dofs, "c_ru_2d_N_m": result.c_ru,
        "c_ru_2d_rel_error": abs(result.c_ru / reference - 1),
        "c_ru_2d_reference_N_m": reference, "c_ru_2d_reference": how,
        "c_ru_2d_reference_scales": list(reference_scales),
        "c_ru_2d_previous_max_rel_difference": float(
            np.abs(previous["c_ru"] / result.c_ru_positions - 1).max()),
    }


def crack_case(scale: float = 1.0, depth: float = CRACK_DEPTH, progress=None) -> dict:
    """A crack case of the sweep (c_ru, c_r, engaged c_rp ratio; fine and coarse level) with
    one factorisation per level against separate ones, same meshes (made beforehand) and
    the same intact reference curves (computed beforehand)."""
    import functools

    from hubvib.fem.estimate import estimate_crack_case, estimate_ring
    from hubvib.fem.tooth_stiffness import engaged_ring_mesh
    from hubvib.build import raba118
    from hubvib.meshing.crack import Crack
    from hubvib.meshing.levels import scaled_options
    from hubvib.meshing.ring_mesh import ring_mesh

    ring, planet = raba118.ring_gear(), raba118.gear_body("planet")
    crack = Crack(0, depth)
    mesher = functools.lru_cache(maxsize=4)(ring_mesh)

    def separate():
        ring_part = estimate_ring(ring, crack, scale, mesher=mesher)
        fine, coarse = (engaged_ring_mesh(planet, ring, crack, scaled_options(s), mesher=mesher)
                        for s in (scale, 2 * scale))
        return (ring_part.c_ru, ring_part.c_r, fine.mean_ratio, fine.min_ratio,
                abs(fine.mean_ratio - coarse.mean_ratio))

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


def solid_race(options=None, crack=None, folder=None, mesh=None, calculix=True,
               previous=False) -> dict:
    """3D c_ru of the Raba ring (planet 1 on tooth 0) by scikit-fem and by CalculiX on the
    same mesh and nodal loads: times per stage and the agreement of the displacements.
    ``mesh`` (a solid ring mesh) skips the meshing; ``previous`` also times the previous
    FE path on it.  ``speedup`` = CalculiX's time / ours (model, loads, solve, c_ru)."""
    import tempfile
    from pathlib import Path

    from hubvib.fem.elasticity import supported
    from hubvib.fem.ring_stiffness import mesh_force_load, planet_teeth, reduced_torsional_stiffness
    from hubvib.fem.solid import solid_model
    from hubvib.build import raba118
    from hubvib.meshing.ring_mesh_3d import ring_mesh_3d

    from . import calculix as ccx

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
    from hubvib.build import raba118
    from hubvib.meshing.levels import SOLID_LEVELS, solid_options
    from hubvib.meshing.ring_mesh_3d import ring_mesh_3d

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


def peak_memory_gb(argv: list[str]) -> float:
    """Peak resident memory [GB] of the command ``argv``, run alone in a fresh process
    (``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss`` of a wrapper, so that no other
    child of this process counts)."""
    import subprocess
    import sys

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
    import sys
    import tempfile
    from pathlib import Path

    from hubvib.build import raba118
    from hubvib.meshing.levels import SOLID_LEVELS, solid_options
    from hubvib.meshing.ring_mesh_3d import ring_mesh_3d

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
                    "from hubvib.build.raba118 import ring_gear; "
                    "from hubvib.validation.benchmark import solid_race, previous_ring_fe; "
                    f"mesh = FEMesh.load({str(path)!r}); {call}")
            out[f"solid_solve_peak_memory_gb{'' if name == 'ours' else '_previous'}"] = \
                peak_memory_gb([sys.executable, "-c", code])
    out["solid_solve_memory_ratio"] = (out["solid_solve_peak_memory_gb_previous"]
                                       / out["solid_solve_peak_memory_gb"])
    say(f"3D solve alone: peak {out['solid_solve_peak_memory_gb']:.2f} GB, previous path "
        f"{out['solid_solve_peak_memory_gb_previous']:.2f} GB")
    return out


def _other_stage(module: str, function: str, **quick) -> tuple[dict | None, str | None]:
    """Another stage's benchmark dict, or None and why not; ``quick`` keyword arguments
    are passed where the function takes them."""
    import importlib
    import inspect

    try:
        run = getattr(importlib.import_module(module), function)
    except (ImportError, AttributeError) as error:
        return None, f"{module}.{function} not available ({error})"
    accepted = inspect.signature(run).parameters
    return run(**{k: v for k, v in quick.items() if k in accepted}), None


def run_benchmark(quick: bool = False, progress=None) -> dict:
    """Every figure of ``hubvib benchmark`` (SI: seconds, GB, N/m; ratios are baseline time
    over ours).  ``quick`` skips the 3D race and the memory probes, takes the 2D reference
    from the default level (``QUICK_REFERENCE_SCALES``), runs the crack case at scale 2
    and the signal stage over two revolutions."""
    say = progress or (lambda line: None)
    started = time.perf_counter()
    out = {"quick": quick}
    out.update(ring_2d(reference_scales=QUICK_REFERENCE_SCALES if quick else REFERENCE_SCALES,
                       progress=say))
    out.update(crack_case(scale=2.0 if quick else 1.0, progress=say))
    skipped = "skipped (--quick)"
    if quick:
        out.update({key: None for key in (
            "calculix_speedup", "calculix_max_rel_difference", "solid_peak_memory_gb")})
        out["solid_skipped"] = skipped
    else:
        from . import calculix as ccx

        out.update(solid_figures(say))
        if not ccx.available():
            out.update(calculix_speedup=None, calculix_max_rel_difference=None,
                       calculix_skipped="ccx not found: install Debian's calculix-ccx")
        out.update(memory_figures(say))
    lumped, why = _other_stage("hubvib.lumped.batch", "benchmark_batch")
    out["lumped"] = lumped
    out["lumped_points_per_second"] = None if lumped is None else lumped["points_per_second"]
    if why:
        out["lumped_skipped"] = why
    say("lumped: " + (why or f"{out['lumped_points_per_second']:.0f} points/s"))
    # --quick: two carrier revolutions instead of ten (its solve_ivp baseline takes minutes)
    signal, why = _other_stage("hubvib.signal", "benchmark_signal",
                               **({"revolutions": 2} if quick else {}))
    out["signal"] = signal
    if why:
        out["signal_skipped"] = why
    say("signal: " + (why or "done"))
    if quick:
        out.update(main_job_fresh_seconds=None, main_job_cached_seconds=None,
                   tests_seconds=None, main_job_skipped=skipped, tests_skipped=skipped)
    else:
        out.update(main_job(say))
        out.update(readme_test_command(say))
    out["seconds_total"] = time.perf_counter() - started
    return out


def main_job(progress=None) -> dict:
    """``hubvib run`` (the default scene) in a subprocess from an empty cache, then again
    with its FE cases and renders cached [s]."""
    import os
    import subprocess
    import sys
    import tempfile

    import json

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


def readme_test_command(progress=None) -> dict:
    """The README's test command (``python -m pytest``) in the source checkout [s]."""
    import subprocess
    import sys
    from pathlib import Path

    say = progress or (lambda line: None)
    root = Path(__file__).resolve().parents[2]
    if not (root / "tests").is_dir() or not (root / "pyproject.toml").is_file():
        return {"tests_seconds": None, "tests_skipped": "no source checkout (tests/)"}
    started = time.perf_counter()
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"],
                         cwd=root, capture_output=True, text=True)
    seconds = time.perf_counter() - started
    last = (run.stdout.strip().splitlines() or ["no output"])[-1]
    if run.returncode != 0:
        return {"tests_seconds": None, "tests_skipped": f"the tests failed: {last}"}
    say(f"tests: {last}")
    return {"tests_seconds": seconds, "tests_summary": last}


# ---- the README's tables (python -m hubvib.validation.benchmark) ---------------------------

def mesh_table() -> list[dict]:
    """2D Raba ring meshing time against element count, intact and cracked."""
    from hubvib.build import raba118
    from hubvib.meshing.crack import Crack
    from hubvib.meshing.ring_mesh import MeshOptions, ring_mesh

    ring = raba118.ring_gear()
    rows = []
    for size, tooth in ((4e-3, 1e-3), (2e-3, 0.5e-3), (1e-3, 0.25e-3)):
        for crack in (None, Crack(0, 5e-3)):
            options = MeshOptions(size=size, tooth_size=tooth, tip_size=1e-5)
            started = time.perf_counter()
            mesh = ring_mesh(ring, crack, options)
            rows.append({"case": "cracked, tip 10 um" if crack else "intact",
                         "tooth_size_mm": tooth * 1e3, "elements": mesh.info["elements"],
                         "nodes_p2": mesh.info["nodes"], "seconds": time.perf_counter() - started})
    return rows


def solid_mesh_table() -> list[dict]:
    """3D Raba ring (P2 tetrahedra) meshing time against element count, with and without cracks."""
    from dataclasses import replace

    from hubvib.build import raba118

    from hubvib.meshing import measure
    from hubvib.meshing.crack import Crack, CrackFront
    from hubvib.meshing.ring_mesh_3d import SOLID_OPTIONS, ring_mesh_3d

    ring = raba118.ring_gear()
    cases = (("intact", None, CrackFront()),
             ("through-width crack 6 mm", Crack(0, 6e-3), CrackFront()),
             ("semi-elliptic 6 x 16 mm", Crack(0, 6e-3), CrackFront("semi_elliptic", 0.5, 8e-3)))
    rows = []
    for scale in (2.0, 1.0):  # 1.0: the solid defaults (tooth 2 mm, load 1 mm, tip 0.5 mm)
        for name, crack, front in cases:
            options = replace(SOLID_OPTIONS, **{k: scale * getattr(SOLID_OPTIONS, k) for k in (
                "size", "tooth_size", "tip_size", "load_size")})
            tooth = options.tooth_size
            started = time.perf_counter()
            mesh = ring_mesh_3d(ring, crack, front, options)
            seconds = time.perf_counter() - started
            rows.append({"case": name, "tooth_size_mm": tooth * 1e3,
                         "elements": mesh.info["elements"], "nodes_p2": mesh.info["nodes"],
                         "volume_rel_error": measure.volume(mesh) / mesh.info["exact_volume"] - 1,
                         "straightened": mesh.info["straightened"], "seconds": seconds})
    return rows


def annulus_table() -> list[dict]:
    """Annulus in torsion: relative error of k_theta against the exact value, and time."""
    from hubvib.fem.annulus import exact_k_theta, fe_k_theta
    from hubvib.fem.material import Material

    a, b, t, steel = 0.08, 0.1, 0.01, Material()
    exact = exact_k_theta(a, b, t, steel)
    rows = []
    for order in (1, 2):
        for size in (8e-3, 4e-3, 2e-3, 1e-3):
            started = time.perf_counter()
            k, dofs = fe_k_theta(a, b, t, steel, size, order)
            rows.append({"order": order, "size_mm": size * 1e3, "dofs": dofs,
                         "relative_error": abs(k / exact - 1),
                         "seconds": time.perf_counter() - started})
    return rows


def ring_table() -> list[dict]:
    """c_ru and c_r of the Raba ring, intact and with a 10 mm root crack, on the default
    mesh with the error estimated against a mesh twice as coarse (``hubvib stiffness``)."""
    from hubvib.fem.estimate import estimate_ring
    from hubvib.build import raba118
    from hubvib.meshing.crack import Crack

    ring = raba118.ring_gear()
    rows = []
    for name, crack in (("intact", None), ("root crack 10 mm", Crack(0, 10e-3))):
        r = estimate_ring(ring, crack).to_dict()
        rows.append({"case": name, "dofs": r["dofs"], "c_ru": r["c_ru_N_m"],
                     "c_ru_rel_error": r["c_ru_error_N_m"] / r["c_ru_N_m"],
                     "c_r": r["c_r_N_m"], "c_r_rel_error": r["c_r_error_N_m"] / r["c_r_N_m"],
                     "mesh_s": r["seconds_mesh"], "fe_s": r["seconds_fe"]})
    return rows


def solid_table() -> list[dict]:
    """3D c_ru over the solid mesh levels, raced against CalculiX, with the error against
    a finer reference level (Richardson is unreliable here: the levels refine rim, teeth
    and load patches by different factors, and the differences do not shrink
    geometrically)."""
    from hubvib.meshing.levels import SOLID_LEVELS, SOLID_REFERENCE, solid_options

    rows = [dict(level=i, **solid_race(solid_options(*sizes)))
            for i, sizes in enumerate(SOLID_LEVELS)]
    reference = solid_race(solid_options(*SOLID_REFERENCE), calculix=False)
    rows.append(dict(level="reference", **reference))
    for r in rows:
        r["c_ru_rel_error"] = abs(r["c_ru"] / reference["c_ru"] - 1)
    return rows


def _print(title, rows):
    print(f"\n{title}")
    keys = list(rows[0])
    print(" | ".join(keys))
    for row in rows:
        print(" | ".join(f"{row[k]:.3g}" if isinstance(row.get(k), float) else str(row.get(k, ""))
                         for k in keys))


def main():
    _print("Mesh: 2D Raba ring (P2), time vs elements", mesh_table())
    _print("Mesh: 3D Raba ring (P2 tetrahedra), time vs elements", solid_mesh_table())
    _print("Annulus in torsion: error vs time (exact k_theta)", annulus_table())
    _print("Raba ring c_ru (intact), mesh levels", ring_table())
    _print("Raba ring c_ru in 3D (P2 tetrahedra): error vs time, race against CalculiX",
           solid_table())


if __name__ == "__main__":
    main()
