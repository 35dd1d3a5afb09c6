"""Compliance of one ring tooth in the solid (3D) ring: a line load across the face (SI).

The plane tooth model (``fem.tooth_fe``) loads the tooth by 1 N along the line
of action at a flank radius and reads the deflection as the rigid motion of
the section through the load point, the rigid motion of the root lands beside
the tooth subtracted.  Here the same 1 N is spread uniformly along the contact
line across the whole face width (a spur pair's contact line), as ``SAMPLES``
point forces at the midpoints of equal strips of the width, each moved
``INSIDE`` along its line of action into the tooth (that moves no moment).
Every strip is read as the plane model reads its section, in its own plane z =
const (section and root-land probes at the strip's z); the tooth's deflection
is the load-weighted mean over the strips, the work-conjugate reading of a
uniform line load.  It is a compliance [m/N] of the whole face width, as the
plane model's over the face-width thickness, so the two compare directly.  On a
half-width model (``fem.solid``) the load and the readings are the half's strips: 1 N
over them on the doubled stiffness is the whole width's 1 N, and the mean over them is
the whole width's mean (mirror symmetry).

The load columns join the ring's own (``fem.ring_stiffness.ring_stiffness``
``tooth=``): one factorisation per mesh serves c_ru, c_r and the tooth at every
flank radius.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubvib.meshing.ring_gear import RingGear

from .locate import interpolation_matrix
from .tooth_beam import load_point
from .tooth_fe import rigid_fit, root_land_points, tooth_rotation

#: point forces (and readings) across the face width: strips of 40/64 = 0.6 mm on the Raba
#: ring, finer than the solid mesh's tooth elements (2-5 mm), so the forces act as a line
SAMPLES = 64
#: [m] the forces and probe points sit this far inside the material (the straight-sided
#: corner mesh used to find their cells misses points within the sagitta of a curved face)
INSIDE = 1e-4
#: nearest cells (by centroid) a probe point is tried against, widening; then every cell
CANDIDATES = (16, 256)
#: cells per slice of the search through every cell
SLICE = 100_000


@dataclass(frozen=True)
class SolidToothLoad:
    """What to load: ring tooth ``tooth`` at flank ``radii`` [m], ``samples`` strips."""

    tooth: int
    radii: tuple
    samples: int = SAMPLES

    def __post_init__(self):
        if isinstance(self.samples, bool) or not isinstance(self.samples, int) \
                or self.samples < 2:
            raise ValueError(f"samples = {self.samples!r}, allowed integers >= 2")


@dataclass(frozen=True)
class SolidToothCompliance:
    """The tooth's compliance [m/N] at each flank radius [m] (1 N over the face width), and
    per radius the deflection of each strip [m/N] at its ``z`` [m] (the profile)."""

    radii: np.ndarray
    compliance: np.ndarray
    z: np.ndarray
    profile: np.ndarray


@dataclass(frozen=True, eq=False)
class SolidToothProbe:
    """Load columns (ndofs, radii) [N] and the probe matrices that read the deflection."""

    load: SolidToothLoad
    loads: np.ndarray
    z: np.ndarray
    rotation: np.ndarray
    section: object   # (3 * points, ndofs): u_x, u_y, u_z at radius x strip x 3 points
    land: object      # the same at strip x land point
    points: list      # per radius (load point, force direction, section points) in 2D
    land_points: np.ndarray


def solid_probes(model, points: np.ndarray, finder=None):
    """Sparse matrix (3 n, ndofs): u_x at the n ``points`` (n, 3) [m], then u_y, then u_z.

    The cell is found on the straight-sided mesh of the corner nodes (``finder``, from
    ``element_finder(model)``; built if not given), then the isoparametric map is
    inverted (``fem.locate``)."""
    basis = model.basis
    points = np.asarray(points, dtype=float).reshape(-1, 3).T
    finder = finder or element_finder(model)
    try:
        cells = finder(*points)
    except ValueError:
        raise ValueError("a probe point of the solid tooth lies outside the mesh") from None
    return interpolation_matrix(basis, points, cells)


def element_finder(model):
    """``finder(x, y, z)``: the cell of each point (coordinates (n,) [m]) on the
    straight-sided tetrahedra of ``model``'s corners; ValueError when a point is in none.

    As skfem's ``MeshTet1.element_finder`` (barycentric coordinates within a few ulps of
    the cell), but each point is tried against its own nearest cells only (centroids,
    ``CANDIDATES`` at a time, then every cell): skfem's tries every point against the
    union of all points' candidates, then against every cell of the mesh, a large part of
    a solid crack case's time and memory peak.  The cells found are
    the same (``test_element_finder_finds_the_cell_of_every_point``)."""
    from scipy.spatial import cKDTree

    fe = model.basis.mesh
    corners = fe.p[:, fe.t[:4]]  # (3, 4, cells)
    origin = corners[:, 0].T
    inverse = np.linalg.inv((corners[:, 1:] - corners[:, :1]).transpose(2, 0, 1))
    tree = cKDTree(corners.mean(axis=1).T)
    count = len(origin)
    eps = np.finfo(float).eps

    def inside(points, near):
        """(points, candidates) bool: point i lies in cell near[i, j]."""
        X = np.einsum("mkij,mkj->mki", inverse[near], points[:, None, :] - origin[near])
        return (X >= -eps).all(axis=2) & (1 - X.sum(axis=2) >= -3 * eps)

    def finder(x, y, z):
        points = np.column_stack([x, y, z]).astype(float)
        cells = np.full(len(points), -1, dtype=np.int64)
        todo = np.arange(len(points))
        for k in CANDIDATES:
            if not len(todo):
                return cells
            near = tree.query(points[todo], min(k, count))[1].reshape(len(todo), -1)
            hit = inside(points[todo], near)
            found = hit.any(axis=1)
            cells[todo[found]] = near[found, hit[found].argmax(axis=1)]
            todo = todo[~found]
        for i in todo:  # far from every nearby centroid: every cell, in slices
            for first in range(0, count, SLICE):
                near = np.arange(first, min(first + SLICE, count))[None, :]
                hit = inside(points[i:i + 1], near)[0]
                if hit.any():
                    cells[i] = near[0, hit.argmax()]
                    break
            else:
                raise ValueError(f"point {points[i].tolist()} m is outside of the mesh")
        return cells

    return finder


def _at_strips(points_2d: np.ndarray, rotation: np.ndarray, z: np.ndarray) -> np.ndarray:
    """(strips x points, 3): the tooth-frame points rotated to the global frame at each z."""
    xy = points_2d @ rotation.T
    return np.column_stack([np.tile(xy, (len(z), 1)), np.repeat(z, len(xy))])


def solid_tooth_probe(ring: RingGear, model, load: SolidToothLoad) -> SolidToothProbe:
    """Load columns and probes of ``load`` on the solid ring ``model`` (z from 0 to the
    face width [m]; a half-width model: its half of the strips)."""
    radii = np.asarray(load.radii, dtype=float)
    low, high = sorted((ring.profile.form_radius, ring.profile.tip_radius))
    if radii.ndim != 1 or not len(radii) or np.any((radii <= low) | (radii >= high)):
        raise ValueError(f"radii must lie on the involute, {low:.6g}..{high:.6g} m; got "
                         f"{np.atleast_1d(radii).tolist()}")
    if isinstance(load.tooth, bool) or not isinstance(load.tooth, (int, np.integer)) \
            or not 0 <= load.tooth < ring.teeth:
        raise ValueError(f"tooth = {load.tooth!r}, allowed integers 0..{ring.teeth - 1}")
    width = ring.gear.face_width
    z = (np.arange(load.samples) + 0.5) / load.samples * width
    if model.mirror_z is not None:  # the half-width model: its half of the same strips
        if load.samples % 2:
            raise ValueError(f"samples = {load.samples}: a half-width model needs an even "
                             "number of strips (its half of them)")
        z = z[:load.samples // 2]
    rot = tooth_rotation(ring.tooth_angle(int(load.tooth)))
    finder = element_finder(model)
    columns, points, section = [], [], []
    for r in radii:
        p, d = load_point(ring, r)
        points.append((p, d, np.array([[p[0], 0.0], [p[0], p[1] / 2], [p[0], -p[1] / 2]])))
        at = solid_probes(model, _at_strips((p + INSIDE * d)[None, :], rot, z), finder)
        n = len(z)
        force = rot @ d / n  # 1 N in all along the line
        columns.append((at[:n].T * force[0] + at[n:2 * n].T * force[1]) @ np.ones(n))
        section.append(_at_strips(points[-1][2], rot, z))
    lands = root_land_points(ring)
    lands = lands * (1 + (INSIDE - 2e-5) / np.hypot(*lands.T))[:, None]
    return SolidToothProbe(load, np.column_stack(columns), z, rot,
                           solid_probes(model, np.vstack(section), finder),
                           solid_probes(model, _at_strips(lands, rot, z), finder), points,
                           lands)


def _local(values: np.ndarray, rotation: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """In-plane u_x, u_y in the tooth's frame from probe values (u_x..., u_y..., u_z...)."""
    n = len(values) // 3
    ux, uy = values[:n], values[n:2 * n]
    return rotation[0, 0] * ux + rotation[1, 0] * uy, rotation[0, 1] * ux + rotation[1, 1] * uy


