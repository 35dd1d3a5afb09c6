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
from hubvib.fem.tooth_stiffness import engaged_mesh, reducer_mesh_stiffness
from hubvib.meshing.crack import CrackFront
from hubvib.meshing.levels import SOLID_LEVELS, scaled_options, solid_options
from hubvib.meshing.ring_mesh import ring_mesh
from hubvib.meshing.ring_mesh_3d import ring_mesh_3d


#: field -> JSON / cache key with its unit
RING_KEYS = {"c_ru": "c_ru_N_m", "c_ru_error": "c_ru_error_N_m", "c_ru_min": "c_ru_min_N_m",
             "c_ru_max": "c_ru_max_N_m", "c_r": "c_r_N_m", "c_r_error": "c_r_error_N_m",
             "c_ru_coarse": "c_ru_coarse_N_m", "c_r_coarse": "c_r_coarse_N_m",
             "c_ru_poor_half": "c_ru_poor_half_N_m", "c_r_poor_half": "c_r_poor_half_N_m",
             "c_rp_engaged_intact": "c_rp_engaged_intact_N_m",
             "c_rp_engaged_intact_min": "c_rp_engaged_intact_min_N_m",
             "tooth_radii": "tooth_radii_m", "tooth_compliance": "tooth_compliance_m_N",
             "tooth_compliance_coarse": "tooth_compliance_coarse_m_N"}
#: a cell whose gmsh min SICN is below this counts as poorly shaped
USABLE_QUALITY = 0.1
#: version of the dict form of the estimates (``to_dict`` / ``from_dict``), stored with
#: every FE cache entry: a change of the fields is a new version, and old entries go
#: (2: the crack case stores the absolute intact engaged c_rp, issue 22 item 6)
SCHEMA_VERSION = 2


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
        Degrees of freedom of the fine level.
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


