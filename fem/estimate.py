"""FE stiffnesses with their error estimate: the default mesh against one twice as coarse (SI).

The estimated error is the difference between the two levels (an upper bound
when the convergence is monotone with rate >= 1; see the annulus study).
"""
from __future__ import annotations

import time
from dataclasses import MISSING, asdict, dataclass, fields

import numpy as np

from hubvib.fem.crack_level import crack_level
from hubvib.fem.material import Material
from hubvib.fem.ring_stiffness import ring_stiffness
from hubvib.fem.mesh_cycle import GearPair
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
             "tooth_compliance_coarse": "tooth_compliance_coarse_m_N"}
#: a cell whose gmsh min SICN is below this counts as poorly shaped
USABLE_QUALITY = 0.1
#: version of the dict form of the estimates (``to_dict`` / ``from_dict``), stored with
#: every FE cache entry: a change of the fields is a new version, and old entries go
#: (2: the crack case stores the absolute intact engaged c_rp; 3: the
#: crack case's c_ru and c_r are the work-conjugate rim parts, the root-land readings and
#: the intact engaged c_rp over the contact window beside them; 4: the
#: solid case stores its cracked tooth's line-load compliance)
SCHEMA_VERSION = 4


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


@dataclass(frozen=True)
class RingEstimate:
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
    tooth_radii, tooth_compliance, tooth_compliance_coarse : tuple of float
        With ``tooth`` (solid): the flank radii [m] and the tooth's line-load compliance
        [m/N] there on the fine and the coarse level (``fem.tooth_solid``; empty otherwise).
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

    def to_dict(self) -> dict:
        """Keys with units (``c_ru_N_m`` ...), as in the JSON output and the cache."""
        return {RING_KEYS.get(k, k): v for k, v in asdict(self).items()}

    @classmethod
    def from_dict(cls, data: dict) -> RingEstimate:
        """The inverse of ``to_dict`` (``SCHEMA_VERSION``); ``ValueError`` names a missing
        key or a value of the wrong type."""
        return _from_dict(cls, data)


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
    """c_ru and c_r on the default mesh (sizes times ``scale``) and on one twice as coarse.

    With ``solid``: the solid ring on the last two ``SOLID_LEVELS``, by default planet 1
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
    if solid:
        levels = {"coarse": solid_options(*SOLID_LEVELS[-2]),
                  "fine": solid_options(*SOLID_LEVELS[-1])}
    else:
        levels = {"coarse": scaled_options(2 * scale), "fine": scaled_options(scale)}
    results = {}
    teeth = [0] if solid and carrier_teeth is None else carrier_teeth
    for name, options in levels.items():
        started = time.perf_counter()
        mesh = (ring_mesh_3d(ring, crack, front or CrackFront(), options=options,
                             half_width=half_width) if solid
                else mesher(ring, crack, options))
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
    fine, coarse = results["fine"][0], results["coarse"][0]
    c_ru, c_ru_positions, c_r = _ring_values(fine, definition)
    c_ru_coarse, _, c_r_coarse = _ring_values(coarse, definition)
    land = {} if definition == "root_land" else dict(
        c_ru_root_land=fine.c_ru, c_ru_root_land_error=abs(fine.c_ru - coarse.c_ru),
        c_r_root_land=fine.c_r, c_r_root_land_error=abs(fine.c_r - coarse.c_r))
    teeth_values = {} if tooth is None else dict(
        tooth_radii=tuple(float(r) for r in fine.tooth.radii),
        tooth_compliance=tuple(float(q) for q in fine.tooth.compliance),
        tooth_compliance_coarse=tuple(float(q) for q in coarse.tooth.compliance))
    return RingEstimate(
        c_ru=c_ru, c_ru_error=abs(c_ru - c_ru_coarse),
        c_ru_min=float(c_ru_positions.min()), c_ru_max=float(c_ru_positions.max()),
        c_r=c_r, c_r_error=abs(c_r - c_r_coarse), dofs=fine.dofs,
        solver=fine.seconds["solver"], seconds_mesh=results["fine"][1],
        seconds_fe=results["fine"][2],
        seconds_total=sum(r[1] + r[2] for r in results.values()),
        c_ru_coarse=c_ru_coarse, c_r_coarse=c_r_coarse,
        min_quality=float(quality.min()), poor_cells=int(poor.sum()), **halved,
        definition=definition, **land, **teeth_values)


@dataclass(frozen=True)
class CrackCaseEstimate:
    """One crack case of a sweep: the ring body's stiffnesses and the cracked tooth's mesh
    stiffness, each on the default mesh with its error against a mesh twice as coarse.

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
        tooth), both levels in all.
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

    def to_dict(self) -> dict:
        """Keys with units, as ``RingEstimate.to_dict`` plus the ``c_rp_engaged_*`` ratios,
        the intact engaged c_rp (``c_rp_engaged_intact_N_m``, ``..._min_N_m``,
        ``..._window_N_m``) and the root-land readings (``c_ru_root_land_N_m`` ...)."""
        return {RING_KEYS.get(k, k): v for k, v in asdict(self).items()}

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
    cracked tooth's engaged c_rp ratio on the default plane mesh
    (sizes times ``scale``) and on one twice as coarse: per level one mesh, one assembly
    and one factorisation serve all three (``fem.crack_level``).

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
    results = {}
    for name, level in (("coarse", 2 * scale), ("fine", scale)):
        options = scaled_options(level)
        if not uncracked and mesher is ring_pieces:
            provide_intact_curve(ring, span, material, options, tooth,
                                 _intact_tooth(ring, planet, crack, options, material, n_planets))
        started = time.perf_counter()
        mesh = mesher(ring, crack, options)
        meshed = time.perf_counter()
        result = crack_level(ring, planet, crack, mesh, options, material, n_planets,
                             intact_tooth=tooth if measures_intact_tooth else None)
        if measures_intact_tooth:
            offer_intact_curve(ring, span, material, options, tooth, result.intact_tooth)
        results[name] = (result, meshed - started, time.perf_counter() - meshed)
    fine, coarse = results["fine"][0], results["coarse"][0]
    ratios = dict(c_rp_engaged_ratio=1.0, c_rp_engaged_ratio_error=0.0,
                  c_rp_engaged_min_ratio=1.0)
    engaged = fine.engaged
    if engaged is None:  # intact: the same tooth's engagement on the fine level's options
        engaged = engaged_mesh(planet, ring, None, scaled_options(scale), material, tooth)
    intact = engaged_intact(engaged)
    if fine.engaged is not None:
        ratios = dict(c_rp_engaged_ratio=fine.engaged.mean_ratio,
                      c_rp_engaged_ratio_error=abs(fine.engaged.mean_ratio
                                                   - coarse.engaged.mean_ratio),
                      c_rp_engaged_min_ratio=fine.engaged.min_ratio)
    ring_fine, ring_coarse = fine.ring, coarse.ring
    rim_fine, rim_coarse = ring_fine.work, ring_coarse.work
    return CrackCaseEstimate(
        c_ru=rim_fine.c_ru_rim, c_ru_error=abs(rim_fine.c_ru_rim - rim_coarse.c_ru_rim),
        c_ru_min=float(rim_fine.c_ru_rim_positions.min()),
        c_ru_max=float(rim_fine.c_ru_rim_positions.max()),
        c_r=rim_fine.c_r_rim, c_r_error=abs(rim_fine.c_r_rim - rim_coarse.c_r_rim),
        **ratios, **intact,
        c_ru_root_land=ring_fine.c_ru, c_ru_root_land_error=abs(ring_fine.c_ru - ring_coarse.c_ru),
        c_r_root_land=ring_fine.c_r, c_r_root_land_error=abs(ring_fine.c_r - ring_coarse.c_r),
        dofs=ring_fine.dofs, solver=ring_fine.seconds["solver"],
        seconds_mesh=results["fine"][1], seconds_fe=results["fine"][2],
        seconds_total=sum(r[1] + r[2] for r in results.values()))


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

    def to_dict(self, engaged: bool = True) -> dict:
        """Keys with units (``value_N_m`` ...), as in ``hubvib stiffness --json``."""
        out = {}
        for key, value in asdict(self).items():
            if key.startswith("engaged") and (value is None or not engaged):
                continue
            if key in ("contact_ratio", "iso_in_range", "seconds_total"):
                out[key] = value
            else:
                out[f"{key}_N_m"] = value
        return out


