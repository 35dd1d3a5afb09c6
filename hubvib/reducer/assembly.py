"""Assembly rules of a planetary stage, checked in one place before any meshing.

Each failure raises ``DesignError`` naming the key and the allowed range:

1. every gear is cuttable: no undercut, no pointed tooth, the ring's tip circle
   outside its base circle (``SpurGear`` checks, ISO 21771);
2. equal working centre distances of the sun-planet and ring-planet pairs, the
   working pressure angles derived from the shifts (ISO 21771);
3. planets assemble: each planet angle theta_i satisfies
   ``theta_i (z_s + z_r) / 2 pi`` integer, i.e. ``(z_s + z_r) / N`` integer for
   equally spaced planets (otherwise the nearest angles that do assemble are
   proposed, printed to ``ANGLE_DECIMALS`` decimals, which the rule accepts as typed);
4. neighbouring planets' tip circles are clear of each other;
5. no tip interference and a transverse contact ratio >= 1 in both meshes.
"""
from __future__ import annotations

import math
import re

from hubvib.reducer import stages as build
from hubvib.design.model import DesignError, ReducerDesign
from hubvib.fem.mesh_cycle import GearPair
from hubvib.foundation.bounds import upper_bound
from hubvib.meshing.gear import GearGeometryError, SpurGear, involute


#: allowed difference of the two working centre distances [m]
CENTRE_DISTANCE_TOLERANCE = 1e-6
#: smallest gap between neighbouring planets' tip circles [m]
MIN_PLANET_GAP = 0.0
#: tolerance of the assembly condition theta (z_s + z_r) / 2 pi on an integer [-]: a
#: fraction of the angle between neighbouring assembly positions, 360 / (z_s + z_r) deg.
#: 1e-4 of it is an arc of 1e-4 pi m z_r / (z_s + z_r) < 1e-4 pi m on the ring's pitch
#: circle (module m; 0.8 um at m = 2.5 mm), well inside a gear's pitch tolerance, and
#: covers angles typed to 4 decimals of a degree for z_s + z_r < 720
ASSEMBLY_TOLERANCE = 1e-4
#: decimals of the proposed planet angles [deg]: their rounding (<= 5e-7 deg) is below
#: 1/30 of ``ASSEMBLY_TOLERANCE`` for every tooth count the design takes (z_s + z_r <= 2000)
ANGLE_DECIMALS = 6


def check_assembly(design: ReducerDesign) -> None:
    """Raise ``DesignError`` for the first rule the design breaks (see the module doc)."""
    try:
        sun, planet, ring = build.spur_gears(design)
    except GearGeometryError as exc:
        raise DesignError(_gear_message(design, exc)) from None
    for name, gear in (("sun", sun), ("planet", planet), ("ring", ring)):
        try:
            gear._check_tooth()
        except GearGeometryError as exc:  # pragma: no cover - SpurGear already checked
            raise DesignError(f"design.{name}: {exc}") from None
    if ring.teeth <= planet.teeth:
        raise DesignError(f"design.ring.teeth = {ring.teeth}; allowed: > planet.teeth = "
                          f"{planet.teeth}")
    a_sp, a_rp = build.centre_distances(design)
    if abs(a_sp - a_rp) > CENTRE_DISTANCE_TOLERANCE:
        alpha = design.pressure_angle
        z = ring.teeth - planet.teeth
        cos_needed = z * design.module * math.cos(alpha) / (2 * a_sp)
        hint = ""
        if cos_needed < 1:
            inv = float(involute(math.acos(cos_needed)))
            x_r = planet.profile_shift + (inv - float(involute(alpha))) * z / (2 * math.tan(alpha))
            hint = f"; ring.shift = {x_r:.6f} gives equal distances"
        raise DesignError(
            f"working centre distances differ: sun-planet {1e3 * a_sp:.6f} mm, ring-planet "
            f"{1e3 * a_rp:.6f} mm; allowed: equal within {1e3 * CENTRE_DISTANCE_TOLERANCE:g} mm "
            f"(design.sun/planet/ring .teeth and .shift){hint}")
    _check_planet_angles(design, sun.teeth + ring.teeth)
    _check_planet_gap(design, planet, a_sp)
    _check_meshes(design)


def assembling_angles(design: ReducerDesign, teeth_sum: int) -> tuple[float, ...]:
    """The planet angles nearest equal spacing that assemble [rad]."""
    n = design.n_planets
    return tuple(2 * math.pi * round(i * teeth_sum / n) / teeth_sum for i in range(n))


