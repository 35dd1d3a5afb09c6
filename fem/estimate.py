"""FE stiffnesses with their error estimate from three mesh levels: the default mesh, one
twice as coarse and one twice as coarse again (SI).

The error bar of every value is ``fem.three_level.three_level_error`` of its three levels:
Richardson's estimate with the observed order where the levels are in the asymptotic
range, else the larger of the two level differences.  The third level is the coarser one
(a quarter of the medium level's elements in the plane: cheap) rather than a finer one
(four times the default's): the error bar is of the default mesh's value either way.
"""
from __future__ import annotations

import time
from dataclasses import MISSING, asdict, dataclass, fields

import numpy as np

from hubvib.fem.crack_level import crack_level
from hubvib.fem.material import Material
from hubvib.fem.ring_stiffness import ring_stiffness
from hubvib.fem.mesh_cycle import GearPair
from hubvib.fem.three_level import ThreeLevelError, three_level_error
from hubvib.fem.tooth_stiffness import (contact_radii, engaged_mesh, offer_intact_curve,
                                         provide_intact_curve, reducer_mesh_stiffness)
from hubvib.meshing.crack import Crack, CrackFront
from hubvib.meshing.levels import SOLID_LEVELS, scaled_options, solid_options
from hubvib.meshing.ring_mesh import ring_mesh
from hubvib.meshing.ring_mesh_3d import ring_mesh_3d
from hubvib.meshing.ring_pieces import ring_pieces


#: field -> JSON / cache key with its unit
RING_KEYS = {"c_ru": "c_ru_N_m", "c_ru_error": "c_ru_error_N_m", "c_ru_min": "c_ru_min_N_m",
             "c_ru_max": "c_ru_max_N_m", "c_r": "c_r_N_m", "c_r_error": "c_r_error_N_m",
             "c_ru_coarse": "c_ru_coarse_N_m", "c_r_coarse": "c_r_coarse_N_m",
             "c_ru_poor_half": "c_ru_poor_half_N_m", "c_r_poor_half": "c_r_poor_half_N_m",
             "c_rp_engaged_intact": "c_rp_engaged_intact_N_m",
             "c_rp_engaged_intact_min": "c_rp_engaged_intact_min_N_m",
             "c_rp_engaged_intact_window": "c_rp_engaged_intact_window_N_m",
             "c_ru_root_land": "c_ru_root_land_N_m",
             "c_ru_root_land_error": "c_ru_root_land_error_N_m",
             "c_r_root_land": "c_r_root_land_N_m", "c_r_root_land_error": "c_r_root_land_error_N_m",
             "tooth_radii": "tooth_radii_m", "tooth_compliance": "tooth_compliance_m_N",
             "tooth_compliance_coarse": "tooth_compliance_coarse_m_N",
             "tooth_compliance_coarsest": "tooth_compliance_coarsest_m_N",
             "c_ru_levels": "c_ru_levels_N_m", "c_r_levels": "c_r_levels_N_m",
             "c_ru_root_land_levels": "c_ru_root_land_levels_N_m",
             "c_r_root_land_levels": "c_r_root_land_levels_N_m"}
#: element sizes of the plane levels over the default's, coarsest first [-]
PLANE_LEVELS = (4.0, 2.0, 1.0)
#: a cell whose gmsh min SICN is below this counts as poorly shaped
USABLE_QUALITY = 0.1
#: version of the dict form of the estimates (``to_dict`` / ``from_dict``), stored with
#: every FE cache entry: a change of the fields is a new version, and old entries go
#: (2: the crack case stores the absolute intact engaged c_rp; 3: the
#: crack case's c_ru and c_r are the work-conjugate rim parts, the root-land readings and
#: the intact engaged c_rp over the contact window beside them; 4: the
#: solid case stores its cracked tooth's line-load compliance; 5: three mesh levels, the
#: values on each stored as ``*_levels``)
SCHEMA_VERSION = 5


