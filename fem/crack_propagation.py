"""Growth of a ring-gear root crack by linear elastic fracture mechanics (SI units).

From a short radial root crack at the critical fillet point of tooth ``tooth``, each step

1. meshes the ring with the crack so far (``meshing.polyline_crack.path_ring_mesh``),
2. solves plane stress under the planet's mesh force ``force`` [N] on that tooth's load
   patch, along the line of action, with the supports clamped,
3. takes K_I, K_II at the tip from the interaction integral (``fem.fracture``) over an
   annulus of outer radius ``domain x step`` (inside the last straight segment),
4. turns the crack by the maximum-tangential-stress angle and extends it by ``step``,

until the next step would reach a surface: the toothed inner boundary (the tooth breaks
off: ``"tooth"``) or the outer surface (the rim breaks: ``"rim"``).

With ``positions`` (the load envelope over the mesh cycle) step 2 solves, with the same
factorisation, one load case per ``LoadPosition`` (its force along the line of action at
its contact radius on the tooth's flank, ``fem.tooth_fe.tooth_probe``), and step 4 turns
the crack by the MTS angle of the position with the largest MTS driving force
``sigma_theta_theta sqrt(2 pi r)`` (``fem.fracture.mts_driving_force``).  A crack that has not
severed anything after ``max_steps`` is classified by where its current direction leaves
the body, and ``severed`` is false.  The magnitude of the load scales K, not the path.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np

from hubvib.meshing.polyline_crack import (Exit, PathCrack, initial_crack, path_ring_mesh,
                                       ray_exit, surface_gap)
from hubvib.meshing.gear import rotation
from hubvib.meshing.ring_gear import RingGear
from hubvib.meshing.ring_mesh import MeshOptions

from .elasticity import plane_model, solve
from .fracture import interaction_integral, mts_angle, mts_driving_force
from .material import Material
from .ring_stiffness import mesh_force_load
from .tooth_beam import load_point
from .tooth_fe import INSIDE

#: the crack stops when the next step would leave less than this many steps of ligament
SEVER_STEPS = 1.5


class GrowthError(ValueError):
    """Growth parameters out of range; the message names the parameter and the range."""


@dataclass(frozen=True)
class GrowthOptions:
    """How the crack is grown.

    Parameters
    ----------
    step : float
        Crack extension per step [m].
    initial_depth : float
        Length of the initial radial root crack [m].
    max_steps : int
        Most steps (FE solutions).
    domain : float
        Outer radius of the interaction-integral annulus over the step [-], < 1.
    tip_cells : float
        That radius over the element size at the tip [-].
    mesh : MeshOptions
        Element sizes away from the tip (``tip_size`` is set from the two above).
    """

    step: float = 0.5e-3
    initial_depth: float = 0.5e-3
    max_steps: int = 40
    domain: float = 0.4
    tip_cells: float = 8.0
    mesh: MeshOptions = field(default_factory=MeshOptions)

    def __post_init__(self):
        for name, low, high in (("step", 1e-5, 1e-2), ("initial_depth", 1e-5, 1e-2),
                                ("domain", 0.05, 0.9), ("tip_cells", 2.0, 50.0)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                    math.isfinite(value) and low <= value <= high):
                raise GrowthError(f"{name} = {value!r}, allowed {low:g}..{high:g}")
        if isinstance(self.max_steps, bool) or not isinstance(self.max_steps, int) or not (
                1 <= self.max_steps <= 500):
            raise GrowthError(f"max_steps = {self.max_steps!r}, allowed integers 1..500")

    @property
    def r_out(self) -> float:
        """Outer radius of the integration annulus [m]."""
        return self.domain * min(self.step, self.initial_depth)

    @property
    def mesh_options(self) -> MeshOptions:
        return replace(self.mesh, tip_size=self.r_out / self.tip_cells)


@dataclass(frozen=True)
class GrowthStep:
    """One FE solution of the growth.

    Attributes
    ----------
    tip : tuple
        Crack tip analysed [m].
    direction : tuple
        Unit direction of the crack at the tip.
    k_i, k_ii : float
        Stress intensity factors [Pa sqrt(m)].
    kink_angle : float
        MTS turn of the next segment from ``direction`` [rad], counter-clockwise positive.
    depth : float
        Crack length along the path [m].
    dofs : int
    load_radius : float or None
        With a load envelope: the contact radius [m] of the position that drove the step.
    k_eq : float or None
        With a load envelope: its MTS driving force [Pa sqrt(m)].
    """

    tip: tuple
    direction: tuple
    k_i: float
    k_ii: float
    kink_angle: float
    depth: float
    dofs: int
    load_radius: float | None = None
    k_eq: float | None = None


@dataclass(frozen=True)
class LoadPosition:
    """One position of the mesh cycle: ``force`` [N] along the line of action at contact
    radius ``radius`` [m] on the cracked tooth's +psi flank."""

    radius: float
    force: float


