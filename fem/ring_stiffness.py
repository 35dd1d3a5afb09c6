"""Reduced torsional stiffness c_ru and support stiffness c_r of the ring gear (SI units).

Loads: each of N planets pushes on one ring tooth with a unit force along the
line of action, spread as a uniform traction over that tooth's load patch, so
the torque is ``N F r_b`` exactly.  The supports (``supports`` group) are
clamped.  Tooth deflection is excluded: the ring rotation is read at the base
of each loaded tooth (mean tangential displacement over its two root-land
arcs, a boundary integral independent of the mesh), not at the load
point, so the bending of the tooth itself belongs to the mesh stiffness c_rp.
``c_ru = k_theta / r_b^2`` with ``k_theta = T / theta``, as the lumped model uses it.

Loads and measurements are sparse maps built once per model (``tooth_forces``,
``root_lands``): every carrier position is a load column of one factorisation.
The same solution also gives the work-conjugate c_ru (with its exact rim / tooth split)
and c_r (``fem.ring_work``, ``RingStiffness.work``); the lumped model uses their rim parts
``c_ru_rim``, ``c_r_rim`` (``fem.estimate``; docs/fe_accuracy.md, "Work-conjugate ring
stiffnesses"), the root-land readings here are a secondary output.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.ring_gear import RingGear

from .elasticity import plane_model, solve
from .material import Material
from .ring_work import RingWork, ring_work
from .solid import solid_model
from .tooth_solid import SolidToothCompliance, solid_tooth_compliance, solid_tooth_probe


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
        assembly/loads/solve/measure wall times [s], and the solver used.
    work : fem.ring_work.RingWork or None
        The work-conjugate c_ru (with its rim and tooth parts) and c_r of the same
        solution; ``c_ru`` and ``c_r`` above are the root-land readings.
    """

    c_ru: float
    c_ru_positions: np.ndarray
    carrier_teeth: np.ndarray
    c_r: float
    dofs: int
    seconds: dict
    work: RingWork | None = None
    tooth: SolidToothCompliance | None = None


@dataclass(frozen=True, eq=False)
class ToothForces:
    """Forces spread uniformly over the load patches (groups ``tooth{k}_load``) of ``teeth``.

    Two facet assemblies serve every tooth and every load case: the load of a traction
    that is constant on each facet is ``B_x t_x + B_y t_y``, ``B`` holding one column per
    facet (``per_facet``); ``owner`` gives each facet's tooth (index into ``teeth``) and
    ``size`` each patch's area [m^2] (length times thickness in a plane model).
    """

    teeth: tuple
    per_facet: tuple
    owner: np.ndarray
    size: np.ndarray

    def loads(self, forces: np.ndarray) -> np.ndarray:
        """Load vectors (ndofs, cases) [N] of the forces ``forces`` (teeth, 2, cases) [N]:
        x and y components on each tooth in each load case."""
        forces = np.asarray(forces, dtype=float)
        on_facet = forces[self.owner] / self.size[self.owner][:, None, None]
        return sum(b @ on_facet[:, i, :] for i, b in enumerate(self.per_facet))

    def resultants(self, modes: np.ndarray) -> np.ndarray:
        """(teeth, 2, modes): work of 1 N along x and along y on each tooth's patch on each
        displacement field ``modes`` (ndofs, modes), e.g. the rigid-body modes [N m/m]."""
        on_facet = np.stack([b.T @ modes for b in self.per_facet], axis=1)  # (facets, 2, m)
        total = np.zeros((len(self.teeth),) + on_facet.shape[1:])
        np.add.at(total, self.owner, on_facet)
        return total / self.size[:, None, None]


def _tooth_groups(model, teeth, part: str):
    """The facets of groups ``tooth{k}_{part}`` of ``teeth`` in one facet basis: the teeth
    as a tuple, the basis, each facet's index in ``teeth`` and each group's length [m]
    (plane) or area [m^2] (solid)."""
    import skfem

    teeth = tuple(int(k) for k in teeth)
    groups = [f"tooth{k}_{part}" for k in teeth]
    basis = model.facet_basis(groups)
    owner = np.repeat(np.arange(len(groups)),
                      [len(model.basis.mesh.boundaries[g]) for g in groups])

    @skfem.Functional
    def size(w):
        return 1.0 + 0.0 * w.x[0]

    return teeth, basis, owner, np.bincount(owner, size.elemental(basis),
                                            minlength=len(groups))


def tooth_forces(model, teeth) -> ToothForces:
    """``ToothForces`` of ``teeth`` on ``model`` (one facet basis for all of them)."""
    import skfem

    teeth, patch, owner, size = _tooth_groups(model, teeth, "load")
    patch_size = size * model.thickness  # [m^2]
    per_facet = []
    for i in range(2):
        @skfem.LinearForm
        def traction(v, w, i=i):
            return model.thickness * v[i]

        coo = traction.coo_data(patch)
        facet = np.tile(np.arange(patch.nelems), patch.Nbfun)
        per_facet.append(sp.csr_matrix((coo.data, (coo.indices[0], facet)),
                                       shape=(model.ndofs, patch.nelems)))
    return ToothForces(teeth, tuple(per_facet), owner, patch_size)


