"""From a design to what each stage needs: gears and bodies (meshing), material and
bearing stiffness (FE), and the lumped model's parameters (SI).

The build layer sits above the stages (meshing, fem, lumped) and below validation and
the app: a design (``hubvib.design``, pure data) never imports a stage, and a stage never
imports a design's builder."""
from __future__ import annotations

import math
from functools import lru_cache

from hubvib.design.model import DesignError, ReducerDesign
from hubvib.fem.bearing import RollerBearing
from hubvib.fem.iso6336 import iso_stiffness
from hubvib.fem.material import Material
from hubvib.fem.mesh_cycle import GearPair
from hubvib.lumped.parameters import ParameterError, PlanetaryParameters
from hubvib.meshing.gear import SpurGear, centre_distance, working_pressure_angle
from hubvib.meshing.gear_body import GearBody
from hubvib.meshing.ring_gear import RingGear, Supports, outer_diameter_for_mass


#: bore of a sun or planet whose design gives none, as a fraction of its root diameter
DEFAULT_BORE_FRACTION = 0.4
#: lumped fields the geometry does not give; a design's ``lumped`` table supplies them
MOUNTING_FIELDS = ("c_ru", "c_r", "c_su", "c_cu")

#: the methods behind the stiffnesses of a design, as every output names them: one name
#: per meaning, so that a name printed twice holds one value
ISO_MESH = "ISO 6336-1 c_gamma b"
ISO_SINGLE = "ISO 6336-1 c' b"
FE_MESH = "FE mean over the mesh cycle"
FE_RING = "FE rim part"
DESIGN_TABLE = "design.lumped"


def spur_gears(design: ReducerDesign):
    """Sun, planet, ring as ``SpurGear`` (ISO 53 rack, the design's module and shifts)."""
    common = dict(module=design.module, pressure_angle=design.pressure_angle,
                  face_width=design.face_width)
    return (SpurGear(design.sun.teeth, profile_shift=design.sun.shift, **common),
            SpurGear(design.planet.teeth, profile_shift=design.planet.shift, **common),
            SpurGear(design.ring.teeth, profile_shift=design.ring.shift, internal=True,
                     **common))


def working_angles(design: ReducerDesign) -> tuple[float, float]:
    """Working pressure angles of the sun-planet and ring-planet meshes [rad] (ISO 21771)."""
    sun, planet, ring = spur_gears(design)
    return working_pressure_angle(sun, planet), working_pressure_angle(planet, ring)


def centre_distances(design: ReducerDesign) -> tuple[float, float]:
    """Working centre distances of the sun-planet and ring-planet pairs [m]."""
    sun, planet, ring = spur_gears(design)
    return centre_distance(sun, planet), centre_distance(planet, ring)


def ring_gear(design: ReducerDesign, supports=None, fillet: str = "trochoid"):
    """The ring with its rim, supports and material density (``meshing.RingGear``).

    The outer diameter follows from the rim thickness below the root circle, or
    from the ring's mass with the exact tooth geometry.  ``supports`` overrides the
    design's (a ``meshing.ring_gear.Supports``).
    """
    return _ring_gear(design, supports, fillet)


@lru_cache(maxsize=16)
def _ring_gear(design, supports, fillet):
    ring = spur_gears(design)[2]
    if supports is None:
        s = design.supports
        supports = Supports(count=s.count, width=s.arc, first_angle=s.first)
    alpha_w = working_angles(design)[1]
    density = design.material.density
    if design.rim.mass is not None:
        outer = outer_diameter_for_mass(ring, design.rim.mass, density=density, fillet=fillet)
    else:
        probe = RingGear(ring, 4 * ring.root_diameter, supports, fillet=fillet,
                         working_pressure_angle=alpha_w, density=density)
        outer = 2 * (probe.profile.root_radius + design.rim.thickness)
    return RingGear(ring, outer, supports, fillet=fillet, working_pressure_angle=alpha_w,
                    density=density)


