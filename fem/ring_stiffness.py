"""Reduced torsional stiffness c_ru and support stiffness c_r of the ring gear (SI units).

Loads: each of N planets pushes on one ring tooth with a unit force along the
line of action, spread as a uniform traction over that tooth's load patch, so
the torque is ``N F r_b`` exactly.  The supports (``supports`` group) are
clamped.  Tooth deflection is excluded: the ring rotation is read at the base
of each loaded tooth (mean tangential displacement over its two root-land
arcs, a boundary integral independent of the mesh), not at the load
point, so the bending of the tooth itself belongs to the mesh stiffness c_rp.
``c_ru = k_theta / r_b^2`` with ``k_theta = T / theta``, as the lumped model uses it.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.ring_gear import RingGear

from .elasticity import plane_model, solve
from .material import Material
from .solid import solid_model


@dataclass(frozen=True)
class RingStiffness:
    """Result of one ring model.

    Attributes
    ----------
    c_ru : float
        Mean over the carrier positions [N/m].
    c_ru_positions : ndarray
        c_ru at each carrier position [N/m].
    carrier_teeth : ndarray
        Carrier positions as the tooth loaded by planet 1.
    c_r : float
        Support (translational) stiffness, mean of x and y [N/m].
    dofs : int
    seconds : dict
        assembly/loads/solve wall times [s], and the solver used.
    """

    c_ru: float
    c_ru_positions: np.ndarray
    carrier_teeth: np.ndarray
    c_r: float
    dofs: int
    seconds: dict


def tooth_unit_forces(model, teeth) -> list[np.ndarray]:
    """Per tooth: load vectors (2, ndofs) of 1 N along x and along y spread uniformly
    over its load patch (group ``tooth{k}_load``).

    Two facet assemblies serve every tooth: the load of a traction that is
    constant on each facet is ``B_x t_x + B_y t_y``, ``B`` holding one column per facet.
    """
    import scipy.sparse as sp
    import skfem

    groups = [f"tooth{k}_load" for k in teeth]
    patch = model.facet_basis(groups)
    owner = np.repeat(np.arange(len(groups)),
                      [len(model.basis.mesh.boundaries[g]) for g in groups])

    @skfem.Functional
    def size(w):
        return 1.0 + 0.0 * w.x[0]

    patch_size = np.bincount(owner, size.elemental(patch)) * model.thickness  # [m^2]
    per_facet = []
    for i in range(2):
        @skfem.LinearForm
        def traction(v, w, i=i):
            return model.thickness * v[i]

        coo = traction.coo_data(patch)
        facet = np.tile(np.arange(patch.nelems), patch.Nbfun)
        per_facet.append(sp.csr_matrix((coo.data, (coo.indices[0], facet)),
                                       shape=(model.ndofs, patch.nelems)))
    forces = []
    for j in range(len(groups)):
        on_tooth = (owner == j) / patch_size[j]
        forces.append(np.array([b @ on_tooth for b in per_facet]))
    return forces


def planet_teeth(ring: RingGear, carrier_tooth: int, n_planets: int) -> list[int]:
    """Ring teeth loaded by N equally spaced planets when planet 1 is at ``carrier_tooth``."""
    z = ring.teeth
    return [(carrier_tooth + round(i * z / n_planets)) % z for i in range(n_planets)]


def mesh_force_load(model, ring: RingGear, teeth: list[int], force: float) -> np.ndarray:
    """Load vector [N] of ``force`` [N] along the line of action on each of ``teeth``."""
    unit = tooth_unit_forces(model, teeth)
    return force * sum(ring.load_point(k)[1] @ f for k, f in zip(teeth, unit))


def reduced_torsional_stiffness(model, ring: RingGear, teeth: list[int], u: np.ndarray
                                ) -> float:
    """c_ru = T / theta / r_b^2 [N/m] from the displacement ``u`` under 1 N along the line
    of action on each of ``teeth``; theta is the mean rotation of their root lands."""
    rb = ring.gear.base_diameter / 2
    roots = model.facet_basis([f"tooth{k}_root" for k in teeth])
    theta = -model.boundary_means(roots, u)[3]  # clockwise positive
    return len(teeth) * rb / theta / rb ** 2


def ring_stiffness(ring: RingGear, mesh: FEMesh, material: Material = Material(),
                   n_planets: int = 3, carrier_teeth=None, solver: str = "auto"
                   ) -> RingStiffness:
    """c_ru at each carrier position (default: every tooth over one planet pitch) and c_r.

    A plane mesh is solved in plane stress over the face width; a solid mesh
    in 3D, with the loads spread over the tooth's load surface across the face.
    ``solver``: see ``fem.solvers``.
    """
    if isinstance(n_planets, bool) or not isinstance(n_planets, int) or not 1 <= n_planets <= 12:
        raise ValueError(f"n_planets = {n_planets!r}, allowed integers 1..12")
    needed = {"supports"} | {f"tooth{k}_{part}" for k in range(ring.teeth)
                             for part in ("load", "root")}
    missing = sorted(needed - set(mesh.boundaries))
    if missing:
        raise ValueError(f"the mesh lacks the groups c_ru needs: {', '.join(missing[:5])}"
                         + (" ..." if len(missing) > 5 else ""))
    z = ring.teeth
    if carrier_teeth is None:
        carrier_teeth = np.arange(int(math.ceil(z / n_planets)))
    carrier_teeth = np.asarray(carrier_teeth, dtype=int)
    t0 = time.perf_counter()
    if mesh.dim == 2:
        model = plane_model(mesh, material, ring.gear.face_width, "stress")
    else:
        model = solid_model(mesh, material)
    t1 = time.perf_counter()
    unit_force = tooth_unit_forces(model, range(z))
    torque_loads, loaded = [], []
    for s in carrier_teeth:
        teeth = planet_teeth(ring, int(s), n_planets)
        loaded.append(teeth)
        torque_loads.append(sum(ring.load_point(k)[1] @ unit_force[k] for k in teeth))
    translation = [sum(f[axis] for f in unit_force) / z for axis in (0, 1)]
    loads = np.column_stack(torque_loads + translation)
    t2 = time.perf_counter()
    solution = solve(model, loads, ["supports"], solver=solver)
    t3 = time.perf_counter()
    c_ru = [reduced_torsional_stiffness(model, ring, teeth, solution.u[:, column])
            for column, teeth in enumerate(loaded)]
    all_roots = model.facet_basis([f"tooth{k}_root" for k in range(z)])
    c_r = [1.0 / model.boundary_means(all_roots, solution.u[:, column])[1 + axis]
           for column, axis in ((-2, 0), (-1, 1))]
    c_ru = np.array(c_ru)
    return RingStiffness(float(c_ru.mean()), c_ru, carrier_teeth, float(np.mean(c_r)),
                         model.ndofs, {"assembly": t1 - t0, "loads": t2 - t1, "solve": t3 - t2,
                                       "solver": solution.solver})
