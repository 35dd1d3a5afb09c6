"""Which rigid-ring mode an elastic-ring mode is, by shape (SI).

The elastic ring's coupled modes carry the lumped bodies (sun, carrier, planets) as the
9 + 3N model does, without the ring's own three coordinates (its body is the FE ring).
On those common lumped coordinates each coupled mode's lumped part is compared with every
rigid-ring mode shape by the mass-weighted modal assurance criterion
``MAC = (a^T M b)^2 / ((a^T M a)(b^T M b))``; the best rigid mode and its MAC name the
pair.  A MAC near 1 means the same motion of the lumped bodies, near 0 a mode of the ring
the rigid model does not have.
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
    rigid = np.asarray(rigid_spectrum.shapes)[keep]
    elastic = np.asarray(elastic_modes.lumped)
    cross = elastic.T @ (mass[:, None] * rigid)
    own_e = np.einsum("im,i,im->m", elastic, mass, elastic)
    own_r = np.einsum("im,i,im->m", rigid, mass, rigid)
    with np.errstate(divide="ignore", invalid="ignore"):
        mac = np.where(own_e[:, None] > 0, cross ** 2 / (own_e[:, None] * own_r[None]), 0.0)
    best = mac.argmax(axis=1)
    f_rigid = np.asarray(rigid_spectrum.omega) / (2 * np.pi)
    f_elastic = np.asarray(elastic_modes.frequency_hz)
    # a coupled mode is mass-normalised over ring and lumped bodies: its lumped part's
    # kinetic energy share is a^T M a
    share = np.clip(own_e, 0.0, 1.0)
    return tuple(ModePair(str(elastic_labels[j]), float(f_elastic[j]),
                          str(rigid_labels[best[j]]), float(f_rigid[best[j]]),
                          float(mac[j, best[j]]), float(share[j]))
                 for j in range(min(len(elastic_labels), elastic.shape[1])))