def gear_body(design: ReducerDesign, name: str):
    """The sun or planet on its bore (``meshing.GearBody``), loaded at the sun-planet
    working pressure angle."""

    if name not in ("sun", "planet"):
        raise DesignError(f"gear body {name!r}; allowed: sun, planet")
    index = ("sun", "planet").index(name)
    gear = spur_gears(design)[index]
    spec = getattr(design, name)
    bore = spec.bore if spec.bore is not None else DEFAULT_BORE_FRACTION * gear.root_diameter
    return GearBody(gear, bore, working_pressure_angle=working_angles(design)[0],
                    density=design.material.density)


def material(design: ReducerDesign):
    """The FE material (``fem.Material``)."""
    m = design.material
    return Material(m.E, m.nu, m.density)


def mesh_force(design: ReducerDesign) -> float:
    """Normal force of each sun-planet mesh at the design's sun torque [N] (equal sharing)."""
    sun = spur_gears(design)[0]
    return design.sun_torque / (design.n_planets * sun.base_diameter / 2)


def planet_bearing_load(design: ReducerDesign) -> float:
    """Radial load on a planet bearing [N]: the sun and ring mesh forces on the planet have
    equal tangential parts, which add, and radial parts that cancel when both working
    angles are equal (their difference is neglected otherwise)."""
    return 2 * mesh_force(design) * math.cos(working_angles(design)[0])


def bearing_method(kind: str, load: float) -> str:
    """The name of a bearing stiffness: ``kind`` (tangent or secant) at ``load`` [N]."""
    return f"Palmgren {kind} at {load / 1e3:.4g} kN"


def labelled(key: str, method: str) -> str:
    """``key (method)``: how a value is named wherever it is printed."""
    return f"{key} ({method})"


def bearing_stiffness(design: ReducerDesign) -> dict[str, dict]:
    """c_p and c_c, tangent and secant [N/m], with the loads they were computed at [N].

    Only the bearings the design gives are in the result.
    """

    out = {}
    for name, spec, default_load in (("c_p", design.planet_bearing, planet_bearing_load),
                                     ("c_c", design.carrier_bearing, None)):
        if spec is None:
            continue
        load = spec.load if spec.load is not None else default_load(design)
        bearing = RollerBearing(rollers=spec.rollers, roller_length=spec.roller_length)
        tangent, secant = bearing.stiffness(load)
        out[name] = {"tangent_N_m": tangent, "secant_N_m": secant, "load_N": load,
                     "rollers": spec.rollers, "roller_length_m": spec.roller_length,
                     "method": bearing_method("tangent", load),
                     "secant_method": bearing_method("secant", load)}
    return out


def mass_properties(design: ReducerDesign) -> dict[str, float]:
    """Masses [kg] and reduced masses J / r_b^2 [kg] from the geometry.

    Sun, planet and ring masses are exact (area of the toothed section x face width x
    density).  Their moments of inertia take the toothed section as the annulus of the
    same area and the same bore (sun, planet) or outer radius (ring): an approximation,
    exact for the rim and within the tooth's share of the mass otherwise.  The carrier
    (not in the design) is a steel disc over the planet-centre circle, face-width thick.
    """
    rho, b = design.material.density, design.face_width
    sun, planet = gear_body(design, "sun"), gear_body(design, "planet")
    ring = ring_gear(design)
    out = {}
    for key, body in (("s", sun), ("p", planet)):
        r_in = body.bore_diameter / 2
        area = body.area()
        r_eq2 = r_in ** 2 + area / math.pi
        inertia = rho * b * math.pi / 2 * (r_eq2 ** 2 - r_in ** 4)
        out[f"m_{key}"] = rho * b * area
        out[f"mu_{key}"] = inertia / (body.gear.base_diameter / 2) ** 2
    r_out = ring.outer_radius
    r_eq2 = r_out ** 2 - ring.area() / math.pi
    out["m_r"] = rho * b * ring.area()
    out["mu_r"] = rho * b * math.pi / 2 * (r_out ** 4 - r_eq2 ** 2) / (
        ring.gear.base_diameter / 2) ** 2
    a_w = centre_distances(design)[0]
    out["m_c"] = rho * b * math.pi * a_w ** 2
    out["mu_c"] = out["m_c"] / 2  # disc J = m a^2 / 2, taken along the radius a_w
    return out


