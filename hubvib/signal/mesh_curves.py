"""Mesh stiffness over the mesh cycle, intact and over a cracked ring tooth's engagement (SI).

The curves come from the FE stage (``hubvib.fem.tooth_stiffness``: FE tooth
compliance of sun, planet and ring tooth at Chebyshev radii, Hertz contact,
load sharing over the path of contact) and are functions of the roll length on
the planet [m] (:mod:`hubvib.signal.mesh_phase` says where each planet is).
Each FE tooth curve is cached as JSON under ``$HUBVIB_CACHE/signal-curves`` by a
hash of everything that decides it (body, contact radii, material, mesh
options, crack, and the source of every hubvib module this one imports), so a scene
that changes only the sensor or the speed does not re-solve FE.
:func:`synthetic_curves` gives the same curves with constant tooth compliances (no
FE), for tests.
"""
from __future__ import annotations

import json
from dataclasses import asdict, dataclass, replace

import numpy as np

from hubvib.reducer.stages import gear_body, ring_gear
from hubvib.fem.material import Material
from hubvib.fem.mesh_cycle import GearPair, mesh_cycle
from hubvib.fem.tooth_beam import hertz_compliance
from hubvib.fem.tooth_stiffness import ToothCurve, contact_radii, fe_curve
from hubvib.meshing.cache import root_folder
from hubvib.meshing.crack import Crack
from hubvib.meshing.levels import scaled_options
from hubvib.runtime.fe_cache import CacheEntryError, entry_key, read_entry, write_entry

#: the entry module of the cached tooth curves: their source key
SOURCE = (__name__,)


@dataclass(frozen=True)
class MeshCurves:
    """Mesh stiffness [N/m] against the roll length on the planet [m].

    Attributes
    ----------
    base_pitch : float
        Period of the intact curves [m].
    sun_s, sun_k, ring_s, ring_k : ndarray
        Intact sun-planet and ring-planet cycle over one base pitch.
    cracked_s, cracked_k : ndarray or None
        Ring-planet stiffness over the engagement of the cracked ring tooth (roll
        length of *that* tooth's contact, one pitch of intact mesh on either side).
    depth : float
        Crack depth [m] (0: intact).
    """

    base_pitch: float
    sun_s: np.ndarray
    sun_k: np.ndarray
    ring_s: np.ndarray
    ring_k: np.ndarray
    cracked_s: np.ndarray | None = None
    cracked_k: np.ndarray | None = None
    depth: float = 0.0

    @property
    def sun_mean(self) -> float:
        """Mean sun-planet stiffness over the cycle [N/m]."""
        return float(np.mean(self.sun_k))

    @property
    def ring_mean(self) -> float:
        """Mean intact ring-planet stiffness over the cycle [N/m]."""
        return float(np.mean(self.ring_k))

    def sun(self, s) -> np.ndarray:
        """Sun-planet stiffness at roll length ``s`` (any, periodic) [N/m]."""
        return np.interp(s, self.sun_s, self.sun_k, period=self.base_pitch)

    def ring(self, s, s_cracked=None) -> np.ndarray:
        """Ring-planet stiffness at roll length ``s`` [N/m]; where ``s_cracked`` (the
        roll length of the cracked tooth's contact) lies in the engagement window, the
        cracked curve."""
        k = np.interp(s, self.ring_s, self.ring_k, period=self.base_pitch)
        if self.cracked_s is None or s_cracked is None:
            return k
        s_cracked = np.asarray(s_cracked)
        inside = (s_cracked >= self.cracked_s[0]) & (s_cracked <= self.cracked_s[-1])
        k[inside] = np.interp(s_cracked[inside], self.cracked_s, self.cracked_k)
        return k

    def scaled(self, sun_factor: float, ring_factor: float) -> "MeshCurves":
        """The curves times these factors (the cracked window with the ring's)."""
        return replace(self, sun_k=sun_factor * self.sun_k, ring_k=ring_factor * self.ring_k,
                       cracked_k=None if self.cracked_k is None else ring_factor * self.cracked_k)

    def to_preset(self, c_sp: float, c_rp: float) -> "MeshCurves":
        """Shapes kept, intact means set to ``c_sp`` and ``c_rp`` [N/m] (``"ratio"``)."""
        return self.scaled(c_sp / self.sun_mean, c_rp / self.ring_mean)


def _curves(pairs, compliance, q_hertz, cracked_compliance=None, depth=0.0) -> MeshCurves:
    sun_pair, ring_pair = pairs
    sun = mesh_cycle(sun_pair, compliance["planet"], compliance["sun"], q_hertz)
    ring = mesh_cycle(ring_pair, compliance["planet"], compliance["ring"], q_hertz)
    cracked_s = cracked_k = None
    if cracked_compliance is not None:
        window = mesh_cycle(ring_pair, compliance["planet"], compliance["ring"], q_hertz,
                            marked_pair_compliance=cracked_compliance)
        cracked_s, cracked_k = window.s, window.stiffness
    return MeshCurves(ring_pair.base_pitch, sun.s, sun.stiffness, ring.s, ring.stiffness,
                      cracked_s, cracked_k, float(depth))


