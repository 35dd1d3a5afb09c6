"""Which rigid-ring mode an elastic-ring mode is, by shape (SI).

The elastic ring's coupled modes carry the lumped bodies (sun, carrier, planets) as the
9 + 3N model does, without the ring's own three coordinates (its body is the FE ring).
On those common lumped coordinates each coupled mode's lumped part is compared with every
rigid-ring mode shape by the mass-weighted modal assurance criterion
``MAC = (a^T M b)^2 / ((a^T M a)(b^T M b))``; the best rigid mode and its MAC name the
pair.  A MAC near 1 means the same motion of the lumped bodies, near 0 a mode of the ring
the rigid model does not have.  A repeated rigid frequency (cyclic symmetry) has no
preferred basis: it is one candidate, its MAC the share of the elastic mode's lumped part
in the pair's span (``rigid 13/14``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["ModePair", "mode_map"]


@dataclass(frozen=True)
class ModePair:
    """One elastic-ring mode and the rigid-ring mode its lumped part resembles most.

    ``elastic``, ``rigid``: the modes' labels; ``elastic_hz``, ``rigid_hz`` [Hz];
    ``mac`` [-] on the lumped coordinates; ``lumped_share``: the elastic mode's kinetic
    energy share in the lumped bodies [-] (small: a mode of the ring's own)."""

    elastic: str
    elastic_hz: float
    rigid: str
    rigid_hz: float
    mac: float
    lumped_share: float

    def row(self) -> dict:
        return {"elastic_mode": self.elastic, "elastic_hz": self.elastic_hz,
                "rigid_mode": self.rigid, "rigid_hz": self.rigid_hz, "mac": self.mac,
                "elastic_lumped_energy_share": self.lumped_share}


def mode_map(rigid_spectrum, rigid_labels, elastic_modes, elastic_labels,
             ring_dofs=(4, 5, 8)) -> tuple[ModePair, ...]:
    """Per elastic mode (``elastic_modes``: a coupled spectrum's modes with ``lumped``
    (lumped DOFs, modes), ``lumped_mass`` (lumped DOFs,) [kg] and ``frequency_hz``) the
    rigid mode of ``rigid_spectrum`` (a ``lumped.Spectrum``: ``shapes`` (9 + 3N, modes),
    ``mass`` (9 + 3N,) [kg], ``omega`` [rad/s]) with the largest MAC on the lumped
    coordinates without ``ring_dofs`` (the 9 + 3N model's x_r, y_r, u_r)."""
    keep = np.array([i for i in range(rigid_spectrum.shapes.shape[0]) if i not in ring_dofs])
    mass = np.asarray(elastic_modes.lumped_mass, dtype=float)
    if mass.size != keep.size:
        raise ValueError(f"the elastic modes have {mass.size} lumped coordinates, the rigid "
                         f"model {keep.size} besides the ring's: they must be the same bodies")
    from .mode_names import repeated_groups

    rigid = np.asarray(rigid_spectrum.shapes)[keep]
    elastic = np.asarray(elastic_modes.lumped)
    f_rigid = np.asarray(rigid_spectrum.omega) / (2 * np.pi)
    f_elastic = np.asarray(elastic_modes.frequency_hz)
    own = np.einsum("im,i,im->m", elastic, mass, elastic)
    groups = repeated_groups(rigid_spectrum.omega)
    mac = np.zeros((elastic.shape[1], len(groups)))
    for g, members in enumerate(groups):
        B = rigid[:, members]
        gram = B.T @ (mass[:, None] * B)
        cross = elastic.T @ (mass[:, None] * B)  # (elastic modes, members)
        projected = np.einsum("em,mn,en->e", cross, np.linalg.pinv(gram), cross)
        mac[:, g] = np.where(own > 0, projected / np.where(own > 0, own, 1.0), 0.0)
    best = mac.argmax(axis=1)

    def label(members) -> str:
        if len(members) == 1:
            return str(rigid_labels[members[0]])
        first = str(rigid_labels[members[0]])
        head, rest = first.split(" (", 1) if " (" in first else (first, "")
        numbers = "/".join(str(i + 1) for i in members)
        return f"rigid {numbers} ({rest}" if rest else f"rigid {numbers}"

    # a coupled mode is mass-normalised over ring and lumped bodies: its lumped part's
    # kinetic energy share is a^T M a
    share = np.clip(own, 0.0, 1.0)
    return tuple(ModePair(str(elastic_labels[j]), float(f_elastic[j]),
                          label(groups[best[j]]), float(f_rigid[groups[best[j]][0]]),
                          float(np.clip(mac[j, best[j]], 0.0, 1.0)), float(share[j]))
                 for j in range(min(len(elastic_labels), elastic.shape[1])))