@dataclass(frozen=True, eq=False)
class CrackGrowth:
    """The grown crack.

    Attributes
    ----------
    crack : PathCrack
        The last crack analysed (mouth, then each analysed tip).
    steps : tuple of GrowthStep
    fracture : str
        ``"tooth"`` or ``"rim"``: the surface the crack reaches (or, if not ``severed``,
        the surface its last direction leads to).
    severed : bool
        The crack reached a surface within ``max_steps``.
    exit : Exit
        Where the path leaves (or would leave) the body.
    """

    crack: PathCrack
    steps: tuple
    fracture: str
    severed: bool
    exit: Exit

    @property
    def path(self) -> np.ndarray:
        """Mouth, every analysed tip, and the exit point if severed [m] (n, 2)."""
        points = self.crack.array
        return np.vstack([points, self.exit.point]) if self.severed else points


def grow_crack(ring: RingGear, tooth: int, force: float, material: Material = Material(),
               options: GrowthOptions = GrowthOptions(),
               on_step: Callable | None = None, positions=None) -> CrackGrowth:
    """Grow the root crack of ``tooth`` under ``force`` [N] along the line of action at
    ``ring.load_radius`` (see the module docstring), or with ``positions`` (a sequence of
    ``LoadPosition``) under the one of them that drives the crack hardest at each step.

    ``on_step(index, mesh, model, u, step)`` is called after each FE solution (to write
    the cracked meshes, for example).
    """
    if not (isinstance(force, (int, float)) and math.isfinite(force) and force > 0):
        raise GrowthError(f"force = {force!r} N, allowed > 0")
    if positions is not None and (len(positions) == 0 or not all(
            math.isfinite(p.force) and p.force > 0 for p in positions)):
        raise GrowthError(f"positions: {len(positions)} load positions; need >= 1, each "
                          "with a finite force > 0 N")
    crack = initial_crack(ring, tooth, options.initial_depth)
    mesh_options = options.mesh_options
    steps = []
    for index in range(options.max_steps):
        mesh = path_ring_mesh(ring, crack, mesh_options)
        model = plane_model(mesh, material, ring.gear.face_width, "stress")
        radius = min(options.r_out, options.domain * crack.last_segment)
        if positions is None:
            load = mesh_force_load(model, ring, [tooth], force)
            u = solve(model, load, ["supports"], solver="superlu").u
            sif = interaction_integral(model, u, crack.tip, crack.direction, radius)
            extra = {}
        else:
            u, sif, extra = _envelope(model, ring, tooth, positions, crack, radius)
        theta = mts_angle(sif.k_i, sif.k_ii)
        step = GrowthStep(tuple(crack.tip.tolist()), tuple(crack.direction.tolist()),
                          sif.k_i, sif.k_ii, theta, crack.depth, model.ndofs, **extra)
        steps.append(step)
        if on_step is not None:
            on_step(index, mesh, model, u, step)
        heading = rotation(theta) @ crack.direction
        leaves = ray_exit(ring, tooth, crack.tip, heading)
        if leaves.distance < SEVER_STEPS * options.step:
            return CrackGrowth(crack, tuple(steps), leaves.surface, True, leaves)
        tip = crack.tip + options.step * heading
        if surface_gap(ring, tooth, tip) < 0.5 * options.step:
            return CrackGrowth(crack, tuple(steps), leaves.surface, True, leaves)
        if index == options.max_steps - 1:
            break
        crack = crack.extended(tip)
    return CrackGrowth(crack, tuple(steps), leaves.surface, False, leaves)


def flank_loads(model, ring: RingGear, tooth: int, positions) -> np.ndarray:
    """Load vectors [N] (ndofs, positions): each position's force along the line of
    action (the flank normal, into the tooth) at its radius on ``tooth``'s +psi flank,
    applied at a point ``INSIDE`` the material along that line (as ``fem.tooth_fe``)."""
    rot = rotation(ring.tooth_angle(tooth))
    at = [load_point(ring, p.radius) for p in positions]
    directions = np.array([d for _, d in at])
    points = (np.array([q for q, _ in at]) + INSIDE * directions) @ rot.T
    forces = directions @ rot.T * np.array([[p.force] for p in positions])
    probes = model.probes(points)  # rows: u_x at each point, then u_y
    n = len(positions)
    return (probes[:n].multiply(forces[:, :1]) + probes[n:].multiply(forces[:, 1:])).T.toarray()


def _envelope(model, ring, tooth, positions, crack, radius):
    """Every load position solved with one factorisation; the displacement [m], SIFs and
    step fields of the one with the largest MTS driving force."""
    loads = flank_loads(model, ring, tooth, positions)
    u = solve(model, loads, ["supports"], solver="superlu").u
    sifs = [interaction_integral(model, u[:, k], crack.tip, crack.direction, radius)
            for k in range(len(positions))]
    drive = [mts_driving_force(s.k_i, s.k_ii) for s in sifs]
    best = int(np.argmax(drive))
    if drive[best] <= 0:
        raise GrowthError(f"no load position opens the crack at depth {crack.depth:.6g} m "
                          "(K_I < 0 at every one)")
    return u[:, best], sifs[best], {"load_radius": float(positions[best].radius),
                                    "k_eq": float(drive[best])}
