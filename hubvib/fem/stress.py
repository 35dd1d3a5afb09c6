"""Stress of a plane solution: von Mises at the mesh vertices (SI units)."""
from __future__ import annotations

import numpy as np

from .elasticity import PlaneModel


def von_mises(model: PlaneModel, u: np.ndarray) -> np.ndarray:
    """Von Mises stress [Pa] at every vertex of ``model.basis.mesh`` (NaN at mid-edge nodes).

    The stress at the quadrature points is L2-projected onto P1, so a uniform
    stress is reproduced exactly; at a crack tip the projection smooths the
    singularity over one element, and its undershoot below 0 there is cut off.
    Plane strain adds sigma_zz = nu (s_xx + s_yy).
    """
    import skfem

    fe = model.basis.mesh
    lam, mu = model.material.lame(model.plane)
    grad = model.basis.interpolate(u).grad
    strain = 0.5 * (grad + grad.transpose(1, 0, 2, 3))
    trace = strain[0, 0] + strain[1, 1]
    sxx = lam * trace + 2 * mu * strain[0, 0]
    syy = lam * trace + 2 * mu * strain[1, 1]
    sxy = 2 * mu * strain[0, 1]
    szz = model.material.nu * (sxx + syy) if model.plane == "strain" else 0.0
    value = np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
                    + 3 * sxy ** 2)
    # the quadrature of plane_model, so ``value`` sits at this basis' points
    scalar = skfem.Basis(fe, skfem.ElementTriP1(), intorder=2 * model.mesh.order)
    projected = scalar.project(value)
    out = np.full(fe.p.shape[1], np.nan)
    vertices = np.unique(fe.t)
    out[vertices] = np.maximum(projected[scalar.nodal_dofs[0, vertices]], 0.0)
    return out