def _check_planet_angles(design: ReducerDesign, teeth_sum: int) -> None:
    bad = [i for i, a in enumerate(design.angles)
           if abs(math.remainder(a * teeth_sum / (2 * math.pi), 1.0)) > ASSEMBLY_TOLERANCE]
    if not bad:
        return
    proposal = ", ".join(f"{math.degrees(a):.{ANGLE_DECIMALS}f}"
                         for a in assembling_angles(design, teeth_sum))
    if design.planet_angles is None:
        raise DesignError(
            f"design.n_planets = {design.n_planets}: equally spaced planets need (z_s + z_r) / N "
            f"an integer, but ({design.sun.teeth} + {design.ring.teeth}) / {design.n_planets} = "
            f"{teeth_sum / design.n_planets:.4g}; allowed: N dividing {teeth_sum}, or "
            f"planet_angles_deg = [{proposal}] (these assemble)")
    raise DesignError(
        f"design.planet_angles_deg: planet {bad[0] + 1} at "
        f"{math.degrees(design.angles[bad[0]]):.4f} deg does not assemble (theta (z_s + z_r) / "
        f"360 deg must be an integer); allowed, e.g.: [{proposal}]")


def _check_planet_gap(design: ReducerDesign, planet, a_w: float) -> None:
    angles = sorted(a % (2 * math.pi) for a in design.angles)
    if len(angles) < 2:
        return
    steps = [b - a for a, b in zip(angles, angles[1:] + [angles[0] + 2 * math.pi])]
    closest = min(steps)
    gap = 2 * a_w * math.sin(closest / 2) - planet.tip_diameter
    if gap <= MIN_PLANET_GAP:
        raise DesignError(
            f"neighbouring planets collide: centres {1e3 * 2 * a_w * math.sin(closest / 2):.3f} mm "
            f"apart ({math.degrees(closest):.3f} deg) but their tip diameter is "
            f"{1e3 * planet.tip_diameter:.3f} mm; allowed: gap > {1e3 * MIN_PLANET_GAP:g} mm "
            f"(design.n_planets / planet_angles_deg / planet.teeth)")


def _check_meshes(design: ReducerDesign) -> None:
    try:
        sun, planet = build.gear_body(design, "sun"), build.gear_body(design, "planet")
        ring = build.ring_gear(design)
    except GearGeometryError as exc:
        raise DesignError(_gear_message(design, exc)) from None
    for label, first, second in (("sun-planet", sun, planet), ("ring-planet", planet, ring)):
        try:
            ratio = GearPair(first, second).contact_ratio
        except GearGeometryError as exc:
            raise DesignError(_mesh_message(label, exc)) from None
        if ratio < 1:
            raise DesignError(f"{label} mesh: contact ratio {ratio:.4f}; allowed >= 1 "
                              "(design.*.teeth, .shift, pressure_angle_deg)")


def _gear_message(design: ReducerDesign, exc: GearGeometryError) -> str:
    """The gear stage's error in the design's keys, its bound printed so that the value
    shown passes the rule when typed back (the stage prints the undercut limit rounded to
    nearest and the root diameter rounded up; its source stays unchanged, as for
    ``_mesh_message``)."""
    text = str(exc)
    undercut = re.match(r"profile_shift = (\S+) undercuts the (\d+)-tooth gear", text)
    if undercut is not None:
        shift, teeth = float(undercut.group(1)), int(undercut.group(2))
        name = next((n for n in ("sun", "planet") if getattr(design, n).teeth == teeth
                     and getattr(design, n).shift == shift), None)
        limit = _undercut_limit(design, teeth, text)
        if name is not None and limit is not None:
            return (f"design.{name}.shift = {shift:g} undercuts the {teeth}-tooth gear; "
                    f"allowed >= {limit} (ISO 21771 undercut limit)")
    bore = re.match(r"bore_diameter = (\S+) m, allowed 0\.\.\S+ m", text)
    if bore is not None:
        value = float(bore.group(1))
        for index, name in enumerate(("sun", "planet")):
            gear = build.spur_gears(design)[index]
            if getattr(design, name).bore == value:
                return (f"design.{name}.bore = {value:g} m; allowed: > 0 and < "
                        f"{upper_bound(gear.root_diameter, strict=True)} m (the "
                        f"{name}'s root diameter)")
    return f"design: {text}"


