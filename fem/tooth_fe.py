"""FE tooth compliance along the flank (SI units).

Tooth 0 of a gear body or ring is loaded by a unit point force along the line
of action at flank radii ``radii``; one factorisation serves all of them.  The
deflection is measured as the analytical method defines it, so that Hertzian
contact is added once (``tooth_beam.hertz_compliance``): the section through
the load point normal to the tooth axis is taken as rigid, its translation
read at the centre line and its rotation from the axial displacements at
half the load point's offset on either side; the deflection is that rigid
motion at the load point along the force.  The local indentation under the
force is thereby excluded.

Gear bodies are held at the bore, and the body's deflection belongs to the
tooth (as Sainsot's foundation term).  On a ring the rigid motion of the
root lands beside the tooth (least squares over points on them) is
subtracted: the rim's deflection belongs to ``c_ru``.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.ring_gear import RingGear, ToothedBody

from .elasticity import plane_model, solve
from .material import Material
from .tooth_beam import load_point

INSIDE = 2e-5  # [m] probe points are moved this far into the material
LAND_POINTS = 6  # per root land


@dataclass(frozen=True)
class FEToothCompliance:
    """Compliance [m/N] of tooth 0 at each flank radius [m], with DOFs and seconds."""

    radii: np.ndarray
    compliance: np.ndarray
    dofs: int
    seconds: dict


def _rigid_fit(points: np.ndarray, displacement: np.ndarray) -> np.ndarray:
    """(u_x, u_y, theta) of the rigid motion closest to ``displacement`` at ``points``."""
    n = len(points)
    A = np.zeros((2 * n, 3))
    A[:n, 0] = 1.0
    A[n:, 1] = 1.0
    A[:n, 2] = -points[:, 1]
    A[n:, 2] = points[:, 0]
    return np.linalg.lstsq(A, np.concatenate([displacement[:n], displacement[n:]]), rcond=None)[0]


def _root_land_points(body: RingGear) -> np.ndarray:
    prof = body.profile
    r = prof.root_radius + INSIDE
    psi = np.linspace(prof.root_land_angle, prof.space_angle, LAND_POINTS + 2)[1:-1]
    psi = np.concatenate([psi, -psi])
    return np.column_stack([r * np.cos(psi), r * np.sin(psi)])


def fe_tooth_compliance(body: ToothedBody, mesh: FEMesh, radii,
                        material: Material = Material()) -> FEToothCompliance:
    """Compliance of tooth 0 at each flank radius (plane stress, face width thickness)."""
    radii = np.atleast_1d(np.asarray(radii, dtype=float))
    low, high = sorted((body.profile.form_radius, body.profile.tip_radius))
    if np.any((radii <= low) | (radii >= high)):
        raise ValueError(f"radii must lie on the involute, {low:.6g}..{high:.6g} m; got "
                         f"{radii.min():.6g}..{radii.max():.6g} m")
    t0 = time.perf_counter()
    model = plane_model(mesh, material, body.gear.face_width, "stress")
    t1 = time.perf_counter()
    points, forces, probes = [], [], []
    for r in radii:
        p, d = load_point(body, r)
        points.append(p + INSIDE * d)  # sliding a force along its line of action moves no moment
        forces.append(d)
        centre = np.array([p[0], 0.0])
        offset = np.array([0.0, p[1] / 2])
        probes.append((p, d, np.array([centre, centre + offset, centre - offset])))
    n, forces = len(radii), np.array(forces)
    at_loads = model.probes(np.array(points))  # rows: u_x at each point, then u_y
    loads = at_loads[:n].multiply(forces[:, :1]) + at_loads[n:].multiply(forces[:, 1:])
    solution = solve(model, loads.T.toarray(), ["supports"])
    t2 = time.perf_counter()
    land = _root_land_points(body) if isinstance(body, RingGear) else None
    land_probe = model.probes(land) if land is not None else None
    compliance = []
    for column, (p, d, points) in enumerate(probes):
        u = solution.u[:, column]
        values = model.probes(points) @ u
        ux, uy = values[:3], values[3:]
        theta = -(ux[1] - ux[2]) / (points[1, 1] - points[2, 1])
        lever = p - points[0]
        moved = np.array([ux[0] - theta * lever[1], uy[0] + theta * lever[0]])
        if land_probe is not None:
            sx, sy, st = _rigid_fit(land, land_probe @ u)
            moved -= np.array([sx - st * p[1], sy + st * p[0]])
        compliance.append(float(d @ moved))
    t3 = time.perf_counter()
    return FEToothCompliance(radii, np.array(compliance), model.ndofs,
                             {"assembly": t1 - t0, "solve": t2 - t1, "measure": t3 - t2})
