"""Every stiffness of a design's lumped model with its error estimate and run time: the FE
ring (c_ru, c_r: the work-conjugate rim parts the lumped model uses, the root-land
readings beside them; plane, and solid on request), the FE mesh stiffness (c_sp, c_rp, mean over
the mesh cycle) and the bearings (c_p, c_c, Palmgren line contact).  ``hubvib stiffness``
prints it.  SI units: N/m, m, s."""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

from hubvib.reducer import bearing_stiffness, gear_body, material, ring_gear
from hubvib.reducer.stages import FE_MESH, FE_RING, ISO_MESH, ISO_SINGLE, labelled
from hubvib.fem.estimate import RingEstimate, estimate_mesh, estimate_ring
from hubvib.meshing.crack import Crack


@dataclass(frozen=True)
class BearingStiffness:
    """One bearing's stiffness (c_p or c_c, Palmgren line contact).

    Attributes
    ----------
    tangent, secant : float
        Tangent stiffness at the operating load (the lumped model's) and secant [N/m].
    load : float
        The load it is taken at [N].
    rollers : int
        Rollers of the bearing.
    roller_length : float
        Effective roller length [m].
    method, secant_method : str
        How ``hubvib design check`` names the two values.
    seconds_total : float
        Time it took [s].
    sun_torque : float
        The design's sun torque [N m] (the operating point).
    """

    tangent: float
    secant: float
    load: float
    rollers: int
    roller_length: float
    method: str
    secant_method: str
    seconds_total: float
    sun_torque: float

    def to_dict(self) -> dict:
        """The JSON row of ``hubvib stiffness`` (keys with units; ``value_N_m`` the tangent)."""
        return {"tangent_N_m": self.tangent, "secant_N_m": self.secant, "load_N": self.load,
                "rollers": self.rollers, "roller_length_m": self.roller_length,
                "method": self.method, "secant_method": self.secant_method,
                "value_N_m": self.tangent, "seconds_total": self.seconds_total,
                "sun_torque_N_m": self.sun_torque}


def bearing_rows(design) -> dict[str, BearingStiffness]:
    """c_p and c_c of the design's bearings (those it gives), with the time they took [s]
    (read from ``reducer.bearing_stiffness``'s rows: their edge)."""
    started = time.perf_counter()
    rows = bearing_stiffness(design)
    seconds = time.perf_counter() - started
    return {key: BearingStiffness(row["tangent_N_m"], row["secant_N_m"], row["load_N"],
                                  row["rollers"], row["roller_length_m"], row["method"],
                                  row["secant_method"], seconds, design.sun_torque)
            for key, row in rows.items()}


@dataclass(frozen=True)
class StiffnessCase:
    """One case of ``hubvib stiffness`` (intact, or cracked), typed.

    Attributes
    ----------
    ring : fem.estimate.RingEstimate
        The plane ring's c_ru and c_r (the rim parts; the root-land readings beside).
    mesh : dict of str to fem.estimate.MeshEstimate
        ``"c_sp"`` and ``"c_rp"``: the FE mesh stiffness over the mesh cycle.
    bearings : dict of str to BearingStiffness
        ``"c_p"`` and ``"c_c"`` where the design gives the bearing.
    ring_solid : fem.estimate.RingEstimate or None
        The solid ring's, on request.
    cracked : bool
        Whether ``mesh["c_rp"]`` carries the cracked tooth's engagement for this case.
    """

    ring: RingEstimate
    mesh: dict
    bearings: dict
    ring_solid: RingEstimate | None = None
    cracked: bool = False

    def rings(self) -> dict[str, RingEstimate]:
        """The ring estimates by row suffix (``""`` plane, ``" 3D"`` solid)."""
        return {"": self.ring} | ({} if self.ring_solid is None else {" 3D": self.ring_solid})

    def to_dict(self) -> dict[str, dict]:
        """Quantity -> JSON row (``value_N_m``, ``error_N_m``, ``seconds_total``, ...): the
        JSON of ``hubvib stiffness``, the output edge."""
        rows = {}
        for suffix, ring in self.rings().items():
            rows.update(_ring_rows(ring, suffix))
        rows.update({key: e.to_dict(engaged=self.cracked) for key, e in self.mesh.items()})
        rows.update({key: b.to_dict() for key, b in self.bearings.items()})
        return rows

    def named_values(self) -> dict[str, float]:
        """Every value by ``key (method)`` [N/m]: the names ``hubvib design check`` gives
        its values (``hubvib.reducer.stages.labelled``), so one name holds one value
        wherever it is printed."""
        out = {}
        for suffix, ring in self.rings().items():
            out[labelled("c_ru", RING_METHODS[suffix])] = ring.c_ru
            out[labelled("c_r", RING_METHODS[suffix])] = ring.c_r
        for key, e in self.mesh.items():
            out[labelled(key, FE_MESH)] = e.value
            out[labelled(key, ISO_MESH)] = e.iso_c_gamma
            out[labelled(key, ISO_SINGLE)] = e.iso_c_single
        for key, b in self.bearings.items():
            out[labelled(key, b.method)] = b.tangent
            out[labelled(key, b.secant_method)] = b.secant
        return out