def planet_teeth(ring: RingGear, carrier_tooth: int, n_planets: int) -> list[int]:
    """Ring teeth loaded by N equally spaced planets when planet 1 is at ``carrier_tooth``."""
    z = ring.teeth
    return [(carrier_tooth + round(i * z / n_planets)) % z for i in range(n_planets)]


def mesh_force_load(model, ring: RingGear, teeth: list[int], force: float) -> np.ndarray:
    """Load vector [N] of ``force`` [N] along the line of action on each of ``teeth``."""
    forces = tooth_forces(model, sorted(set(teeth)))
    along = np.zeros((len(forces.teeth), 2, 1))
    for k in teeth:
        along[forces.teeth.index(k), :, 0] += force * ring.load_point(k)[1]
    return forces.loads(along)[:, 0]


@dataclass(frozen=True, eq=False)
class RootLands:
    """Boundary integrals over the root lands of each of ``teeth``, as sparse functionals.

    Attributes
    ----------
    teeth : tuple of int
    size : ndarray
        Length [m] (plane) or area [m^2] (solid) of each tooth's root lands.
    u_x, u_y, rotation : scipy.sparse.csr_matrix (teeth, ndofs)
        Row k applied to a displacement [m] gives the integral over tooth k's root
        lands of u_x, u_y [m^2 or m^3] and of the rotation about the ring axis
        u_theta / r [rad m or rad m^2], counter-clockwise positive.
    """

    teeth: tuple
    size: np.ndarray
    u_x: object
    u_y: object
    rotation: object

    def rows(self, teeth) -> np.ndarray:
        index = {k: i for i, k in enumerate(self.teeth)}
        return np.array([index[k] for k in teeth])

    def mean_rotation(self, teeth, u: np.ndarray):
        """Mean rotation [rad] over the root lands of ``teeth`` (together) of the
        displacement ``u`` (ndofs,) or of each column of (ndofs, k)."""
        rows = self.rows(teeth)
        return (self.rotation[rows] @ u).sum(axis=0) / self.size[rows].sum()

    def mean_translation(self, u: np.ndarray) -> tuple:
        """Mean u_x, u_y [m] over all the root lands."""
        total = self.size.sum()
        return (self.u_x @ u).sum(axis=0) / total, (self.u_y @ u).sum(axis=0) / total


def root_lands(model, teeth) -> RootLands:
    """``RootLands`` of ``teeth`` (groups ``tooth{k}_root``): one facet basis for all."""
    import skfem

    teeth, lands, owner, size = _tooth_groups(model, teeth, "root")
    per_tooth = sp.csr_matrix((np.ones(len(owner)), (np.arange(len(owner)), owner)),
                              shape=(lands.nelems, len(teeth)))

    def functional(density):
        form = skfem.LinearForm(lambda v, w: density(v, w.x))
        coo = form.coo_data(lands)
        facet = np.tile(np.arange(lands.nelems), lands.Nbfun)
        per_facet = sp.csr_matrix((coo.data, (facet, coo.indices[0])),
                                  shape=(lands.nelems, model.ndofs))
        return (per_tooth.T @ per_facet).tocsr()

    return RootLands(
        teeth, size,
        functional(lambda v, x: v[0]), functional(lambda v, x: v[1]),
        functional(lambda v, x: (-x[1] * v[0] + x[0] * v[1]) / (x[0] ** 2 + x[1] ** 2)))


def reduced_torsional_stiffness(model, ring: RingGear, teeth: list[int], u: np.ndarray,
                                lands: RootLands | None = None):
    """c_ru = T / theta / r_b^2 [N/m] from the displacement ``u`` under 1 N along the line
    of action on each of ``teeth``; theta is the mean rotation of their root lands.

    ``u`` (ndofs,) gives a float, (ndofs, k) an array; ``lands`` (covering ``teeth``)
    saves building the boundary functionals again."""
    rb = ring.gear.base_diameter / 2
    lands = lands or root_lands(model, teeth)
    theta = -lands.mean_rotation(teeth, u)  # clockwise positive
    c_ru = len(teeth) * rb / theta / rb ** 2
    return float(c_ru) if np.ndim(c_ru) == 0 else c_ru


@dataclass(frozen=True, eq=False)
class RingLoads:
    """The load columns of ``ring_stiffness`` and what they mean.

    ``loads`` (ndofs, positions + 2) [N]: 1 N along the line of action on each tooth of
    ``loaded[i]`` (column i, one per carrier position), then 1 N spread over all teeth
    along x and along y (the support stiffness).
    """

    loads: np.ndarray
    loaded: list
    carrier_teeth: np.ndarray
    forces: ToothForces | None = None


