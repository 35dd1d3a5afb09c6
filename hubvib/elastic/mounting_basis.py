"""One reduced ring for a whole family of foundation stiffnesses (SI units).

The Winkler foundation enters the ring's stiffness linearly: ``K(s) = K_0 + s F`` with
``F`` the foundation of the reference stiffness (``k_n``, ``k_t`` per unit arc length) and
``s`` the scale.  A mode of ``K(s)`` obeys ``(K(1) - omega^2 M) u = -(s - 1) F u``: it is
the response of the reference ring to a load on the support arcs.  The Ritz basis is
therefore the reference ring's modes up to the cut-off plus the static responses
``K(1)^-1 (...)`` to

- each contact tooth's load and that response's inertia (as ``fem.ring_basis``), and
- the foundation's reaction to smooth displacements of each support arc (radial and
  tangential, times the Legendre polynomials of degree 0..``degree`` along the arc) and
  those responses' inertia (the second Krylov vector: the truncated modes' inertia),

M-orthonormalised.  The foundation reaction of a mode is smooth along an arc wherever the
arc is not held outright, so these loads span it; every scale is then a small dense
problem.  Stiff enough to clamp, the reaction concentrates at the arcs' ends and the
basis no longer holds: the scales it serves are checked against full rebuilds
(``tests/elastic/test_elastic_map.py``).  Only the reduced matrices are kept (light to pickle).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from hubvib.foundation.blas import blas_threads

#: Legendre degree of the arc displacements whose foundation reaction the basis answers
ARC_DEGREE = 6
#: angular gap that separates two support arcs [rad]
ARC_GAP = np.radians(3.0)

__all__ = ["ScaledRing", "scaled_ring", "family_ring", "cached_family_ring",
           "ring_operators_at", "ARC_DEGREE"]


@dataclass(frozen=True, eq=False)
class ScaledRing:
    """A ring reduced once for every foundation scale ``s``.

    Attributes
    ----------
    K0, F : ndarray (m, m)
        Reduced stiffness without the foundation and of the reference foundation [N/m];
        the reduced mass is the identity [kg].
    contact : ndarray (m, z)
        Every tooth's contact functional in the reduced coordinates [-].
    probe : ndarray (2 P, m)
        Mid-rim radial then tangential displacement [m per unit coordinate].
    moment_sign, patch_angles, directions : ndarray
        As ``lumped.elastic_ring.RingOperators``.
    foundation : tuple
        The reference ``(k_n, k_t)`` [N/m^2].
    ring_mass : float
        The ring's mass [kg].
    ring_dofs : int
    teeth : tuple
        Teeth whose contact responses are in the basis.
    mode_hz : ndarray
        The reference ring's own modes in the basis [Hz].
    """

    K0: np.ndarray
    F: np.ndarray
    contact: np.ndarray
    probe: np.ndarray
    moment_sign: np.ndarray
    patch_angles: np.ndarray
    directions: np.ndarray
    foundation: tuple
    ring_mass: float
    ring_dofs: int
    teeth: tuple
    mode_hz: np.ndarray

    @property
    def size(self) -> int:
        return self.K0.shape[0]


def ring_operators_at(ring: ScaledRing, scale: float):
    """The reduced ring on the foundation ``scale`` x the reference, as the coupled model
    takes it (``lumped.elastic_ring.RingOperators``)."""
    from hubvib.lumped.elastic_ring import RingOperators

    if not (np.isfinite(scale) and scale > 0):
        raise ValueError(f"foundation scale = {scale!r}, allowed > 0")
    K = ring.K0 + scale * ring.F
    return RingOperators(0.5 * (K + K.T), np.eye(ring.size), ring.contact,
                         ring.moment_sign, ring.patch_angles, ring.directions, ring.probe)


def arc_patterns(body, support: np.ndarray, degree: int = ARC_DEGREE) -> np.ndarray:
    """(free dofs, k): radial and tangential displacement of each support arc times the
    Legendre polynomials of degree 0..``degree`` of the arc's own coordinate, on the
    support DOFs ``support`` (zero elsewhere)."""
    from hubvib.fem.elasticity import dof_components

    basis = body.model.basis
    expand = body.expand.tocsc()
    # one model DOF of each free DOF: its place and component
    first = expand.indices[expand.indptr[:-1]]
    xy = basis.doflocs[:, first[support]]
    component = dof_components(basis)[first[support]]
    theta = np.arctan2(xy[1], xy[0])
    arcs = _arcs(theta)
    out = []
    for members in arcs:
        angle = np.unwrap(theta[members][np.argsort(theta[members])])
        order = np.argsort(theta[members])
        local = np.empty(members.size)
        local[order] = angle
        low, high = local.min(), local.max()
        xi = 2 * (local - low) / (high - low) - 1 if high > low else np.zeros_like(local)
        th = theta[members]
        radial = np.where(component[members] == 0, np.cos(th), np.sin(th))
        tangential = np.where(component[members] == 0, -np.sin(th), np.cos(th))
        for k in range(degree + 1):
            p = np.polynomial.legendre.Legendre.basis(k)(xi)
            for direction in (radial, tangential):
                column = np.zeros(body.ndofs)
                column[support[members]] = p * direction
                out.append(column)
    return np.column_stack(out)


def _arcs(theta: np.ndarray) -> list[np.ndarray]:
    """Indices of ``theta`` grouped into arcs separated by more than ``ARC_GAP``."""
    order = np.argsort(theta)
    t = theta[order]
    gaps = np.diff(np.concatenate([t, [t[0] + 2 * np.pi]]))
    cuts = np.flatnonzero(gaps > ARC_GAP)
    if cuts.size == 0:
        return [order]
    # start after the first cut so that an arc across +-pi stays whole
    start = (cuts[0] + 1) % t.size
    rolled = np.roll(order, -start)
    gaps = np.roll(gaps, -start)
    ends = np.flatnonzero(gaps > ARC_GAP) + 1
    return [g for g in np.split(rolled, ends) if g.size]


def scaled_ring(body, teeth, cutoff_hz: float, degree: int = ARC_DEGREE,
                solver: str = "auto") -> ScaledRing:
    """The family basis of a ring ``body`` (``fem.ring_body.RingBody`` on a foundation):
    modes up to ``cutoff_hz`` [Hz], the contact responses of ``teeth`` and the arcs'
    reaction responses (module docstring)."""
    if body.mounting != "foundation" or body.foundation is None:
        raise ValueError(f"mounting = {body.mounting!r}: a foundation family needs the ring "
                         "on its foundation")
    teeth = tuple(sorted({int(k) for k in teeth}))
    with blas_threads(1):
        return _scaled_ring(body, teeth, cutoff_hz, degree, solver)


def _scaled_ring(body, teeth, cutoff_hz, degree, solver) -> ScaledRing:
    import scipy.sparse as sp

    from hubvib.fem.ring_basis import ring_modes
    from hubvib.fem.ring_body import support_springs

    normal, tangential = support_springs(body.model)
    f = body.foundation
    restrict = body.expand.T.tocsr()
    F = (restrict @ (f.k_n * normal + f.k_t * tangential) @ body.expand).tocsr()
    support = np.flatnonzero(np.asarray(abs(F).sum(axis=1)).ravel() > 0)
    omega, phi, factor, _ = ring_modes(body, cutoff_hz, solver)
    try:
        loads = body.contact[:, list(teeth)].toarray() if teeth else np.zeros((body.ndofs, 0))
        first = np.asarray(factor.solve(loads)).reshape(body.ndofs, len(teeth))
        second = np.asarray(factor.solve(body.M @ first)).reshape(body.ndofs, len(teeth))
        reaction = F @ arc_patterns(body, support, degree)
        arcs = np.asarray(factor.solve(reaction)).reshape(body.ndofs, reaction.shape[1])
        inertia = np.asarray(factor.solve(body.M @ arcs)).reshape(arcs.shape)
    finally:
        factor.free()
    static = np.hstack([first, second, arcs, inertia])
    Mphi = body.M @ phi
    for _ in range(2):  # Gram-Schmidt against the (M-orthonormal) modes, twice: to round-off
        static = static - phi @ (Mphi.T @ static)
    Ms = body.M @ static
    scale = 1 / np.sqrt(np.einsum("ij,ij->j", static, Ms))
    gram = scale[:, None] * (static.T @ Ms) * scale[None, :]
    w, U = np.linalg.eigh(0.5 * (gram + gram.T))
    useful = w > 1e-10 * w.max()
    T = scale[:, None] * U[:, useful] / np.sqrt(w[useful])
    V = np.hstack([phi, static @ T])
    # V is M-orthonormal to round-off; one Cholesky step of its small Gram matrix (formed
    # from the products above) makes it so to the last digits, applied to the reduced
    # matrices rather than to V
    cross = Mphi.T @ V
    S_gram = T.T @ (static.T @ Ms) @ T
    m = phi.shape[1]
    gram = np.block([[cross[:, :m], cross[:, m:]], [cross[:, m:].T, S_gram]])
    L = sla.cholesky(0.5 * (gram + gram.T), lower=True)

    def reduced(A):  # L^-1 A L^-T
        A = sla.solve_triangular(L, A, lower=True)
        return sla.solve_triangular(L, A.T, lower=True).T

    K1 = reduced(V.T @ (body.K @ V))
    on = support  # the foundation acts on the support DOFs only
    Fr = reduced(V[on].T @ (F[on][:, on] @ V[on]))
    sign = -np.sign(body.rigid[:, 2] @ body.contact)
    contact = sla.solve_triangular(L, np.asarray(sp.csc_matrix(body.contact).T @ V).T,
                                   lower=True)
    probe = sla.solve_triangular(L, np.asarray(body.probe @ V).T, lower=True).T
    return ScaledRing(
        K0=0.5 * ((K1 - Fr) + (K1 - Fr).T), F=0.5 * (Fr + Fr.T), contact=contact,
        probe=probe, moment_sign=np.asarray(sign).ravel(),
        patch_angles=body.patch_angles, directions=body.directions,
        foundation=(f.k_n, f.k_t), ring_mass=float(body.rigid_mass()[0, 0]),
        ring_dofs=body.ndofs, teeth=teeth, mode_hz=omega / (2 * np.pi))


def family_ring(design, crack=None, options=None, foundation: tuple | None = None,
                carrier_teeth=(0,), params=None, degree: int = ARC_DEGREE) -> ScaledRing:
    """The ``ScaledRing`` of ``design`` with ``crack`` (None: intact; faces open) on the
    reference ``foundation`` ``(k_n, k_t)`` [N/m^2] (None: sized to the design's lumped
    ``c_r``, ``c_ru`` on this ring), with contact responses for planet 1 on each of
    ``carrier_teeth``; ``options``: ``ElasticOptions`` (mesh, cut-off)."""
    from hubvib.reducer.stages import lumped_parameters, material, ring_gear
    from hubvib.fem.ring_body import Foundation, ring_body
    from hubvib.lumped.elastic_ring import RingOperators, engagement
    from hubvib.meshing.ring_mesh import ring_mesh

    from .options import ElasticOptions

    options = ElasticOptions() if options is None else options
    params = lumped_parameters(design) if params is None else params
    ring, mat = ring_gear(design), material(design)
    if crack is not None and crack.depth == 0:
        crack = None
    mesh = ring_mesh(ring, crack, options.mesh)
    if foundation is None:
        body = ring_body(ring, mesh, mat, "foundation", sized_to=(params.c_r, params.c_ru))
    else:
        body = ring_body(ring, mesh, mat, "foundation", Foundation(*foundation))
    angles = RingOperators(None, None, None, None, body.patch_angles, body.directions, None)
    teeth = {k for c in carrier_teeth for k in engagement(params, angles, int(c)).teeth}
    return scaled_ring(body, teeth, options.cutoff_hz, degree)


def cached_family_ring(design, crack, options, foundation: tuple | None, carrier_teeth,
                       degree: int = ARC_DEGREE) -> ScaledRing:
    """``family_ring`` through the result cache (inputs and this computation's source)."""
    from hubvib.runtime.result_cache import cached_result

    foundation = None if foundation is None else tuple(float(x) for x in foundation)
    teeth = tuple(int(k) for k in carrier_teeth)
    inputs = (design.fingerprint(), crack, options, foundation, teeth, int(degree))
    return cached_result("elastic-mounting-ring", inputs, (__name__,),
                         lambda: family_ring(design, crack, options, foundation, teeth,
                                             degree=degree), ScaledRing)

