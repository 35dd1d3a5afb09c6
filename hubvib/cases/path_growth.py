"""The LEFM growth of a ring-gear root crack for a design, without output (SI inside).

The design gives the ring, its supports, the material and the planet's mesh force
(``hubvib.reducer.stages.mesh_force``).  The load sits at the worst point of the mesh cycle
for the ring tooth's root (``single_contact_radius``) or, with ``load = "envelope"``, at
the position of the mesh cycle that drives each step hardest (``mesh_cycle_positions``).
``grow_path`` grows the crack (``fem.crack_propagation``); ``hubvib.studies.lefm_path``
writes the files of ``hubvib crack-path``, and ``hubvib.cases.predicted_path`` caches the
path a crack sweep follows.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from hubvib.reducer.stages import gear_body, material, mesh_force, ring_gear
from hubvib.design.model import ReducerDesign
from hubvib.fem.crack_propagation import CrackGrowth, GrowthOptions, LoadPosition, grow_crack
from hubvib.fem.mesh_cycle import GearPair
from hubvib.meshing.polyline_crack import backup_ratio, tooth_height
from hubvib.meshing.ring_gear import RingGear

#: Lewicki & Ballarini 1997 (NASA TM-107229): backup ratios 3.3 and 1.0 gave tooth
#: fractures, 0.3 rim fractures, 0.5 both (rim in the tests), predicted and tested
LEWICKI_TOOTH = (3.3, 1.0)
LEWICKI_RIM = (0.3,)
LEWICKI_MIXED = (0.5,)
#: the loads ``crack_path`` grows the crack under
LOADS = ("worst", "envelope")
#: positions of the mesh cycle in the envelope (besides the two single-pair ends)
ENVELOPE_POSITIONS = 9


def single_contact_radius(design: ReducerDesign) -> float:
    """Radius on the ring of the highest point of single tooth contact [m]: the end of the
    single-pair zone of the planet-ring mesh nearest the ring's tip."""
    ring, planet = ring_gear(design), gear_body(design, "planet")
    pair = GearPair(planet, ring)
    start, end = pair.path
    roll = float(pair.second_roll(end - pair.base_pitch))
    return math.hypot(roll, ring.gear.base_diameter / 2)


def mesh_cycle_positions(design: ReducerDesign,
                         n: int = ENVELOPE_POSITIONS) -> tuple[LoadPosition, ...]:
    """The load on a ring tooth over its engagement with a planet: ``n`` contact points
    evenly along the path of contact plus the two ends of the single-pair zone, at each
    the planet's mesh force [N] (single pair) or half of it (two pairs in contact; equal
    sharing, the pairs' stiffness difference neglected), on the ring radius [m] of that
    contact (kept 1e-9 inside the involute's ends)."""
    ring, planet = ring_gear(design), gear_body(design, "planet")
    pair = GearPair(planet, ring)
    start, end = pair.path
    single = (end - pair.base_pitch, start + pair.base_pitch)
    rolls = np.unique(np.concatenate([np.linspace(start, end, n), single]))
    low, high = sorted((ring.profile.form_radius, ring.profile.tip_radius))
    force = mesh_force(design)
    positions = []
    for s in rolls:
        radius = float(np.clip(pair.radii(s)[1], low * (1 + 1e-9), high * (1 - 1e-9)))
        shared = not single[0] - 1e-12 <= s <= single[1] + 1e-12
        positions.append(LoadPosition(radius, force * (0.5 if shared else 1.0)))
    return tuple(positions)


def loaded_ring(design: ReducerDesign) -> RingGear:
    """The design's ring with its load patch at ``single_contact_radius``."""
    ring = ring_gear(design)
    radius = single_contact_radius(design)
    return replace(ring, working_pressure_angle=math.acos(ring.gear.base_diameter / 2 / radius))


