"""The ring gear as an elastic body for coupled vibration: stiffness, mass, mounting, the
planets' contact functionals and a probe circle, on the free DOFs (SI units).

Plane stress, the mesh's order (P2 by default), consistent mass (density x thickness).
The mounting on the support arcs (group ``supports``) is one of

- ``"clamped"``: every DOF on the arcs held;
- ``"foundation"``: a Winkler foundation, normal stiffness ``k_n`` and tangential ``k_t``
  per unit arc length [N/m^2] (of the whole face width), energy
  ``1/2 int (k_n u_n^2 + k_t u_t^2) ds``; ``foundation_for`` sizes it so that its rigid-ring
  totals are a lumped model's ``c_r`` and ``c_ru``;
- ``"free"``: no mounting (free-free; three rigid-body modes).

A closed crack (``tie_crack=True``) ties its two faces: every pair of DOFs at one place
and of one component is made one DOF.

The contact of a planet on ring tooth k is the work-conjugate of a 1 N force along the
line of action spread uniformly over the tooth's load patch (``ring_stiffness``): the
patch's mean displacement along that line, ``contact[:, k] . u`` [m].  Its moment arm is
the base radius: a rigid rotation ``phi`` moves it by ``-r_b phi`` (sign of the ring's
+psi flank).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from hubvib.meshing.fe_mesh import FEMesh
from hubvib.meshing.ring_gear import RingGear

from .elasticity import plane_model
from .material import Material
from .modal import mass_matrix
from .ring_stiffness import tooth_forces
from .ring_work import in_plane_modes

MOUNTINGS = ("clamped", "foundation", "free")
PROBE_POINTS = 256  # points on the mid-rim circle (Fourier content up to n = 127)
TIE_TOLERANCE = 1e-12  # [m, relative to the outer radius] two DOFs at one place


class MountingError(ValueError):
    """A mounting that cannot be built; the message names the field and its range."""


@dataclass(frozen=True)
class Foundation:
    """Winkler foundation on the support arcs, per unit arc length [N/m^2]."""

    k_n: float
    k_t: float

    def __post_init__(self):
        for name in ("k_n", "k_t"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                    math.isfinite(value) and 0 <= value <= 1e18):
                raise MountingError(f"foundation.{name} = {value!r} N/m^2, allowed 0..1e18")
        if self.k_n == 0 and self.k_t == 0:
            raise MountingError("foundation: k_n and k_t are both 0; give one > 0 or use "
                                "mounting 'free'")


@dataclass(frozen=True, eq=False)
class RingBody:
    """Matrices and functionals of the mounted ring on its free DOFs.

    Attributes
    ----------
    K, M : scipy.sparse.csr_matrix
        Stiffness with the mounting [N/m] and consistent mass [kg].
    contact : scipy.sparse.csc_matrix (dofs, z)
        Column k: the load of 1 N along tooth k's line of action spread over its patch;
        ``contact[:, k] @ u`` is the patch's mean displacement along that line [m].
    directions : ndarray (z, 2)
        Each tooth's line-of-action direction (into the tooth) [-].
    patch_angles : ndarray (z,)
        Polar angle of each tooth's load point (on the working pitch circle) [rad].
    rigid : ndarray (dofs, 3)
        Rigid translation x, y [m per m] and rotation [m per rad] as DOF vectors.
    probe : scipy.sparse.csr_matrix (2 P, dofs)
        Radial, then tangential displacement at ``PROBE_POINTS`` points of the mid-rim
        circle (radius ``probe_radius``, angles ``probe_angles``) [m per m].
    expand : scipy.sparse.csr_matrix (model dofs, dofs)
        The full DOF vector of the plane model from the free DOFs (zeros where held,
        tied DOFs copied).
    model : fem.elasticity.PlaneModel
    mounting : str
    foundation : Foundation or None
    base_radius : float
        [m]
    """

    K: object
    M: object
    contact: object
    directions: np.ndarray
    patch_angles: np.ndarray
    rigid: np.ndarray
    probe: object
    probe_radius: float
    probe_angles: np.ndarray
    expand: object
    model: object
    mounting: str
    foundation: Foundation | None
    base_radius: float
    tied: int = 0  # DOFs tied to a twin (a closed crack's faces)

    @property
    def ndofs(self) -> int:
        return self.K.shape[0]

    @property
    def teeth(self) -> int:
        return self.contact.shape[1]

    def rigid_mass(self) -> np.ndarray:
        """3 x 3 mass of the rigid motions: [kg] for translations, [kg m^2] for rotation."""
        return self.rigid.T @ (self.M @ self.rigid)

    def rigid_stiffness(self) -> np.ndarray:
        """3 x 3 stiffness of the mounting against the rigid motions [N/m, N m/rad]."""
        return self.rigid.T @ (self.K @ self.rigid)


def support_springs(model) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Foundation matrices of unit normal and unit tangential stiffness per unit arc length
    over the ``supports`` group [N/m per N/m^2]."""
    import skfem

    basis = model.facet_basis(["supports"])

    def form(which):
        @skfem.BilinearForm
        def spring(u, v, w):
            n = w.n
            t = (-n[1], n[0])
            d = n if which == "n" else t
            return (u[0] * d[0] + u[1] * d[1]) * (v[0] * d[0] + v[1] * d[1])
        return spring.assemble(basis).tocsr()

    return form("n"), form("t")


