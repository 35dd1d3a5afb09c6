"""Annulus in torsion: the FE chain's exact-solution benchmark (SI units)."""
from __future__ import annotations

import math

import numpy as np

from hubvib.meshing.annulus import annulus_mesh

from .elasticity import plane_model, solve
from .material import Material


def exact_k_theta(inner: float, outer: float, thickness: float, material: Material) -> float:
    """k_theta = 4 pi G t a^2 b^2 / (b^2 - a^2) [N m/rad] (inner edge clamped, plane stress)."""
    return 4 * math.pi * material.shear_modulus * thickness * inner ** 2 * outer ** 2 / (
        outer ** 2 - inner ** 2)


def fe_k_theta(inner: float, outer: float, thickness: float, material: Material, size: float,
               order: int) -> tuple[float, int]:
    """FE k_theta [N m/rad] and DOF count: unit torque as a uniform shear traction on the
    outer edge, rotation from the work T theta = f . u."""
    import skfem

    model = plane_model(annulus_mesh(inner, outer, size, order), material, thickness)
    fb = model.facet_basis(["outer"])
    tau = 1.0 / (2 * math.pi * outer ** 2 * thickness)

    @skfem.LinearForm
    def load(v, w):
        x, y = w.x
        r = np.sqrt(x * x + y * y)
        return thickness * tau * (-y / r * v[0] + x / r * v[1])

    f = load.assemble(fb)
    u = solve(model, f, ["inner"]).u
    return 1.0 / float(f @ u), model.ndofs