def estimate_mesh(sun, planet, ring, crack=None, scale: float = 1.0,
                  material=None) -> dict[str, MeshEstimate]:
    """c_sp and c_rp (FE mean over the mesh cycle) on the default mesh (sizes times
    ``scale``) and on one twice as coarse; analytical and ISO 6336-1 values beside them.

    ``sun``, ``planet`` are gear bodies, ``ring`` the ring gear; with ``crack`` the
    ring-planet mesh is also given over the cracked tooth's engagement.
    """
    results = {}
    for name, level in (("coarse", 2 * scale), ("fine", scale)):
        started = time.perf_counter()
        results[name] = (reducer_mesh_stiffness(sun, planet, ring, scaled_options(level), crack,
                                                **({} if material is None else
                                                   {"material": material})),
                         time.perf_counter() - started)
    seconds = sum(r[1] for r in results.values())
    out = {}
    for key, fine in results["fine"][0].items():
        coarse = results["coarse"][0][key]
        engaged = {}
        if fine.cracked is not None:
            intact = fine.cracked_reference
            engaged = dict(engaged=fine.cracked.mean, engaged_intact=intact.mean,
                           engaged_min=float(fine.cracked.stiffness.min()),
                           engaged_intact_min=float(intact.stiffness.min()))
        out[key] = MeshEstimate(
            value=fine.value, error=abs(fine.value - coarse.value),
            min=float(fine.fe.stiffness.min()), max=float(fine.fe.stiffness.max()),
            single_pair_max=fine.fe.single_pair_max, contact_ratio=fine.pair.contact_ratio,
            analytic=fine.analytic.mean, iso_c_gamma=fine.iso_mesh, iso_c_single=fine.iso_single,
            iso_in_range=fine.iso_in_range, seconds_total=seconds, **engaged)
    return out