def _pairs(design):
    planet = gear_body(design, "planet")
    bodies = {"sun": gear_body(design, "sun"), "planet": planet, "ring": ring_gear(design)}
    return bodies, (GearPair(planet, bodies["sun"]), GearPair(planet, bodies["ring"]))


def synthetic_curves(design, tooth_compliance: float = 2.0e-9, crack_factor: float = 1.0,
                     depth: float = 0.0) -> MeshCurves:
    """Mesh curves of a design's reducer with every tooth of constant compliance [m/N]
    (no FE).

    The stiffness is then piecewise constant (one or two pairs in contact) over the
    true paths of contact; ``crack_factor`` > 1 multiplies the cracked ring tooth's
    compliance (``depth`` only labels the case).
    """
    bodies, pairs = _pairs(design)

    def constant(value):
        return lambda r: np.full(np.shape(r), value)

    compliance = {name: constant(tooth_compliance) for name in bodies}
    q_h = hertz_compliance(pairs[1].second.gear.face_width, Material())
    cracked = constant(tooth_compliance * crack_factor) if crack_factor != 1.0 else None
    return _curves(pairs, compliance, q_h, cracked, depth)


def fe_mesh_curves(depths, start: str, angle: float, scale: float, progress,
                   design) -> list[MeshCurves]:
    """FE mesh curves of a design's reducer for each crack depth [m] (0: intact).

    ``scale`` is the mesh level (``hubvib.meshing.levels.scaled_options``); the crack
    (``hubvib.meshing.crack.Crack``) is moved to tooth 0 for the tooth model, as in
    the crack sweep.  ``progress(message)`` is called before each FE solve.
    """
    if design is None:
        material = Material()
    else:
        from hubvib.reducer.stages import material as design_material

        material = design_material(design)
    options = scaled_options(scale)
    bodies, pairs = _pairs(design)
    spans = {"sun": contact_radii(bodies["sun"], [pairs[0]]),
             "planet": contact_radii(bodies["planet"], list(pairs)),
             "ring": contact_radii(bodies["ring"], [pairs[1]])}
    compliance = {name: cached_tooth_curve(body, spans[name], material, options, None,
                                           progress, name)
                  for name, body in bodies.items()}
    q_h = hertz_compliance(min(pairs[1].first.gear.face_width,
                               pairs[1].second.gear.face_width), material)
    out = []
    for depth in depths:
        cracked = None
        if depth > 0:
            crack = Crack(0, float(depth), angle, start)
            cracked = cached_tooth_curve(bodies["ring"], spans["ring"], material, options,
                                         crack, progress, "ring")
        out.append(_curves(pairs, compliance, q_h, cracked, depth))
    return out


def cached_tooth_curve(body, span, material, options, crack=None, progress=None,
                       name: str = "tooth"):
    """FE tooth compliance curve (``hubvib.fem.tooth_stiffness.fe_curve``), cached and
    checked (``hubvib.runtime.fe_cache``: inputs, checksum, source key of this module)."""
    inputs = json.loads(json.dumps({
        "quantity": "tooth compliance curve", "body": repr(body),
        "span_m": [float(v) for v in span], "material": asdict(material),
        "options": asdict(options), "crack": None if crack is None else asdict(crack)}))
    path = root_folder() / "signal-curves" / f"{entry_key(inputs, modules=SOURCE)}.json"

    def check(result):
        radii, values = result.get("radii_m"), result.get("compliance_m_N")
        if not (isinstance(radii, list) and isinstance(values, list) and radii
                and len(radii) == len(values)
                and all(isinstance(v, float) and np.isfinite(v) and v > 0 for v in values)):
            raise CacheEntryError("not a compliance curve of finite positive values")

    try:
        data = read_entry(path, inputs, check, modules=SOURCE)
        return ToothCurve(np.array(data["radii_m"]), np.array(data["compliance_m_N"]))
    except CacheEntryError:
        pass
    if progress is not None:
        progress(f"FE tooth compliance of the {name}"
                 + ("" if crack is None else f", crack {1e3 * crack.depth:.3g} mm"))
    curve = fe_curve(body, span, material, options, crack)
    write_entry(path, inputs, {"radii_m": curve.radii.tolist(),
                               "compliance_m_N": curve.compliance.tolist(), "dofs": curve.dofs},
                modules=SOURCE)
    return curve
