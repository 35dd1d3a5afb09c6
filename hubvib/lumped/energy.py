"""Where each mode stores its energy: strain per spring group, kinetic per member."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .network import dof_members, spring_network
from .parameters import STIFFNESS_FIELDS
from .spectrum import Spectrum


@dataclass(frozen=True)
class ModalEnergy:
    """Energy fractions per mode (rows) [-]; each row sums to 1.

    ``strain[i, j]``: share of mode i's strain energy in the springs of
    stiffness ``springs[j]`` (a rigid-body mode has none: its row is 0).
    ``kinetic[i, j]``: share of its kinetic energy in member ``members[j]``.
    ``strain_by_element`` splits the strain energy per individual spring,
    named by ``elements``.
    """

    springs: tuple[str, ...]
    strain: np.ndarray
    members: tuple[str, ...]
    kinetic: np.ndarray
    elements: tuple[str, ...]
    strain_by_element: np.ndarray


def modal_energy(spectrum: Spectrum) -> ModalEnergy:
    """Modal strain and kinetic energy distribution of ``spectrum``."""
    network = spring_network(spectrum.params)
    element_energy = network.k[:, None] * (network.G @ spectrum.shapes) ** 2
    total = element_energy.sum(axis=0)
    elastic = total > 0
    by_element = np.zeros_like(element_energy)
    by_element[:, elastic] = element_energy[:, elastic] / total[elastic]
    springs = tuple(p for p in STIFFNESS_FIELDS if p in network.parameter)
    strain = np.array([by_element[network.rows_of(p)].sum(axis=0) for p in springs]).T

    member_of = dof_members(spectrum.params.n_planets)
    members = tuple(dict.fromkeys(member_of))
    dof_energy = spectrum.mass[:, None] * spectrum.shapes**2
    kinetic = np.array(
        [dof_energy[[m == name for m in member_of]].sum(axis=0) for name in members]
    ).T
    return ModalEnergy(springs, strain, members, kinetic, network.label, by_element.T)