def estimate_ring(ring, crack=None, scale: float = 1.0, solver: str = "auto",
                  solid: bool = False, mesher=None, material=None,
                  n_planets: int = 3, front=None, carrier_teeth=None,
                  poor_cells_halved: bool = False, tooth=None) -> RingEstimate:
    """c_ru and c_r on the default mesh (sizes times ``scale``) and on one twice as coarse.

    With ``solid``: the solid ring on the last two ``SOLID_LEVELS``, by default planet 1
    on tooth 0 only.  ``mesher(ring, crack, options)`` replaces the plane mesher
    (to share meshes).  ``material`` (default steel) and ``n_planets`` (equally spaced)
    are the design's; ``front`` (``meshing.crack.CrackFront``) shapes a solid crack
    (default: through the face width); ``carrier_teeth`` lists the carrier positions as
    the tooth planet 1 loads (default: every tooth of one planet pitch in the plane);
    ``poor_cells_halved`` (solid) solves the fine level once more with the cells below
    ``USABLE_QUALITY`` at half stiffness.  ``tooth`` (solid: a
    ``fem.tooth_solid.SolidToothLoad``) measures that tooth's line-load compliance on both
    levels with the same factorisations.
    """
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
        mesh = (ring_mesh_3d(ring, crack, front or CrackFront(), options=options) if solid
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
        halved = dict(c_ru_poor_half=result.c_ru, c_r_poor_half=result.c_r)
        results["halved"] = (result, 0.0, time.perf_counter() - started)
    fine, coarse = results["fine"][0], results["coarse"][0]
    teeth_values = {} if tooth is None else dict(
        tooth_radii=tuple(float(r) for r in fine.tooth.radii),
        tooth_compliance=tuple(float(q) for q in fine.tooth.compliance),
        tooth_compliance_coarse=tuple(float(q) for q in coarse.tooth.compliance))
    return RingEstimate(
        c_ru=fine.c_ru, c_ru_error=abs(fine.c_ru - coarse.c_ru),
        c_ru_min=float(fine.c_ru_positions.min()), c_ru_max=float(fine.c_ru_positions.max()),
        c_r=fine.c_r, c_r_error=abs(fine.c_r - coarse.c_r), dofs=fine.dofs,
        solver=fine.seconds["solver"], seconds_mesh=results["fine"][1],
        seconds_fe=results["fine"][2],
        seconds_total=sum(r[1] + r[2] for r in results.values()),
        c_ru_coarse=coarse.c_ru, c_r_coarse=coarse.c_r,
        min_quality=float(quality.min()), poor_cells=int(poor.sum()), **halved,
        **teeth_values)


@dataclass(frozen=True)
class CrackCaseEstimate:
    """One crack case of a sweep: the ring body's stiffnesses and the cracked tooth's mesh
    stiffness, each on the default mesh with its error against a mesh twice as coarse.

    Attributes
    ----------
    c_ru, c_ru_error : float
        Reduced torsional stiffness, mean over the carrier positions of one planet
        pitch, and its error [N/m].
    c_ru_min, c_ru_max : float
        Lowest and highest c_ru over those carrier positions [N/m].
    c_r, c_r_error : float
        Radial (support) stiffness and its error [N/m].
    c_rp_engaged_ratio, c_rp_engaged_ratio_error : float
        Ring-planet mesh stiffness averaged over the cracked tooth's engagement, as a
        ratio to the same tooth intact, and its error [-] (1 and 0 without a crack).
    c_rp_engaged_min_ratio : float
        The same for the lowest value over the engagement [-].
    c_rp_engaged_intact, c_rp_engaged_intact_min : float
        The intact tooth's ring-planet mesh stiffness, mean and lowest over the mesh cycle
        [N/m] (the lumped c_rp of a design-derived scene).  The ratio's denominator is
        the intact mean over the cracked tooth's contact only, 4.75 % above this mean on
        the Raba stage, so the crack's extra compliance taken as
        ``(1/ratio - 1) / c_rp_engaged_intact`` [m/N] is that much too large (the series
        method; the ratio method does not use it).
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
    dofs: int
    solver: str
    seconds_mesh: float
    seconds_fe: float
    seconds_total: float

    def to_dict(self) -> dict:
        """Keys with units, as ``RingEstimate.to_dict`` plus the ``c_rp_engaged_*`` ratios
        and the intact engaged c_rp (``c_rp_engaged_intact_N_m``, ``..._min_N_m``)."""
        return {RING_KEYS.get(k, k): v for k, v in asdict(self).items()}

    @classmethod
    def from_dict(cls, data: dict) -> CrackCaseEstimate:
        """The inverse of ``to_dict`` (``SCHEMA_VERSION``); ``ValueError`` names a missing
        key or a value of the wrong type."""
        return _from_dict(cls, data)


def estimate_crack_case(ring, planet, crack, scale: float = 1.0, mesher=None, material=None,
                        n_planets: int = 3) -> CrackCaseEstimate:
    """c_ru, c_r and the cracked tooth's engaged c_rp ratio on the default plane mesh
    (sizes times ``scale``) and on one twice as coarse: per level one mesh, one assembly
    and one factorisation serve all three (``fem.crack_level``).

    ``crack`` (None or depth 0: intact) is measured on the tooth it is in; ``planet`` is
    the planet's gear body; ``mesher(ring, crack, options)`` replaces ``ring_mesh``;
    ``material`` (default steel) and ``n_planets`` (equally spaced) are the design's.
    """
    mesher = mesher or ring_mesh
    material = material or Material()
    results = {}
    for name, level in (("coarse", 2 * scale), ("fine", scale)):
        options = scaled_options(level)
        started = time.perf_counter()
        mesh = mesher(ring, crack, options)
        meshed = time.perf_counter()
        result = crack_level(ring, planet, crack, mesh, options, material, n_planets)
        results[name] = (result, meshed - started, time.perf_counter() - meshed)
    fine, coarse = results["fine"][0], results["coarse"][0]
    ratios = dict(c_rp_engaged_ratio=1.0, c_rp_engaged_ratio_error=0.0,
                  c_rp_engaged_min_ratio=1.0)
    engaged = fine.engaged
    if engaged is None:  # intact: the same tooth's engagement on the fine level's options
        engaged = engaged_mesh(planet, ring, None, scaled_options(scale), material,
                               0 if crack is None else crack.tooth)
    intact = dict(c_rp_engaged_intact=float(engaged.intact.mean),
                  c_rp_engaged_intact_min=float(engaged.intact.stiffness.min()))
    if fine.engaged is not None:
        ratios = dict(c_rp_engaged_ratio=fine.engaged.mean_ratio,
                      c_rp_engaged_ratio_error=abs(fine.engaged.mean_ratio
                                                   - coarse.engaged.mean_ratio),
                      c_rp_engaged_min_ratio=fine.engaged.min_ratio)
    ring_fine, ring_coarse = fine.ring, coarse.ring
    return CrackCaseEstimate(
        c_ru=ring_fine.c_ru, c_ru_error=abs(ring_fine.c_ru - ring_coarse.c_ru),
        c_ru_min=float(ring_fine.c_ru_positions.min()),
        c_ru_max=float(ring_fine.c_ru_positions.max()),
        c_r=ring_fine.c_r, c_r_error=abs(ring_fine.c_r - ring_coarse.c_r), **ratios, **intact,
        dofs=ring_fine.dofs, solver=ring_fine.seconds["solver"],
        seconds_mesh=results["fine"][1], seconds_fe=results["fine"][2],
        seconds_total=sum(r[1] + r[2] for r in results.values()))


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