def ring_loads(model, ring: RingGear, carrier_teeth, n_planets: int) -> RingLoads:
    """Torque load of each carrier position and the two translation loads."""
    z = ring.teeth
    loaded = [planet_teeth(ring, int(s), n_planets) for s in carrier_teeth]
    forces = np.zeros((z, 2, len(loaded) + 2))
    for column, teeth in enumerate(loaded):
        for k in teeth:
            forces[k, :, column] += ring.load_point(k)[1]
    forces[:, 0, -2] = forces[:, 1, -1] = 1.0 / z
    spread = tooth_forces(model, range(z))
    return RingLoads(spread.loads(forces), loaded, np.asarray(carrier_teeth, dtype=int),
                     spread)


def ring_response(model, ring: RingGear, loads: RingLoads, u: np.ndarray
                  ) -> tuple[np.ndarray, float]:
    """c_ru at each carrier position and c_r [N/m] from the displacements ``u``
    (ndofs, columns of ``loads.loads``)."""
    lands = root_lands(model, range(ring.teeth))
    c_ru = np.array([reduced_torsional_stiffness(model, ring, teeth, u[:, column], lands)
                     for column, teeth in enumerate(loads.loaded)])
    positions = len(loads.loaded)
    means = lands.mean_translation(u[:, positions:positions + 2])
    c_r = float(np.mean([1.0 / means[0][0], 1.0 / means[1][1]]))
    return c_ru, c_r


def check_ring_input(ring: RingGear, mesh: FEMesh, n_planets: int) -> None:
    """Raise ValueError for a planet count out of range or a mesh without the ring groups."""
    if isinstance(n_planets, bool) or not isinstance(n_planets, int) or not 1 <= n_planets <= 12:
        raise ValueError(f"n_planets = {n_planets!r}, allowed integers 1..12")
    needed = {"supports"} | {f"tooth{k}_{part}" for k in range(ring.teeth)
                             for part in ("load", "root")}
    missing = sorted(needed - set(mesh.boundaries))
    if missing:
        raise ValueError(f"the mesh lacks the groups c_ru needs: {', '.join(missing[:5])}"
                         + (" ..." if len(missing) > 5 else ""))


def default_carrier_teeth(ring: RingGear, n_planets: int) -> np.ndarray:
    """Every tooth over one planet pitch."""
    return np.arange(int(math.ceil(ring.teeth / n_planets)))


def ring_stiffness(ring: RingGear, mesh: FEMesh, material: Material = Material(),
                   n_planets: int = 3, carrier_teeth=None, solver: str = "auto",
                   cell_scale=None, tooth=None) -> RingStiffness:
    """c_ru at each carrier position (default: every tooth over one planet pitch) and c_r.

    A plane mesh is solved in plane stress over the face width; a solid mesh
    in 3D, with the loads spread over the tooth's load surface across the face.
    ``solver``: see ``fem.solvers``.  One factorisation serves every load column.
    ``cell_scale`` (solid meshes: one stiffness factor per cell) measures how much the
    result depends on some cells.  ``tooth`` (solid meshes: a
    ``fem.tooth_solid.SolidToothLoad``) adds that tooth's line loads as further columns of
    the same factorisation; ``RingStiffness.tooth`` is then its compliance.
    """
    check_ring_input(ring, mesh, n_planets)
    if tooth is not None and mesh.dim != 3:
        raise ValueError("tooth: the line-load tooth compliance needs a solid mesh")
    if carrier_teeth is None:
        carrier_teeth = default_carrier_teeth(ring, n_planets)
    t0 = time.perf_counter()
    model = ring_model(ring, mesh, material, cell_scale)
    t1 = time.perf_counter()
    loads = ring_loads(model, ring, carrier_teeth, n_planets)
    probe = solid_tooth_probe(ring, model, tooth) if tooth is not None else None
    columns = loads.loads if probe is None else np.column_stack([loads.loads, probe.loads])
    t2 = time.perf_counter()
    solution = solve(model, columns, ["supports"], solver=solver)
    t3 = time.perf_counter()
    ring_u = solution.u[:, :loads.loads.shape[1]]
    c_ru, c_r = ring_response(model, ring, loads, ring_u)
    work = ring_work(model, ring, loads, ring_u, loads.forces,
                     root_lands(model, range(ring.teeth)))
    measured = (solid_tooth_compliance(probe, solution.u[:, loads.loads.shape[1]:])
                if probe is not None else None)
    return RingStiffness(float(c_ru.mean()), c_ru, loads.carrier_teeth, c_r, model.ndofs,
                         {"assembly": t1 - t0, "loads": t2 - t1, "solve": t3 - t2,
                          "measure": time.perf_counter() - t3, "solver": solution.solver},
                         work, measured)


def ring_model(ring: RingGear, mesh: FEMesh, material: Material = Material(),
               cell_scale=None):
    """Plane-stress model over the face width (plane mesh) or solid model (3D mesh, each
    cell's stiffness times ``cell_scale`` if given)."""
    if mesh.dim == 2:
        if cell_scale is not None:
            raise ValueError("cell_scale applies to solid meshes only")
        return plane_model(mesh, material, ring.gear.face_width, "stress")
    return solid_model(mesh, material, cell_scale)