def foundation_for(model, c_r: float, c_ru: float, base_radius: float,
                   springs: tuple | None = None) -> Foundation:
    """The foundation whose rigid-ring totals are ``c_r`` (translation, mean of x and y)
    [N/m] and ``c_ru`` (rotation, reduced to the base radius) [N/m]; ``springs``: the
    model's ``support_springs`` when already assembled."""
    for name, value in (("c_r", c_r), ("c_ru", c_ru)):
        if not (math.isfinite(value) and value > 0):
            raise MountingError(f"{name} = {value!r} N/m: a foundation sized to it needs > 0")
    normal, tangential = support_springs(model) if springs is None else springs
    R = in_plane_modes(model)
    a_n, a_t = R.T @ (normal @ R), R.T @ (tangential @ R)
    # c_r = k_n tr_n + k_t tr_t ; c_ru r_b^2 = k_n rot_n + k_t rot_t
    A = np.array([[0.5 * (a_n[0, 0] + a_n[1, 1]), 0.5 * (a_t[0, 0] + a_t[1, 1])],
                  [a_n[2, 2], a_t[2, 2]]])
    k_n, k_t = np.linalg.solve(A, [c_r, c_ru * base_radius ** 2])
    if k_n < 0 or k_t < 0:
        raise MountingError(
            f"no foundation on the support arcs gives c_r = {c_r:.4g} N/m and c_ru = "
            f"{c_ru:.4g} N/m together (k_n = {k_n:.4g}, k_t = {k_t:.4g} N/m^2): c_ru alone "
            "needs more translational stiffness than c_r")
    return Foundation(float(k_n), float(k_t))


