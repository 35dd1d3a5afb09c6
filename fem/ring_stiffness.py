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

from meshing.fe_mesh import FEMesh
from meshing.ring_gear import RingGear

from .elasticity import PlaneModel, plane_model, solve
from .material import Material


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
        mesh/assembly/solve wall times [s].
    """

    c_ru: float
    c_ru_positions: np.ndarray
    carrier_teeth: np.ndarray
    c_r: float
    dofs: int
    seconds: dict


def _mean_rotation(model: PlaneModel, groups: list[str], u: np.ndarray) -> float:
    """Mean rotation [rad] (counter-clockwise positive) of the named boundaries:
    integral of u_theta / r over their length divided by the length."""
    import skfem

    fe = model.basis.mesh
    facets = np.concatenate([fe.boundaries[g] for g in groups])
    fb = skfem.FacetBasis(fe, model.basis.elem, facets=facets, intorder=2 * model.mesh.order)

    @skfem.Functional
    def turn(w):
        x, y = w.x
        r2 = x * x + y * y
        return (-y * w["u"][0] + x * w["u"][1]) / r2

    @skfem.Functional
    def length(w):
        return 1.0 + 0 * w.x[0]

    return float(turn.assemble(fb, u=fb.interpolate(u)) / length.assemble(fb))


def ring_stiffness(ring: RingGear, mesh: FEMesh, material: Material = Material(),
                   n_planets: int = 3, carrier_teeth=None) -> RingStiffness:
    """c_ru at each carrier position (default: every tooth over one planet pitch) and c_r."""
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
    model = plane_model(mesh, material, ring.gear.face_width, "stress")
    patch = {k: model.group_length(f"tooth{k}_load") for k in range(z)}
    t1 = time.perf_counter()

    def tooth_force(k, direction):
        traction = np.asarray(direction) / (patch[k] * model.thickness)
        return model.traction_load(f"tooth{k}_load", traction)

    torque_loads, loaded = [], []
    for s in carrier_teeth:
        teeth = [(int(s) + round(i * z / n_planets)) % z for i in range(n_planets)]
        loaded.append(teeth)
        torque_loads.append(sum(tooth_force(k, ring.load_point(k)[1]) for k in teeth))
    translation = [sum(tooth_force(k, e) for k in range(z)) / z
                   for e in (np.array([1.0, 0.0]), np.array([0.0, 1.0]))]
    loads = np.column_stack(torque_loads + translation)
    t2 = time.perf_counter()
    solution = solve(model, loads, ["supports"])
    t3 = time.perf_counter()
    rb = ring.gear.base_diameter / 2
    c_ru = []
    for column, teeth in enumerate(loaded):
        theta = -_mean_rotation(model, [f"tooth{k}_root" for k in teeth], solution.u[:, column])
        torque = n_planets * 1.0 * rb
        c_ru.append(torque / theta / rb ** 2)
    c_r = []
    for column, axis in ((-2, 0), (-1, 1)):
        mean = _mean_displacement(model, [f"tooth{k}_root" for k in range(z)],
                                  solution.u[:, column])
        c_r.append(1.0 / mean[axis])
    c_ru = np.array(c_ru)
    return RingStiffness(float(c_ru.mean()), c_ru, carrier_teeth, float(np.mean(c_r)),
                         model.ndofs, {"assembly": t1 - t0, "loads": t2 - t1, "solve": t3 - t2})


def _mean_displacement(model: PlaneModel, groups: list[str], u: np.ndarray) -> np.ndarray:
    """Mean displacement (2,) [m] over the named boundaries (boundary integral / length)."""
    import skfem

    fe = model.basis.mesh
    facets = np.concatenate([fe.boundaries[g] for g in groups])
    fb = skfem.FacetBasis(fe, model.basis.elem, facets=facets, intorder=2 * model.mesh.order)
    uh = fb.interpolate(u)
    means = []
    for i in range(2):
        @skfem.Functional
        def component(w, i=i):
            return w["u"][i]
        means.append(component.assemble(fb, u=uh))

    @skfem.Functional
    def length(w):
        return 1.0 + 0 * w.x[0]

    return np.array(means) / length.assemble(fb)
