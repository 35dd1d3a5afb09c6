"""FE tooth compliance along the flank (SI units).

One tooth of a gear body or ring (tooth 0 unless asked: any other is measured
in its own frame, tooth 0's rotated) is loaded by a unit point force along the
line of action at flank radii ``radii``; one factorisation serves all of them,
and ``tooth_probe`` gives the load columns to share a factorisation with other
loads (``crack_level``).  The
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


def rigid_fit(points: np.ndarray, displacement: np.ndarray) -> np.ndarray:
    """(u_x, u_y, theta) of the rigid motion closest to ``displacement`` at ``points``."""
    n = len(points)
    A = np.zeros((2 * n, 3))
    A[:n, 0] = 1.0
    A[n:, 1] = 1.0
    A[:n, 2] = -points[:, 1]
    A[n:, 2] = points[:, 0]
    return np.linalg.lstsq(A, np.concatenate([displacement[:n], displacement[n:]]), rcond=None)[0]


def root_land_points(body: RingGear) -> np.ndarray:
    prof = body.profile
    r = prof.root_radius + INSIDE
    psi = np.linspace(prof.root_land_angle, prof.space_angle, LAND_POINTS + 2)[1:-1]
    psi = np.concatenate([psi, -psi])
    return np.column_stack([r * np.cos(psi), r * np.sin(psi)])


@dataclass(frozen=True, eq=False)
class ToothProbe:
    """Unit loads on one tooth and the probes that measure its deflection.

    Attributes
    ----------
    loads : ndarray (ndofs, radii)
        1 N along the line of action at each flank radius [N].
    radii : ndarray
        Flank radii [m].
    rotation : ndarray (2, 2)
        From the tooth's own frame (tooth 0's position) to the global one.
    section, land : scipy.sparse matrices
        Displacements at the section probe points of every radius and at the root-land
        points (rows: u_x of every point, then u_y) [m per m of DOF].
    """

    loads: np.ndarray
    radii: np.ndarray
    rotation: np.ndarray
    section: object
    land: object | None
    points: list
    land_points: np.ndarray | None


def tooth_rotation(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s], [s, c]])


def tooth_probe(body: ToothedBody, model, radii, tooth: int = 0) -> ToothProbe:
    """Loads and probes of tooth ``tooth`` at flank ``radii`` [m] (on the involute).

    The tooth is measured in its own frame, tooth 0's rotated by its angle, so that
    every tooth of an intact gear has the same compliance."""
    radii = np.atleast_1d(np.asarray(radii, dtype=float))
    low, high = sorted((body.profile.form_radius, body.profile.tip_radius))
    if np.any((radii <= low) | (radii >= high)):
        raise ValueError(f"radii must lie on the involute, {low:.6g}..{high:.6g} m; got "
                         f"{radii.min():.6g}..{radii.max():.6g} m")
    if isinstance(tooth, bool) or not isinstance(tooth, (int, np.integer)) \
            or not 0 <= tooth < body.teeth:
        raise ValueError(f"tooth = {tooth!r}, allowed integers 0..{body.teeth - 1}")
    rot = tooth_rotation(body.tooth_angle(int(tooth)))
    points, forces, probes = [], [], []
    for r in radii:
        p, d = load_point(body, r)
        points.append(p + INSIDE * d)  # sliding a force along its line of action moves no moment
        forces.append(d)
        centre = np.array([p[0], 0.0])
        offset = np.array([0.0, p[1] / 2])
        probes.append((p, d, np.array([centre, centre + offset, centre - offset])))
    n = len(radii)
    forces = np.array(forces) @ rot.T
    at_loads = model.probes(np.array(points) @ rot.T)  # rows: u_x at each point, then u_y
    loads = at_loads[:n].multiply(forces[:, :1]) + at_loads[n:].multiply(forces[:, 1:])
    section = model.probes(np.vstack([q for _, _, q in probes]) @ rot.T)
    land = root_land_points(body) if isinstance(body, RingGear) else None
    land_probe = model.probes(land @ rot.T) if land is not None else None
    return ToothProbe(loads.T.toarray(), radii, rot, section, land_probe, probes, land)


def _local(probe, rotation: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """u_x, u_y in the tooth's frame at the probe's points."""
    values = probe @ u
    n = len(values) // 2
    ux, uy = values[:n], values[n:]
    return rotation[0, 0] * ux + rotation[1, 0] * uy, rotation[0, 1] * ux + rotation[1, 1] * uy


def tooth_compliance(probe: ToothProbe, u: np.ndarray) -> np.ndarray:
    """Compliance [m/N] at each radius from the displacements ``u`` (ndofs, radii) under
    ``probe.loads``."""
    compliance = []
    for column, (p, d, points) in enumerate(probe.points):
        ux, uy = _local(probe.section, probe.rotation, u[:, column])
        ux, uy = ux[3 * column:3 * column + 3], uy[3 * column:3 * column + 3]
        theta = -(ux[1] - ux[2]) / (points[1, 1] - points[2, 1])
        lever = p - points[0]
        moved = np.array([ux[0] - theta * lever[1], uy[0] + theta * lever[0]])
        if probe.land is not None:
            sx, sy, st = rigid_fit(probe.land_points,
                                    np.concatenate(_local(probe.land, probe.rotation,
                                                          u[:, column])))
            moved -= np.array([sx - st * p[1], sy + st * p[0]])
        compliance.append(float(d @ moved))
    return np.array(compliance)


def fe_tooth_compliance(body: ToothedBody, mesh: FEMesh, radii,
                        material: Material = Material(), tooth: int = 0) -> FEToothCompliance:
    """Compliance of tooth ``tooth`` at each flank radius (plane stress, face width thickness)."""
    t0 = time.perf_counter()
    model = plane_model(mesh, material, body.gear.face_width, "stress")
    t1 = time.perf_counter()
    probe = tooth_probe(body, model, radii, tooth)
    solution = solve(model, probe.loads, ["supports"])
    t2 = time.perf_counter()
    compliance = tooth_compliance(probe, solution.u)
    t3 = time.perf_counter()
    return FEToothCompliance(probe.radii, compliance, model.ndofs,
                             {"assembly": t1 - t0, "solve": t2 - t1, "measure": t3 - t2})
