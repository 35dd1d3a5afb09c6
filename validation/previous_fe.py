"""The previous FE path of the ring (the benchmark's baseline): an eagerly evaluated
scikit-fem basis, stiffness triplets sorted and summed by scipy, facet bases by
scikit-fem's Newton inversion, one facet basis per carrier position, ``K[free][:, free]``,
pypardiso's CSR interface in 3D.  It solves the same problem as ``fem.ring_stiffness``
(tests/benchmarks/test_benchmark.py), more slowly."""
from __future__ import annotations

import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from hubvib.fem.material import Material
from hubvib.fem.ring_stiffness import default_carrier_teeth, planet_teeth
from hubvib.meshing.to_skfem import to_skfem

def previous_assembly(basis, lam: float, mu: float):
    """Elasticity stiffness [N/m] as assembled before the node-block assembly: one
    (row, column, value) triplet per element-matrix entry, sorted and summed by scipy."""
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
    import skfem


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