def _undercut_limit(design: ReducerDesign, teeth: int, text: str) -> str | None:
    """The smallest shift to 4 decimals that the gear stage's undercut rule accepts for a
    ``teeth``-tooth external gear of ``design`` (from the limit ``text`` prints)."""
    printed = re.search(r"allowed >= (\S+)", text)
    if printed is None:
        return None
    shift = float(printed.group(1))
    for _ in range(3):
        try:
            SpurGear(teeth, profile_shift=shift, module=design.module,
                     pressure_angle=design.pressure_angle, face_width=design.face_width)
        except GearGeometryError as exc:
            if "undercuts" in str(exc):
                shift = round(shift + 1e-4, 4)
                continue
        return f"{shift:.4f}"
    return None


def _mesh_message(label: str, exc: GearGeometryError) -> str:
    """The mesh error in the design's keys: which gear, and what would fix it (the FE
    stage's message names ``GearPair.first/second``; its source is left unchanged, since
    any edit there invalidates every FE cache entry)."""
    found = re.match(r"GearPair\.(first|second): the path of contact runs below the form "
                     r"circle \(r = ([0-9.eE+-]+) m\)", str(exc))
    if found is None:
        return f"{label} mesh: {exc}"
    body, form_radius = found.group(1), float(found.group(2))
    gears = dict(zip(("first", "second"), label.split("-")[::-1] if label == "ring-planet"
                     else label.split("-")))
    gear, other = gears[body], gears["second" if body == "first" else "first"]
    return (f"{label} mesh: the path of contact runs below the {gear}'s form circle "
            f"(r = {1e3 * form_radius:.4f} mm): the {other}'s tips would cut into the "
            f"{gear}'s flanks (tip interference); allowed: a path of contact inside both form "
            f"circles: give the gears positive profile shifts (design.{gear}.shift, with "
            f"design.sun/planet/ring .shift chosen for equal centre distances) or change "
            f".teeth")


def summary(design: ReducerDesign) -> dict:
    """What follows from a design that assembles: distances, angles, contact ratios,
    masses and the lumped fields the geometry gives (SI).

    ``lumped``: each lumped field once, the value the lumped model uses with its method
    (``design.lumped`` where the design's table gives it, then with the geometry's value
    and method beside it); ``named_values``: every value by ``key (method)``, the names
    ``hubvib stiffness`` gives its values too."""

    a_sp, a_rp = build.centre_distances(design)
    alpha_s, alpha_r = build.working_angles(design)
    sun, planet = build.gear_body(design, "sun"), build.gear_body(design, "planet")
    ring = build.ring_gear(design)
    derived = build.derived_lumped_fields(design)
    methods = build.derived_field_methods(design)
    given = design.lumped_fields
    missing = [k for k in build.MOUNTING_FIELDS + ("c_p", "c_c")
               if k not in given and k not in derived]
    lumped = {}
    for key in list(derived) + [k for k in given if k not in derived]:
        if key in given:
            row = {"value": given[key], "method": build.DESIGN_TABLE}
            if key in derived:
                row.update(geometry_value=derived[key], geometry_method=methods[key])
        else:
            row = {"value": derived[key], "method": methods[key]}
        lumped[key] = row
    named = {build.labelled(k, methods[k]): v for k, v in derived.items()}
    named.update({build.labelled(k, build.DESIGN_TABLE): v for k, v in given.items()})
    return {
        "name": design.name, "n_planets": design.n_planets,
        "planet_angles_deg": [math.degrees(a) for a in design.angles],
        "equally_spaced": design.equally_spaced,
        "centre_distance_m": a_sp, "centre_distance_ring_planet_m": a_rp,
        "working_pressure_angle_sun_planet_deg": math.degrees(alpha_s),
        "working_pressure_angle_ring_planet_deg": math.degrees(alpha_r),
        "contact_ratio_sun_planet": GearPair(sun, planet).contact_ratio,
        "contact_ratio_ring_planet": GearPair(planet, ring).contact_ratio,
        "ratio_carrier_to_sun": 1 + design.ring.teeth / design.sun.teeth,
        "ring_outer_diameter_m": ring.outer_diameter,
        "ring_rim_thickness_m": ring.rim_thickness,
        "lumped_from_geometry": derived,
        "lumped_from_design_table": given,
        "lumped_missing": missing,
        "lumped": lumped,
        "named_values": named,
        "notes": list(design.notes),
    }
