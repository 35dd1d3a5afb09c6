"""Raba 118/76 bearing stiffness and loads, from its design (``hubvib.design.presets``)."""
from __future__ import annotations

from hubvib.meshing.raba118 import design


def sun_torque() -> float:
    """The ASSUMED operating sun torque [N m]."""
    return design().sun_torque


def n_planets() -> int:
    return design().n_planets


def mesh_force() -> float:
    """Normal force of each sun-planet mesh [N] (equal load sharing)."""
    from hubvib.design.build import mesh_force as build

    return build(design())


def bearing_stiffness() -> dict[str, dict]:
    """c_p and c_c, tangent and secant [N/m], with the loads they were computed at [N]."""
    from hubvib.design.build import bearing_stiffness as build

    return build(design())