def solid_tooth_compliance(probe: SolidToothProbe, u: np.ndarray) -> SolidToothCompliance:
    """Compliance [m/N] at each radius from the displacements ``u`` (ndofs, radii) under
    ``probe.loads``: per strip the plane model's reading, then the mean over the strips."""
    strips = len(probe.z)
    profile = np.zeros((len(probe.points), strips))
    for column, (p, d, points) in enumerate(probe.points):
        sx, sy = _local(probe.section @ u[:, column], probe.rotation)
        lx, ly = _local(probe.land @ u[:, column], probe.rotation)
        # section values: radius-major, then strip, then the three points
        block = slice(3 * strips * column, 3 * strips * (column + 1))
        sx, sy = sx[block].reshape(strips, 3), sy[block].reshape(strips, 3)
        lx = lx.reshape(strips, -1)
        ly = ly.reshape(strips, -1)
        theta = -(sx[:, 1] - sx[:, 2]) / (points[1, 1] - points[2, 1])
        lever = p - points[0]
        moved = np.column_stack([sx[:, 0] - theta * lever[1], sy[:, 0] + theta * lever[0]])
        for j in range(strips):
            tx, ty, tt = rigid_fit(probe.land_points, np.concatenate([lx[j], ly[j]]))
            moved[j] -= np.array([tx - tt * p[1], ty + tt * p[0]])
        profile[column] = moved @ d
    return SolidToothCompliance(np.asarray(probe.load.radii, dtype=float),
                                profile.mean(axis=1), probe.z, profile)