def derived_lumped_fields(design: ReducerDesign, skip=()) -> dict[str, float]:
    """Every lumped field the geometry gives, except those in ``skip`` (not computed)."""
    sun_gear, planet_gear, ring_spur = spur_gears(design)
    alpha_s, alpha_r = working_angles(design)
    out = dict(d_s=sun_gear.base_diameter, d_p=planet_gear.base_diameter,
               d_r=ring_spur.base_diameter, d_c=2 * centre_distances(design)[0],
               alpha_s=alpha_s, alpha_r=alpha_r)
    if not {"m_s", "m_p", "m_r", "m_c", "mu_s", "mu_p", "mu_r", "mu_c"} <= set(skip):
        out.update(mass_properties(design))
    if not {"c_sp", "c_rp"} <= set(skip):
        sun, planet = gear_body(design, "sun"), gear_body(design, "planet")
        for key, first, second, p, w in (
                ("c_sp", sun, planet, sun_gear, planet_gear),
                ("c_rp", planet, ring_gear(design), planet_gear, ring_spur)):
            pair = GearPair(first, second)
            out[key] = iso_stiffness(p, w, pair.contact_ratio).per_face_width(
                design.face_width)[1]
    if not {"c_p", "c_c"} <= set(skip):
        out.update({k: row["tangent_N_m"] for k, row in bearing_stiffness(design).items()})
    return {k: v for k, v in out.items() if k not in skip}


def derived_field_methods(design: ReducerDesign) -> dict[str, str]:
    """How each lumped field the geometry gives is computed (``derived_lumped_fields``'s
    keys): ``geometry`` for diameters, angles and masses, ``ISO_MESH`` for c_sp and c_rp
    (the mean mesh stiffness, as the FE's mean over the mesh cycle), the bearings' tangent
    stiffness at their load for c_p and c_c."""
    methods = dict.fromkeys(("d_s", "d_p", "d_r", "d_c", "alpha_s", "alpha_r", "m_s", "mu_s",
                             "m_p", "mu_p", "m_r", "mu_r", "m_c", "mu_c"), "geometry")
    methods.update(c_sp=ISO_MESH, c_rp=ISO_MESH)
    methods.update({k: row["method"] for k, row in bearing_stiffness(design).items()})
    return methods


def lumped_parameters(design: ReducerDesign):
    """The lumped model's parameters: derived from the geometry, then the design's
    ``lumped`` table (fields the geometry cannot give, or a published table's values).

    c_sp, c_rp default to ISO 6336-1's c_gamma_alpha b (no FE), c_p and c_c to the
    bearings' tangent stiffness; c_ru, c_r, c_su, c_cu (the mountings and shafts) must
    be in the ``lumped`` table.
    """

    given = design.lumped_fields
    fields = derived_lumped_fields(design, skip=given) | given
    missing = [k for k in MOUNTING_FIELDS + ("c_p", "c_c") if k not in fields]
    if missing:
        raise DesignError(
            f"design {design.name!r}: the lumped model needs {', '.join(f'lumped.{k}' for k in missing)}"
            " [N/m] (mountings, shafts and bearings the geometry does not give; bearings may be "
            "given as [design.bearings] planet = {...} / carrier = {...} instead of lumped.c_p "
            "/ lumped.c_c)")
    try:
        return PlanetaryParameters(theta=design.angles, **fields)
    except (ParameterError, TypeError) as exc:
        raise DesignError(f"design {design.name!r}: lumped: {exc}") from None