def ring_body(ring: RingGear, mesh: FEMesh, material: Material = Material(),
              mounting: str = "foundation", foundation: Foundation | None = None,
              tie_crack: bool = False, sized_to: tuple[float, float] | None = None
              ) -> RingBody:
    """The ring of ``mesh`` mounted as asked.  ``mounting="foundation"`` needs either a
    ``foundation`` or ``sized_to = (c_r, c_ru)`` [N/m], the rigid-ring totals the
    foundation is sized to on this model (``foundation_for``)."""
    if mounting not in MOUNTINGS:
        raise MountingError(f"mounting = {mounting!r}; allowed: {', '.join(MOUNTINGS)}")
    if (mounting == "foundation") != (foundation is not None or sized_to is not None):
        raise MountingError("foundation: give one (or sized_to) exactly when mounting = "
                            "'foundation'")
    model = plane_model(mesh, material, thickness=ring.gear.face_width)
    K, M = model.K.tocsr(), mass_matrix(model)
    if mounting == "foundation":
        normal, tangential = support_springs(model)
        if foundation is None:
            foundation = foundation_for(model, *sized_to, ring.gear.base_diameter / 2,
                                        springs=(normal, tangential))
        K = (K + foundation.k_n * normal + foundation.k_t * tangential).tocsr()
    forces = tooth_forces(model, range(ring.teeth))
    along = np.zeros((ring.teeth, 2, ring.teeth))
    directions = np.array([ring.load_point(k)[1] for k in range(ring.teeth)])
    along[np.arange(ring.teeth), :, np.arange(ring.teeth)] = directions
    contact = sp.csc_matrix(forces.loads(along))
    contact.eliminate_zeros()
    points = np.array([ring.load_point(k)[0] for k in range(ring.teeth)])
    radius = 0.5 * (ring.profile.root_radius + ring.outer_radius)
    angles = 2 * np.pi * np.arange(PROBE_POINTS) / PROBE_POINTS
    xy = radius * np.column_stack([np.cos(angles), np.sin(angles)])
    at = model.probes(xy)  # u_x at all points, then u_y
    c, s = sp.diags(np.cos(angles)), sp.diags(np.sin(angles))
    n = PROBE_POINTS
    probe = sp.vstack([c @ at[:n] + s @ at[n:], -s @ at[:n] + c @ at[n:]]).tocsr()

    expand, tied = _free_map(model, mounting == "clamped", tie_crack, ring.outer_radius)
    restrict = expand.T.tocsr()
    return RingBody(
        K=(restrict @ K @ expand).tocsr(), M=(restrict @ M @ expand).tocsr(),
        contact=(restrict @ contact).tocsc(), directions=directions,
        patch_angles=np.arctan2(points[:, 1], points[:, 0]),
        rigid=_rigid(model, expand), probe=(probe @ expand).tocsr(), probe_radius=radius,
        probe_angles=angles, expand=expand, model=model, mounting=mounting,
        foundation=foundation, base_radius=ring.gear.base_diameter / 2, tied=tied)


def _held(model) -> np.ndarray:
    return np.unique(model.basis.get_dofs("supports").flatten())


def _free_map(model, clamped: bool, tie: bool, scale: float) -> tuple[sp.csr_matrix, int]:
    """(model dofs, free dofs): held DOFs dropped, each tied DOF mapped onto its twin; and
    the number of DOFs tied to a twin."""
    n = model.ndofs
    master = np.arange(n)
    if tie:
        from .elasticity import dof_components

        where = np.vstack([model.basis.doflocs, dof_components(model.basis)[None]])
        keys = np.round(where[:2] / (TIE_TOLERANCE * scale)).astype(np.int64)
        table = np.vstack([keys, where[2:].astype(np.int64)]).T
        _, first, inverse = np.unique(table, axis=0, return_index=True, return_inverse=True)
        master = first[inverse.ravel()]
    dropped = np.zeros(n, dtype=bool)
    if clamped:
        dropped[_held(model)] = True
        dropped |= dropped[master]  # a DOF tied to a held one is held
    keep = (master == np.arange(n)) & ~dropped
    column = np.full(n, -1)
    column[keep] = np.arange(int(keep.sum()))
    target = column[master]
    rows = np.flatnonzero(~dropped)
    expand = sp.csr_matrix((np.ones(rows.size), (rows, target[rows])),
                           shape=(n, int(keep.sum())))
    return expand, int(np.sum(master != np.arange(n)))


def _rigid(model, expand) -> np.ndarray:
    """The rigid motions on the free DOFs (least squares through ``expand``: exact where
    nothing is held)."""
    R = in_plane_modes(model)
    counts = np.asarray(expand.sum(axis=0)).ravel()
    return (expand.T @ R) / counts[:, None]
