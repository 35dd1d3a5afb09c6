"""The path a ring-gear root crack takes, predicted by LEFM for a design (SI inside).

The design gives the ring, its supports, the material and the planet's mesh force
(``hubvib.reducer.stages.mesh_force``).  The load sits at the worst point of the mesh cycle for the
ring tooth's root: the highest point of single tooth contact on the ring, the single-pair
contact nearest the ring's tip (largest bending arm), from the planet-ring path of contact
(``fem.mesh_cycle.GearPair``).  The cracked tooth is the one midway between two support
pads, where the rim bends most (tooth 0 when the whole outer surface is held).  The crack
grows from a radial root crack at the critical fillet point (``fem.crack_propagation``)
until it severs the tooth or the rim.

With ``load = "envelope"`` the crack is driven, at each step, by the position of the
mesh cycle that maximises the MTS driving force (``mesh_cycle_positions``: contact
radii along the planet-ring path of contact, the whole mesh force in the single-pair
zone, half of it where two pairs share the load) instead of the single worst position.

``crack_path`` runs it and writes, into a folder, the path on the ring (PNG), the cracked
mesh of every step (VTU) and the result (JSON).
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from hubvib.cases.path_growth import (ENVELOPE_POSITIONS, LEWICKI_MIXED, LEWICKI_RIM,
                                      LEWICKI_TOOTH, LOADS, CrackPathResult, cracked_tooth,
                                      growth_inputs, grow_path, loaded_ring,
                                      mesh_cycle_positions, single_contact_radius)
from hubvib.design.model import ReducerDesign
from hubvib.fem.crack_propagation import GrowthOptions, grow_crack
from hubvib.foundation.output import json_text, output_set, write_text
from hubvib.meshing.export import write_vtu
from hubvib.render.path_figure import render_path

__all__ = ["crack_path", "CrackPathResult", "LOADS", "ENVELOPE_POSITIONS", "LEWICKI_TOOTH",
           "LEWICKI_RIM", "LEWICKI_MIXED", "cracked_tooth", "loaded_ring",
           "mesh_cycle_positions", "single_contact_radius", "grow_path"]


def crack_path(design: ReducerDesign, options: GrowthOptions = GrowthOptions(),
               out: Path | None = None, tooth: int | None = None,
               load: str = "worst", on_step=None) -> CrackPathResult:
    """Grow the root crack of ``design`` at ``tooth`` (default ``cracked_tooth``) under
    ``load`` (``LOADS``, see the module docstring); with ``out``, write ``crack_path.png``,
    ``crack_step_NN.vtu`` per step and ``crack_path.json`` there, all or nothing.
    ``on_step(index, step)`` is called after each growth step's FE solution (progress)."""
    if out is None:
        return grow_path(design, options, tooth, load, on_step)
    ring, tooth, force, steel, positions = growth_inputs(design, tooth, load)
    out = Path(out)
    names = []
    with output_set(out) as staged:
        def write(index, mesh, model, u, step):
            names.append(f"crack_step_{index:02d}.vtu")
            write_vtu(mesh, staged / names[-1])
            if on_step is not None:
                on_step(index, step)

        growth = grow_crack(ring, tooth, force, steel, options, on_step=write,
                            positions=positions)
        names.append("crack_path.png")
        result = CrackPathResult(design.name, growth, ring, tooth, force, options, load=load)
        verb = "severs the" if growth.severed else "heads for the"
        render_path(ring, tooth, growth.path, staged / names[-1],
                    f"{design.name}: backup ratio {result.backup_ratio:.2f}, crack {verb} "
                    f"{growth.fracture} ({len(growth.steps)} steps of {1e3 * options.step:g} mm)")
        names.append("crack_path.json")
        files = tuple(str(out / n) for n in names)
        result = replace(result, files=files)
        write_text(staged / names[-1], json_text(result.to_dict()) + "\n")
    return result