def stiffness_parts(crack_depth: float = 0.0, solid: bool = False) -> int:
    """How many FE parts ``stiffness_table`` computes (the mesh stiffness, then the ring per
    case, plane and solid): its ``on_part`` calls."""
    return 1 + (2 if crack_depth > 0 else 1) * (2 if solid else 1)


def stiffness_table(design, crack_depth: float = 0.0, solver: str = "auto",
                    solid: bool = False, on_part=None) -> dict[str, StiffnessCase]:
    """Case name ("intact", and "crack D m" when ``crack_depth`` [m] > 0, a root crack at
    tooth 0) -> its ``StiffnessCase`` (c_ru, c_r, [c_ru 3D, c_r 3D,] c_sp, c_rp, c_p, c_c;
    ``StiffnessCase.to_dict``: the JSON of ``hubvib stiffness``).

    ``on_part(label)`` is called after each FE part (``stiffness_parts`` of them: progress).

    Raises ``ValueError`` naming the design or ``--crack-depth`` for a design whose planets
    are not equally spaced (the FE ring model loads equally spaced planets only) or a depth
    that is not a finite number >= 0.
    """
    if not design.equally_spaced:
        raise ValueError(f"design {design.name!r}: the FE ring model loads equally spaced planets "
                         "only")
    if not (math.isfinite(crack_depth) and crack_depth >= 0):
        raise ValueError(f"--crack-depth = {crack_depth!r}; allowed: a finite depth >= 0 [m] "
                         "(0 = intact only)")
    ring, steel = ring_gear(design), material(design)
    cases = {"intact": None}
    if crack_depth > 0:
        crack = Crack(0, crack_depth)
        crack.path(ring)  # validate before any meshing
        cases[f"crack {crack_depth:g} m"] = crack
    # c_sp, c_rp are intact means in both cases; the cracked run adds the cracked tooth's
    # engagement to c_rp, so one run serves both
    done = on_part or (lambda label: None)
    estimates = estimate_mesh(gear_body(design, "sun"), gear_body(design, "planet"), ring,
                              list(cases.values())[-1], material=steel)
    done("c_sp, c_rp")
    bearings = bearing_rows(design)
    out = {}
    for name, crack in cases.items():
        ring_options = dict(solver=solver, material=steel, n_planets=design.n_planets,
                            definition="rim")
        plane = estimate_ring(ring, crack, **ring_options)
        done(f"c_ru, c_r {name}")
        solid_ring = None
        if solid:
            solid_ring = estimate_ring(ring, crack, solid=True, **ring_options)
            done(f"c_ru, c_r {name}, solid")
        out[name] = StiffnessCase(plane, estimates, bearings, solid_ring,
                                  cracked=crack is not None)
    return out


#: the methods of the ring rows' values, by row suffix ("" plane, " 3D" solid)
RING_METHODS = {"": FE_RING, " 3D": f"{FE_RING}, solid"}


def _ring_rows(r: RingEstimate, suffix: str) -> dict:
    """The JSON rows of one ring estimate (keys with units: the output boundary); the
    root-land readings beside the values (``root_land_N_m``, ``root_land_error_N_m``)."""
    common = {"seconds_total": r.seconds_total, "dofs": r.dofs, "solver": r.solver}
    return {f"c_ru{suffix}": {"value_N_m": r.c_ru, "error_N_m": r.c_ru_error,
                              "min_N_m": r.c_ru_min, "max_N_m": r.c_ru_max,
                              "root_land_N_m": r.c_ru_root_land,
                              "root_land_error_N_m": r.c_ru_root_land_error, **common},
            f"c_r{suffix}": {"value_N_m": r.c_r, "error_N_m": r.c_r_error,
                             "root_land_N_m": r.c_r_root_land,
                             "root_land_error_N_m": r.c_r_root_land_error, **common}}