#: the field types of the estimates, as their annotations name them
_TYPES = {"float": float, "int": int, "str": str, "tuple": tuple}


def _from_dict(cls, data: dict):
    """An estimate from its dict form (the keys of ``to_dict``; other keys are the
    caller's).  ``ValueError`` names the missing keys or the key of a wrong type."""
    if not isinstance(data, dict):
        raise ValueError(f"{cls.__name__}: {data!r} is not a table")
    values, missing = {}, []
    for f in fields(cls):
        key = RING_KEYS.get(f.name, f.name)
        if key not in data:
            if f.default is MISSING:
                missing.append(key)
            continue
        value, kind = data[key], _TYPES[f.type]
        if kind is tuple:  # a list of numbers
            if not isinstance(value, (list, tuple)) or not all(
                    isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
                raise ValueError(f"{key} = {value!r}; allowed: a list of numbers")
            values[f.name] = tuple(float(v) for v in value)
            continue
        if isinstance(value, bool) or not (isinstance(value, (int, float)) if kind is float
                                           else isinstance(value, kind)):
            raise ValueError(f"{key} = {value!r}; allowed: {kind.__name__}")
        values[f.name] = float(value) if kind is float else value
    if missing:
        raise ValueError(f"lacks {', '.join(missing)}")
    return cls(**values)


def level_ratio(coarse, fine) -> float:
    """Element size of the ``coarse`` options over the ``fine`` ones' [-]: the geometric
    mean of the rim, tooth and load-patch sizes' ratios."""
    return float((coarse.size / fine.size * coarse.tooth_size / fine.tooth_size
                  * coarse.load_size / fine.load_size) ** (1 / 3))


def level_ratios(options) -> tuple[float, float]:
    """(coarsest over coarse, coarse over fine) element sizes [-] of three levels'
    options, coarsest first."""
    return level_ratio(options[0], options[1]), level_ratio(options[1], options[2])


def level_error(levels: tuple, ratios: tuple) -> ThreeLevelError:
    """``three_level_error`` of one value's ``levels`` (coarsest, coarse, fine) with the
    levels' size ``ratios`` (``level_ratios``)."""
    return three_level_error(*levels, r_fine=ratios[1], r_coarse=ratios[0])


def _dict_of(estimate) -> dict:
    """``estimate``'s fields under their ``RING_KEYS``, without the level fields it does
    not store (empty)."""
    return {RING_KEYS.get(k, k): v for k, v in asdict(estimate).items()
            if not ((k.endswith("_levels") or k == "level_ratios") and v == ())}


class _Levels:
    """The three-level error of a stored value: ``error_of(name)`` from ``name_levels``."""

    def error_of(self, name: str) -> ThreeLevelError:
        """The three-level error (estimate, error, order, rule) of the field ``name``
        (``c_ru``, ``c_r``, ...) from its stored levels."""
        levels = getattr(self, f"{name}_levels")
        if len(levels) != 3 or len(self.level_ratios) != 2:
            raise ValueError(f"{name}: no three levels stored ({len(levels)} values)")
        return level_error(levels, self.level_ratios)


@dataclass(frozen=True)
class RingEstimate(_Levels):
    """The ring body's stiffnesses on the default mesh, with error estimates.

    Attributes
    ----------
    c_ru, c_ru_error : float
        Reduced torsional stiffness, mean over carrier positions, and its error [N/m].
    c_ru_min, c_ru_max : float
        Lowest and highest c_ru over the carrier positions [N/m].
    c_r, c_r_error : float
        Radial (support) stiffness and its error [N/m].
    dofs : int
        Degrees of freedom of the fine level (a half-width model: the half's).
    solver : str
        Sparse solver used.
    seconds_mesh, seconds_fe, seconds_total : float
        Wall times [s]: fine mesh, fine FE, both levels in all.
    c_ru_coarse, c_r_coarse : float
        The same on the coarse level [N/m]: a crack's change of c_ru has the error
        ``|(fine - fine_intact) - (coarse - coarse_intact)|``, much below ``c_ru_error``
        where the meshes differ only near the crack.
    min_quality : float
        Lowest gmsh min SICN of the fine mesh's cells [-].
    poor_cells : int
        Fine-mesh cells with min SICN below ``USABLE_QUALITY``.
    c_ru_poor_half, c_r_poor_half : float
        With ``poor_cells_halved``: the fine level again with those cells at half their
        stiffness [N/m], how much the result hangs on them (NaN otherwise).
    definition : str
        What c_ru and c_r are (``RING_DEFINITIONS``): ``"root_land"``, the root-land
        readings, or ``"rim"``, the work-conjugate rim parts (``fem.ring_work``) the
        lumped model uses.
    c_ru_root_land, c_ru_root_land_error, c_r_root_land, c_r_root_land_error : float
        With ``"rim"``: the root-land readings and their errors beside them [N/m].
    tooth_radii, tooth_compliance, tooth_compliance_coarse, tooth_compliance_coarsest : tuple
        With ``tooth`` (solid): the flank radii [m] and the tooth's line-load compliance
        [m/N] there on the fine, the coarse and the coarsest level (``fem.tooth_solid``;
        empty otherwise).
    c_ru_levels, c_r_levels, c_ru_root_land_levels, c_r_root_land_levels : tuple of float
        The value on each level, coarsest first [N/m]: the errors are their
        ``three_level_error`` (``error_of``).
    level_ratios : tuple of float
        Element size of the coarsest level over the coarse one's and of the coarse over
        the fine one's [-] (``level_ratios``).
    """

    c_ru: float
    c_ru_error: float
    c_ru_min: float
    c_ru_max: float
    c_r: float
    c_r_error: float
    dofs: int
    solver: str
    seconds_mesh: float
    seconds_fe: float
    seconds_total: float
    c_ru_coarse: float = float("nan")
    c_r_coarse: float = float("nan")
    min_quality: float = float("nan")
    poor_cells: int = 0
    c_ru_poor_half: float = float("nan")
    c_r_poor_half: float = float("nan")
    definition: str = "root_land"
    c_ru_root_land: float = float("nan")
    c_ru_root_land_error: float = float("nan")
    c_r_root_land: float = float("nan")
    c_r_root_land_error: float = float("nan")
    tooth_radii: tuple = ()
    tooth_compliance: tuple = ()
    tooth_compliance_coarse: tuple = ()
    tooth_compliance_coarsest: tuple = ()
    c_ru_levels: tuple = ()
    c_r_levels: tuple = ()
    c_ru_root_land_levels: tuple = ()
    c_r_root_land_levels: tuple = ()
    level_ratios: tuple = ()

    def to_dict(self) -> dict:
        """Keys with units (``c_ru_N_m`` ...), as in the JSON output and the cache (level
        values only where stored)."""
        return _dict_of(self)

    @classmethod
    def from_dict(cls, data: dict) -> RingEstimate:
        """The inverse of ``to_dict`` (``SCHEMA_VERSION``); ``ValueError`` names a missing
        key or a value of the wrong type."""
        return _from_dict(cls, data)


#: the three mesh levels, coarsest first
LEVEL_NAMES = ("coarsest", "coarse", "fine")
#: what ``estimate_ring`` gives as c_ru and c_r: the root-land readings or the
#: work-conjugate rim parts (the lumped model's definition)
RING_DEFINITIONS = ("root_land", "rim")


def _ring_values(result, definition: str) -> tuple:
    """(c_ru, c_ru at each carrier position, c_r) [N/m] of a ``RingStiffness`` by
    ``definition``."""
    if definition == "rim":
        work = result.work
        return work.c_ru_rim, work.c_ru_rim_positions, work.c_r_rim
    return result.c_ru, result.c_ru_positions, result.c_r


def estimate_ring(ring, crack=None, scale: float = 1.0, solver: str = "auto",
                  solid: bool = False, mesher=None, material=None,
                  n_planets: int = 3, front=None, carrier_teeth=None,
                  poor_cells_halved: bool = False,
                  definition: str = "root_land", tooth=None,
                  half_width: bool = False) -> RingEstimate:
    """c_ru and c_r on the default mesh (sizes times ``scale``), with their three-level
    errors (``PLANE_LEVELS``: twice and four times as coarse besides).

    With ``solid``: the solid ring on the three ``SOLID_LEVELS``, by default planet 1
    on tooth 0 only.  ``mesher(ring, crack, options)`` replaces the plane mesher
    (to share meshes).  ``material`` (default steel) and ``n_planets`` (equally spaced)
    are the design's; ``front`` (``meshing.crack.CrackFront``) shapes a solid crack
    (default: through the face width); ``carrier_teeth`` lists the carrier positions as
    the tooth planet 1 loads (default: every tooth of one planet pitch in the plane);
    ``poor_cells_halved`` (solid) solves the fine level once more with the cells below
    ``USABLE_QUALITY`` at half stiffness.  ``definition`` (``RING_DEFINITIONS``): the
    root-land readings, or the work-conjugate rim parts with the root-land readings beside.
    ``tooth`` (solid: a ``fem.tooth_solid.SolidToothLoad``) measures that tooth's line-load
    compliance on both levels with the same factorisations.  ``half_width`` (solid): mesh
    and solve half the face width, its mid-plane a mirror plane (``fem.solid``): for a
    mirror-symmetric case (crack, if any, centred on the width) the whole ring's solution
    on the half's mesh (the same to round-off on a mirrored mesh, within discretisation of
    another whole mesh: ``tests/fem/test_half_width.py``), at ~40 % of the CPU time on the 3D
    scene; ``dofs`` are then the half's.
    """
    if definition not in RING_DEFINITIONS:
        raise ValueError(f"definition = {definition!r}; allowed: {', '.join(RING_DEFINITIONS)}")
    if half_width and not solid:
        raise ValueError("half_width = True applies to the solid ring only (solid = True)")
    mesher = mesher or ring_mesh
    options = ([solid_options(*level) for level in SOLID_LEVELS[-3:]] if solid
               else [scaled_options(factor * scale) for factor in PLANE_LEVELS])
    ratios = level_ratios(options)
    results = {}
    teeth = [0] if solid and carrier_teeth is None else carrier_teeth
    for name, level in zip(LEVEL_NAMES, options):
        started = time.perf_counter()
        mesh = (ring_mesh_3d(ring, crack, front or CrackFront(), options=level,
                             half_width=half_width) if solid
                else mesher(ring, crack, level))
        meshed = time.perf_counter()
        result = ring_stiffness(ring, mesh, material or Material(), n_planets=n_planets,
                                carrier_teeth=teeth, solver=solver, tooth=tooth)
        results[name] = (result, meshed - started, time.perf_counter() - meshed)
    quality = mesh.cell_quality
    if quality is None:
        raise ValueError("the mesh carries no cell quality (a mesh cached by an older hubvib)")
    poor = quality < USABLE_QUALITY
    halved = {}
    if poor_cells_halved:
        started = time.perf_counter()
        result = ring_stiffness(ring, mesh, material or Material(), n_planets=n_planets,
                                carrier_teeth=teeth, solver=solver,
                                cell_scale=np.where(poor, 0.5, 1.0))
        c_ru_half, _, c_r_half = _ring_values(result, definition)
        halved = dict(c_ru_poor_half=c_ru_half, c_r_poor_half=c_r_half)
        results["halved"] = (result, 0.0, time.perf_counter() - started)
    solved = [results[name][0] for name in LEVEL_NAMES]
    fine, coarse, coarsest = solved[2], solved[1], solved[0]
    values = [_ring_values(result, definition) for result in solved]
    c_ru_levels = tuple(float(v[0]) for v in values)
    c_r_levels = tuple(float(v[2]) for v in values)
    c_ru_positions = values[2][1]
    land = {}
    if definition != "root_land":
        land_ru = tuple(float(r.c_ru) for r in solved)
        land_r = tuple(float(r.c_r) for r in solved)
        land = dict(c_ru_root_land=land_ru[2], c_ru_root_land_error=level_error(land_ru, ratios).error,
                    c_r_root_land=land_r[2], c_r_root_land_error=level_error(land_r, ratios).error,
                    c_ru_root_land_levels=land_ru, c_r_root_land_levels=land_r)
    teeth_values = {} if tooth is None else dict(
        tooth_radii=tuple(float(r) for r in fine.tooth.radii),
        tooth_compliance=tuple(float(q) for q in fine.tooth.compliance),
        tooth_compliance_coarse=tuple(float(q) for q in coarse.tooth.compliance),
        tooth_compliance_coarsest=tuple(float(q) for q in coarsest.tooth.compliance))
    return RingEstimate(
        c_ru=c_ru_levels[2], c_ru_error=level_error(c_ru_levels, ratios).error,
        c_ru_min=float(c_ru_positions.min()), c_ru_max=float(c_ru_positions.max()),
        c_r=c_r_levels[2], c_r_error=level_error(c_r_levels, ratios).error, dofs=fine.dofs,
        solver=fine.seconds["solver"], seconds_mesh=results["fine"][1],
        seconds_fe=results["fine"][2],
        seconds_total=sum(r[1] + r[2] for r in results.values()),
        c_ru_coarse=c_ru_levels[1], c_r_coarse=c_r_levels[1],
        min_quality=float(quality.min()), poor_cells=int(poor.sum()), **halved,
        definition=definition, **land, **teeth_values, c_ru_levels=c_ru_levels,
        c_r_levels=c_r_levels, level_ratios=ratios)


@dataclass(frozen=True)
class CrackCaseEstimate(_Levels):
    """One crack case of a sweep: the ring body's stiffnesses and the cracked tooth's mesh
    stiffness, each on the default mesh with its three-level error (``PLANE_LEVELS``).

    Attributes
    ----------
    c_ru, c_ru_error : float
        Reduced torsional stiffness of the ring body as the lumped model uses it: the
        work-conjugate rim part ``c_ru_rim`` (``fem.ring_work``), mean over the carrier
        positions of one planet pitch, and its error [N/m].
    c_ru_min, c_ru_max : float
        Lowest and highest c_ru over those carrier positions [N/m].
    c_r, c_r_error : float
        Radial (support) stiffness, the work-conjugate rim part ``c_r_rim``, and its
        error [N/m].
    c_ru_root_land, c_ru_root_land_error, c_r_root_land, c_r_root_land_error : float
        The root-land readings (``ring_stiffness.ring_response``; the lumped model's c_ru
        and c_r formerly) and their errors [N/m], a secondary output (NaN: not
        measured, e.g. rows built from a solid case that lacks them).
    c_rp_engaged_ratio, c_rp_engaged_ratio_error : float
        Ring-planet mesh stiffness averaged over the cracked tooth's engagement, as a
        ratio to the same tooth intact, and its error [-] (1 and 0 without a crack).
    c_rp_engaged_min_ratio : float
        The same for the lowest value over the engagement [-].
    c_rp_engaged_intact, c_rp_engaged_intact_min : float
        The intact tooth's ring-planet mesh stiffness, mean and lowest over the mesh cycle
        [N/m] (the lumped c_rp of a design-derived scene).
    c_rp_engaged_intact_window : float
        The intact mean over the cracked tooth's contact only [N/m], the ratio's
        denominator (``EngagedMesh.intact_window_mean``; 4.8 % above the whole-cycle mean
        on the Raba stage): the crack's extra compliance is
        ``(1/ratio - 1) / c_rp_engaged_intact_window`` [m/N] (the series method).
    dofs : int
        Degrees of freedom of the fine level.
    solver : str
        Sparse solver used.
    seconds_mesh, seconds_fe, seconds_total : float
        Wall times [s]: fine mesh, fine FE (one factorisation for c_ru, c_r and the
        tooth), the three levels in all.
    c_ru_levels, c_r_levels, c_ru_root_land_levels, c_r_root_land_levels : tuple of float
        The value on each level, coarsest first [N/m] (``error_of``; empty: not stored).
    c_rp_engaged_ratio_levels : tuple of float
        The same for the engaged c_rp ratio [-].
    level_ratios : tuple of float
        Element size of the coarsest level over the coarse one's and of the coarse over
        the fine one's [-].
    """

    c_ru: float
    c_ru_error: float
    c_ru_min: float
    c_ru_max: float
    c_r: float
    c_r_error: float
    c_rp_engaged_ratio: float
    c_rp_engaged_ratio_error: float
    c_rp_engaged_min_ratio: float
    c_rp_engaged_intact: float
    c_rp_engaged_intact_min: float
    c_rp_engaged_intact_window: float
    dofs: int
    solver: str
    seconds_mesh: float
    seconds_fe: float
    seconds_total: float
    c_ru_root_land: float = float("nan")
    c_ru_root_land_error: float = float("nan")
    c_r_root_land: float = float("nan")
    c_r_root_land_error: float = float("nan")
    c_ru_levels: tuple = ()
    c_r_levels: tuple = ()
    c_ru_root_land_levels: tuple = ()
    c_r_root_land_levels: tuple = ()
    c_rp_engaged_ratio_levels: tuple = ()
    level_ratios: tuple = ()

    def to_dict(self) -> dict:
        """Keys with units, as ``RingEstimate.to_dict`` plus the ``c_rp_engaged_*`` ratios,
        the intact engaged c_rp (``c_rp_engaged_intact_N_m``, ``..._min_N_m``,
        ``..._window_N_m``) and the root-land readings (``c_ru_root_land_N_m`` ...); level
        values only where stored."""
        return _dict_of(self)

    @classmethod
    def from_dict(cls, data: dict) -> CrackCaseEstimate:
        """The inverse of ``to_dict`` (``SCHEMA_VERSION``); ``ValueError`` names a missing
        key or a value of the wrong type."""
        return _from_dict(cls, data)


def engaged_intact(engaged) -> dict:
    """The intact ring-planet mesh of an ``EngagedMesh`` as ``CrackCaseEstimate`` fields
    [N/m]: mean and lowest over the mesh cycle, and the mean over the cracked tooth's
    contact window (the denominator of its ``mean_ratio``)."""
    return dict(c_rp_engaged_intact=float(engaged.intact.mean),
                c_rp_engaged_intact_min=float(engaged.intact.stiffness.min()),
                c_rp_engaged_intact_window=engaged.intact_window_mean)


def estimate_crack_case(ring, planet, crack, scale: float = 1.0, mesher=None, material=None,
                        n_planets: int = 3) -> CrackCaseEstimate:
    """c_ru, c_r (the work-conjugate rim parts; the root-land readings beside them) and the
    cracked tooth's engaged c_rp ratio on the default plane mesh (sizes times ``scale``),
    with their three-level errors (``PLANE_LEVELS``): per level one mesh, one assembly and
    one factorisation serve all three (``fem.crack_level``).

    ``crack`` (None or depth 0: intact) is measured on the tooth it is in; ``planet`` is
    the planet's gear body; ``mesher(ring, crack, options)`` replaces ``ring_mesh``
    (``meshing.ring_pieces.ring_pieces``: the ring glued from pieces and solved by
    substructures, ``fem.substructure``);
    ``material`` (default steel) and ``n_planets`` (equally spaced) are the design's.
    """
    material = material or Material()
    tooth = 0 if crack is None else crack.tooth
    uncracked = crack is None or crack.depth == 0
    # an intact ring (whole, or glued from pieces) is the model of the intact tooth curves:
    # its tooth is measured on the same solve and offered to them (no mesh of their own)
    measures_intact_tooth = uncracked and mesher in (None, ring_mesh, ring_pieces)
    mesher = mesher or ring_mesh
    span = contact_radii(ring, [GearPair(planet, ring)])
    options = [scaled_options(factor * scale) for factor in PLANE_LEVELS]
    ratios = level_ratios(options)
    results = {}
    for name, level in zip(LEVEL_NAMES, options):
        if not uncracked and mesher is ring_pieces:
            provide_intact_curve(ring, span, material, level, tooth,
                                 _intact_tooth(ring, planet, crack, level, material, n_planets))
        started = time.perf_counter()
        mesh = mesher(ring, crack, level)
        meshed = time.perf_counter()
        result = crack_level(ring, planet, crack, mesh, level, material, n_planets,
                             intact_tooth=tooth if measures_intact_tooth else None)
        if measures_intact_tooth:
            offer_intact_curve(ring, span, material, level, tooth, result.intact_tooth)
        results[name] = (result, meshed - started, time.perf_counter() - meshed)
    solved = [results[name][0] for name in LEVEL_NAMES]
    fine = solved[2]
    ratio_levels = (1.0, 1.0, 1.0)
    engaged = fine.engaged
    if engaged is None:  # intact: the same tooth's engagement on the fine level's options
        engaged = engaged_mesh(planet, ring, None, scaled_options(scale), material, tooth)
    else:
        ratio_levels = tuple(float(level.engaged.mean_ratio) for level in solved)
    intact = engaged_intact(engaged)
    ratios_of = dict(c_rp_engaged_ratio=ratio_levels[2],
                     c_rp_engaged_ratio_error=level_error(ratio_levels, ratios).error,
                     c_rp_engaged_min_ratio=(1.0 if fine.engaged is None
                                             else fine.engaged.min_ratio))
    rim_ru = tuple(float(level.ring.work.c_ru_rim) for level in solved)
    rim_r = tuple(float(level.ring.work.c_r_rim) for level in solved)
    land_ru = tuple(float(level.ring.c_ru) for level in solved)
    land_r = tuple(float(level.ring.c_r) for level in solved)
    ring_fine = fine.ring
    return CrackCaseEstimate(
        c_ru=rim_ru[2], c_ru_error=level_error(rim_ru, ratios).error,
        c_ru_min=float(ring_fine.work.c_ru_rim_positions.min()),
        c_ru_max=float(ring_fine.work.c_ru_rim_positions.max()),
        c_r=rim_r[2], c_r_error=level_error(rim_r, ratios).error,
        **ratios_of, **intact,
        c_ru_root_land=land_ru[2], c_ru_root_land_error=level_error(land_ru, ratios).error,
        c_r_root_land=land_r[2], c_r_root_land_error=level_error(land_r, ratios).error,
        dofs=ring_fine.dofs, solver=ring_fine.seconds["solver"],
        seconds_mesh=results["fine"][1], seconds_fe=results["fine"][2],
        seconds_total=sum(r[1] + r[2] for r in results.values()),
        c_ru_levels=rim_ru, c_r_levels=rim_r, c_ru_root_land_levels=land_ru,
        c_r_root_land_levels=land_r, c_rp_engaged_ratio_levels=ratio_levels,
        level_ratios=ratios)


def _intact_tooth(ring, planet, crack, options, material, n_planets: int):
    """The computation of the intact curve of ``crack``'s tooth on the intact ring's pieces
    (the block of the crack's mouth, ``meshing.ring_pieces``), as the intact case gives it."""
    def compute():
        intact = Crack(crack.tooth, 0.0, getattr(crack, "angle", 0.0), crack.start)
        level = crack_level(ring, planet, intact, ring_pieces(ring, intact, options), options,
                            material, n_planets, intact_tooth=crack.tooth)
        return level.intact_tooth
    return compute


@dataclass(frozen=True)
class MeshEstimate:
    """One gear mesh's stiffness over the mesh cycle, with its checks.

    Attributes
    ----------
    value, error : float
        FE mean over the mesh cycle and its error estimate [N/m].
    min, max, single_pair_max : float
        Lowest, highest over the cycle, and highest single-pair value [N/m].
    contact_ratio : float
        Transverse contact ratio [-].
    analytic, iso_c_gamma, iso_c_single : float
        Potential-energy model and ISO 6336-1 c_gamma_alpha b, c' b [N/m].
    iso_in_range : bool
        Whether the profile shifts lie in ISO 6336-1's fitted range.
    seconds_total : float
        Both levels [s].
    engaged, engaged_intact, engaged_min, engaged_intact_min : float or None
        With a cracked ring tooth: mean and minimum over its engagement, cracked
        and intact [N/m].
    levels : tuple of float
        The FE mean on each level, coarsest first [N/m]; ``error`` is their
        ``three_level_error`` (``error_of``).
    level_ratios : tuple of float
        Element size of the coarsest level over the coarse one's and of the coarse over
        the fine one's [-].
    """

    value: float
    error: float
    min: float
    max: float
    single_pair_max: float
    contact_ratio: float
    analytic: float
    iso_c_gamma: float
    iso_c_single: float
    iso_in_range: bool
    seconds_total: float
    engaged: float | None = None
    engaged_intact: float | None = None
    engaged_min: float | None = None
    engaged_intact_min: float | None = None
    levels: tuple = ()
    level_ratios: tuple = ()

    def error_of(self) -> ThreeLevelError:
        """The three-level error (estimate, error, order, rule) of ``value``."""
        return level_error(self.levels, self.level_ratios)

    def to_dict(self, engaged: bool = True) -> dict:
        """Keys with units (``value_N_m`` ...), as in ``hubvib stiffness --json``."""
        out = {}
        for key, value in asdict(self).items():
            if key.startswith("engaged") and (value is None or not engaged):
                continue
            if key in ("contact_ratio", "iso_in_range", "seconds_total", "level_ratios"):
                out[key] = value
            else:
                out[f"{key}_N_m"] = value
        return out


def estimate_mesh(sun, planet, ring, crack=None, scale: float = 1.0,
                  material=None) -> dict[str, MeshEstimate]:
    """c_sp and c_rp (FE mean over the mesh cycle) on the default mesh (sizes times
    ``scale``) with their three-level errors (``PLANE_LEVELS``); analytical and ISO 6336-1
    values beside them.

    ``sun``, ``planet`` are gear bodies, ``ring`` the ring gear; with ``crack`` the
    ring-planet mesh is also given over the cracked tooth's engagement.
    """
    options = [scaled_options(factor * scale) for factor in PLANE_LEVELS]
    ratios = level_ratios(options)
    results = {}
    for name, level in zip(LEVEL_NAMES, options):
        started = time.perf_counter()
        results[name] = (reducer_mesh_stiffness(sun, planet, ring, level, crack,
                                                **({} if material is None else
                                                   {"material": material})),
                         time.perf_counter() - started)
    seconds = sum(r[1] for r in results.values())
    out = {}
    for key, fine in results["fine"][0].items():
        levels = tuple(float(results[name][0][key].value) for name in LEVEL_NAMES)
        engaged = {}
        if fine.cracked is not None:
            intact = fine.cracked_reference
            engaged = dict(engaged=fine.cracked.mean, engaged_intact=intact.mean,
                           engaged_min=float(fine.cracked.stiffness.min()),
                           engaged_intact_min=float(intact.stiffness.min()))
        out[key] = MeshEstimate(
            value=fine.value, error=level_error(levels, ratios).error,
            min=float(fine.fe.stiffness.min()), max=float(fine.fe.stiffness.max()),
            single_pair_max=fine.fe.single_pair_max, contact_ratio=fine.pair.contact_ratio,
            analytic=fine.analytic.mean, iso_c_gamma=fine.iso_mesh, iso_c_single=fine.iso_single,
            iso_in_range=fine.iso_in_range, seconds_total=seconds, **engaged, levels=levels,
            level_ratios=ratios)
    return out
