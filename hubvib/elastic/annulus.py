"""A plain free annulus's in-plane modes by the project's FE, with their nodal diameters
(plane stress, P2; SI units): the check of the ring model against ring theory."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hubvib.fem.elasticity import plane_model
from hubvib.fem.material import Material
from hubvib.fem.modal import lowest_modes
from hubvib.meshing.annulus import annulus_mesh

from .content import diameter_content

PROBE_POINTS = 256


@dataclass(frozen=True)
class AnnulusModes:
    """Elastic modes (rigid-body modes dropped) [Hz] with each one's nodal diameters."""

    frequency_hz: np.ndarray
    nodal_diameter: np.ndarray
    dofs: int


def annulus_modes(inner_radius: float, outer_radius: float, width: float,
                  material: Material = Material(), count: int = 20,
                  size: float | None = None) -> AnnulusModes:
    """The ``count`` lowest elastic in-plane modes of a free annulus [m]; ``size``: element
    size [m] (default a quarter of the wall thickness)."""
    wall = outer_radius - inner_radius
    if not (0 < inner_radius < outer_radius):
        raise ValueError(f"annulus radii {inner_radius!r}, {outer_radius!r}: allowed "
                         "0 < inner < outer [m]")
    mesh = annulus_mesh(inner_radius, outer_radius, size or wall / 4, order=2)
    model = plane_model(mesh, material, thickness=width)
    modes = lowest_modes(model, count + 3, None)
    elastic = modes.omega > 1e-3 * modes.omega.max()
    radius = 0.5 * (inner_radius + outer_radius)
    angles = 2 * np.pi * np.arange(PROBE_POINTS) / PROBE_POINTS
    at = model.probes(radius * np.column_stack([np.cos(angles), np.sin(angles)]))
    ux, uy = at[:PROBE_POINTS] @ modes.shapes, at[PROBE_POINTS:] @ modes.shapes
    c, s = np.cos(angles)[:, None], np.sin(angles)[:, None]
    probe = np.vstack([c * ux + s * uy, -s * ux + c * uy])
    n = np.array([int(np.argmax(diameter_content(probe[:, j]))) for j in range(probe.shape[1])])
    keep = np.flatnonzero(elastic)[:count]
    return AnnulusModes(modes.hertz[keep], n[keep], model.ndofs)
