"""One mesh level of a crack case: c_ru, c_r and the cracked tooth's compliance from one
assembly and one factorisation (SI units).

The ring's torque and translation loads (``ring_stiffness``) and the unit
forces on the cracked tooth's flank (``tooth_fe``) act on the same model with
the same supports, so they are load columns of one solve.  The cracked tooth is
measured where the crack is (its own frame), and its engagement is compared with
the same tooth intact: the tooth's compliance relative to its root lands depends
on where it sits between the supports (tooth 5 of the Raba ring, between two
support arcs, differs from tooth 0, over one, by up to 4-6 % over the flank;
``tests/fem/test_elasticity_and_ring_stiffness.py``).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from hubvib.meshing.ring_pieces import RingPieces

from .elasticity import supported
from .material import Material
from .mesh_cycle import GearPair
from .ring_stiffness import (RingStiffness, check_ring_input, default_carrier_teeth,
                             ring_loads, ring_model, ring_response, root_lands)
from .ring_work import ring_work
from .substructure import substructured
from .tooth_fe import tooth_compliance, tooth_probe
from .tooth_stiffness import (EngagedMesh, ToothCurve, chebyshev_radii, contact_radii,
                              engaged_mesh)


@dataclass(frozen=True)
class CrackLevel:
    """The ring's stiffness and, with a crack, the cracked tooth's engagement on one mesh.

    ``engaged`` is None for an intact ring.  ``seconds``: assembly, loads, solve, measure
    and engaged (the mesh cycles, with the intact curves when first needed) [s].
    ``intact_tooth``: an intact ring's tooth curve when asked for (``ring_and_tooth``).
    """

    ring: RingStiffness
    cracked_tooth: ToothCurve | None
    engaged: EngagedMesh | None
    seconds: dict
    intact_tooth: ToothCurve | None = None


def ring_and_tooth(ring, planet, crack, mesh, material: Material = Material(),
                   n_planets: int = 3, solver: str = "auto", intact_tooth: int | None = None
                   ) -> tuple[RingStiffness, ToothCurve | None]:
    """c_ru at every carrier position over one planet pitch, c_r (root-land readings and the
    work-conjugate values with their rim parts, ``RingStiffness.work``) and (when ``crack`` has a
    depth) the cracked ring tooth's compliance at the Chebyshev radii of its contact span
    with ``planet``, all from one factorisation of the model of ``mesh``.

    ``intact_tooth`` (an intact ring only): the compliance of that tooth instead, by a
    solve of its own on the same factorisation: the floats ``tooth_fe.fe_tooth_compliance``
    gives on ``mesh`` (the same model, factorisation and load columns).

    ``mesh`` may be a ``meshing.ring_pieces.RingPieces``: the model of its glued mesh is
    then solved by substructures (``fem.substructure``), the same solution to round-off
    with only the crack's block and the ring of cuts factorised."""
    pieces = mesh if isinstance(mesh, RingPieces) else None
    mesh = mesh.mesh if pieces is not None else mesh
    check_ring_input(ring, mesh, n_planets)
    cracked = crack is not None and crack.depth > 0
    if cracked and intact_tooth is not None:
        raise ValueError("intact_tooth: an intact ring only (crack given)")
    t0 = time.perf_counter()
    model = ring_model(ring, mesh, material)
    t1 = time.perf_counter()
    loads = ring_loads(model, ring, default_carrier_teeth(ring, n_planets), n_planets)
    columns = [loads.loads]
    probe = None
    if cracked:
        radii = chebyshev_radii(*contact_radii(ring, [GearPair(planet, ring)]))
        probe = tooth_probe(ring, model, radii, crack.tooth)
        columns.append(probe.loads)
    t2 = time.perf_counter()
    system = (supported(model, ["supports"], solver=solver) if pieces is None
              else substructured(pieces, model, material, ring.gear.face_width, solver))
    try:
        solution = system.solve(np.hstack(columns))
        if intact_tooth is not None:
            radii = chebyshev_radii(*contact_radii(ring, [GearPair(planet, ring)]))
            probe = tooth_probe(ring, model, radii, intact_tooth)
            own = system.solve(probe.loads)
    finally:
        system.release()
    t3 = time.perf_counter()
    ring_columns = loads.loads.shape[1]
    c_ru, c_r = ring_response(model, ring, loads, solution.u[:, :ring_columns])
    work = ring_work(model, ring, loads, solution.u[:, :ring_columns], loads.forces,
                     root_lands(model, range(ring.teeth)))
    curve = None
    if cracked:
        curve = ToothCurve(probe.radii, tooth_compliance(probe, solution.u[:, ring_columns:]),
                           model.ndofs)
    elif intact_tooth is not None:
        curve = ToothCurve(probe.radii, tooth_compliance(probe, own.u), model.ndofs)
    t4 = time.perf_counter()
    result = RingStiffness(float(c_ru.mean()), c_ru, loads.carrier_teeth, c_r, model.ndofs,
                           {"assembly": t1 - t0, "loads": t2 - t1, "solve": t3 - t2,
                            "measure": t4 - t3, "solver": system.method}, work)
    return result, curve


def crack_level(ring, planet, crack, mesh, options, material: Material = Material(),
                n_planets: int = 3, solver: str = "auto",
                intact_tooth: int | None = None) -> CrackLevel:
    """``ring_and_tooth`` on ``mesh`` (meshed with ``options``) and, with a crack, the
    cracked tooth's engagement against the same tooth intact (its intact curves meshed
    with ``options`` too, and kept between calls); ``intact_tooth`` as in
    ``ring_and_tooth`` (``CrackLevel.intact_tooth``)."""
    result, curve = ring_and_tooth(ring, planet, crack, mesh, material, n_planets, solver,
                                   intact_tooth)
    seconds = {k: v for k, v in result.seconds.items() if k != "solver"}
    if intact_tooth is not None:  # an intact ring: the curve is its intact tooth's
        return CrackLevel(result, None, None, seconds | {"engaged": 0.0}, curve)
    started = time.perf_counter()
    engaged = (None if curve is None
               else engaged_mesh(planet, ring, curve, options, material, crack.tooth))
    return CrackLevel(result, curve, engaged,
                      seconds | {"engaged": time.perf_counter() - started})