def cracked_tooth(ring: RingGear) -> int:
    """The tooth nearest the middle between support pads 0 and 1 (0 if all is held)."""
    supports = ring.supports
    if supports.count == 0:
        return 0
    angle = supports.first_angle + math.pi / supports.count
    return int(round(angle / (2 * math.pi) * ring.teeth)) % ring.teeth


@dataclass(frozen=True, eq=False)
class CrackPathResult:
    """A predicted crack path and what it severs.

    Attributes
    ----------
    design : str
    growth : CrackGrowth
    ring : RingGear
        The ring as loaded (load patch at the single-contact radius).
    tooth : int
    force : float
        Planet mesh force on the tooth [N].
    options : GrowthOptions
    files : tuple of str
        What was written.
    load : str
        ``"worst"`` (the single-contact point) or ``"envelope"`` (the mesh cycle's
        position that drives each step hardest).
    """

    design: str
    growth: CrackGrowth
    ring: RingGear
    tooth: int
    force: float
    options: GrowthOptions
    files: tuple = ()
    load: str = "worst"

    @property
    def backup_ratio(self) -> float:
        return backup_ratio(self.ring)

    def to_dict(self) -> dict:
        """JSON-ready (SI, K in MPa sqrt(m))."""
        g, ring = self.growth, self.ring
        return {
            "design": self.design,
            "path_m": g.path.tolist(),
            "k_i_mpa_sqrt_m": [s.k_i / 1e6 for s in g.steps],
            "k_ii_mpa_sqrt_m": [s.k_ii / 1e6 for s in g.steps],
            "kink_angle_deg": [math.degrees(s.kink_angle) for s in g.steps],
            "depth_m": [s.depth for s in g.steps],
            "fracture": g.fracture,
            "severed": g.severed,
            "exit_m": g.exit.point.tolist(),
            "backup_ratio": self.backup_ratio,
            "rim_thickness_m": ring.rim_thickness,
            "tooth_height_m": tooth_height(ring),
            "tooth": self.tooth,
            "load_radius_m": ring.load_radius,
            "force_N": self.force,
            "step_m": self.options.step,
            "steps": len(g.steps),
            "files": list(self.files),
            "load": self.load,
            **({"step_load_radius_m": [s.load_radius for s in g.steps],
                "k_eq_mpa_sqrt_m": [s.k_eq / 1e6 for s in g.steps]}
               if self.load == "envelope" else {}),
        }


def growth_inputs(design: ReducerDesign, tooth: int | None, load: str) -> tuple:
    """The loaded ring, the cracked tooth (default ``cracked_tooth``), the mesh force [N],
    the material and the load positions (``None``: the worst point) of a growth under
    ``load`` (``LOADS``); ``ValueError`` names a wrong ``load`` or ``tooth``."""
    if load not in LOADS:
        raise ValueError(f"load = {load!r}, allowed: {', '.join(LOADS)}")
    positions = mesh_cycle_positions(design) if load == "envelope" else None
    ring = loaded_ring(design)
    if tooth is None:
        tooth = cracked_tooth(ring)
    elif isinstance(tooth, bool) or not isinstance(tooth, int) or not 0 <= tooth < ring.teeth:
        raise ValueError(f"tooth = {tooth!r}, allowed integers 0..{ring.teeth - 1}")
    return ring, tooth, mesh_force(design), material(design), positions


def grow_path(design: ReducerDesign, options: GrowthOptions = GrowthOptions(),
              tooth: int | None = None, load: str = "worst", on_step=None) -> CrackPathResult:
    """Grow the root crack of ``design`` at ``tooth`` under ``load`` (``growth_inputs``);
    ``on_step(index, step)`` is called after each growth step's FE solution."""
    ring, tooth, force, steel, positions = growth_inputs(design, tooth, load)
    growth = grow_crack(ring, tooth, force, steel, options, positions=positions,
                        on_step=None if on_step is None else
                        lambda index, mesh, model, u, step: on_step(index, step))
    return CrackPathResult(design.name, growth, ring, tooth, force, options, load=load)
