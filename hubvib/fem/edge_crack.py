"""Edge-cracked strip in pure bending: handbook compliance vs FE (SI units).

Handbook (Tada, Paris & Irwin, The Stress Analysis of Cracks Handbook, 3rd
ed., 2.13; Brown & Srawley 1966): ``K = sigma sqrt(pi a) F(a/W)``,
``sigma = 6 M / (t W^2)``, ``F = 1.122 - 1.40 x + 7.33 x^2 - 13.08 x^3 + 14.0 x^4``
(within 0.2 % for x = a/W <= 0.6).  With ``G = K^2 / E`` (plane stress) and
``G t = (M^2 / 2) dC/da`` the crack adds to the end-to-end rotation compliance
``C = theta / M``

    Delta C = 72 pi / (E t W^2) int_0^{a/W} x F(x)^2 dx.

The FE value is the work-conjugate rotation ``f . u / M^2`` of the cracked strip
minus that of the uncracked strip (pure bending is reproduced exactly by P2).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import quad

from hubvib.meshing.strip import edge_crack_strip

from .elasticity import plane_model, solve
from .material import Material

BROWN_SRAWLEY = (1.122, -1.40, 7.33, -13.08, 14.0)
VALID_RATIO = 0.6


def brown_srawley(x: float) -> float:
    """Geometry factor F(a/W) of an edge crack in pure bending [-] (a/W <= 0.6)."""
    if not 0 <= x <= VALID_RATIO:
        raise ValueError(f"a/W = {x!r}, the Brown-Srawley polynomial holds for 0..{VALID_RATIO}")
    return sum(c * x ** k for k, c in enumerate(BROWN_SRAWLEY))


def handbook_added_compliance(depth: float, width: float, thickness: float,
                              material: Material = Material()) -> float:
    """Rotation compliance the crack adds [rad/(N m)]."""
    integral = quad(lambda x: x * brown_srawley(x) ** 2, 0.0, depth / width, epsabs=0,
                    epsrel=1e-12)[0]
    return 72 * math.pi / (material.E * thickness * width ** 2) * integral


def fe_rotation_compliance(depth: float, width: float, thickness: float,
                           material: Material = Material(), size: float | None = None,
                           tip_size: float | None = None, order: int = 2) -> tuple[float, int]:
    """End-to-end rotation per moment of the strip (length 4 W) [rad/(N m)] and DOFs."""
    import skfem

    size = width / 10 if size is None else size
    tip_size = width / 400 if tip_size is None else tip_size
    mesh = edge_crack_strip(width, 2 * width, depth, size, tip_size, order)
    model = plane_model(mesh, material, thickness, "stress")
    stress = 12.0 / (thickness * width ** 3)  # bending stress per unit moment and height

    loads = []
    for end, sign in (("right", 1.0), ("left", -1.0)):
        @skfem.LinearForm
        def traction(v, w, sign=sign):
            return sign * thickness * stress * (width / 2 - w.x[1]) * v[0]
        loads.append(traction.assemble(model.facet_basis([end])))
    f = loads[0] + loads[1]
    pins = np.concatenate([model.node_dofs(mesh.points_of["pin"], 0),
                           model.node_dofs(mesh.points_of["pin"], 1),
                           model.node_dofs(mesh.points_of["roller"], 1)])
    u = solve(model, f, [], fixed_dofs=pins).u
    return float(f @ u), model.ndofs
