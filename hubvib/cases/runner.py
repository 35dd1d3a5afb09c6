"""FE stage of a crack sweep: c_ru, c_r and c_rp of the cracked ring, one case per crack (SI).

``model = "plane"``: one case per depth, a crack through the face width in plane
stress.  ``c_rp`` is the ring-planet mesh stiffness averaged over the engagement
of the cracked tooth, as a ratio to the same window intact; the tooth model
loads tooth 0, so the crack is moved there (the tooth's compliance relative
to its root lands does not depend on where the supports are).

``model = "solid"``: one case per depth and half-length, a semi-elliptic root
crack centred on the face width in the solid ring (``c_ru``, ``c_r``, and the
cracked tooth's compliance under a line load across the face at the flank radii
of the plane tooth model, ``fem.tooth_solid``, from the same factorisations); its
``c_rp`` ratio follows in ``hubvib.studies.crack_growth`` (against the intact
case), which compares it with the slice method's from the plane cases.

Every case is cached (``hubvib.runtime.fe_cache``: keyed on the design, the crack, the
mesh level and the source of every hubvib module this one imports, ``SOURCE``; checked
before it is used), written
atomically by the calling process when it finishes.  A sweep killed at any point
resumes without losing or recomputing a finished case.  Cases run in worker
processes or on a Dask cluster (``hubvib.runtime.engines``).
"""
from __future__ import annotations

import sys
import time
from contextlib import ExitStack
from dataclasses import asdict, dataclass

from hubvib.reducer.stages import gear_body, material, ring_gear
from hubvib.fem.estimate import PLANE_LEVELS, estimate_crack_case
from hubvib.fem.mesh_cycle import GearPair
from hubvib.fem.tooth_solid import SAMPLES, SolidToothLoad
from hubvib.fem.tooth_stiffness import chebyshev_radii, contact_radii, set_intact_store
from hubvib.meshing.cache import root_folder
from hubvib.meshing.polyline_crack import PathCrack, path_ring_mesh
from hubvib.meshing.ring_pieces import ring_pieces
from hubvib.foundation.source_graph import source_key
from hubvib.runtime.engines import Execution, check_reachable, run_cases
from hubvib.runtime.fe_cache import (CacheEntryError, case_lock, entry_key, finite_positive,
                                     read_entry, write_entry)
from hubvib.runtime.progress import progress as hubvib_progress
from hubvib.runtime.tooth_curves import shared_intact_curve
from hubvib.cases.piece_store import pieces_on_disk
from hubvib.cases.results import PlaneCase, SolidCase, typed_case
from hubvib.cases.sweep import ACCURACY, CrackSweep, crack_of, front_of

#: the entry module of an FE case: its cache entries are keyed on the source of every
#: hubvib module it imports (``hubvib.foundation.source_graph``)
SOURCE = (__name__,)
#: every value of a case's result that must be a finite number > 0
POSITIVE_KEYS = ("c_ru_N_m", "c_r_N_m", "c_ru_min_N_m", "c_ru_max_N_m", "c_rp_engaged_ratio",
                 "c_rp_engaged_min_ratio", "c_rp_engaged_intact_N_m",
                 "c_rp_engaged_intact_min_N_m", "c_rp_engaged_intact_window_N_m",
                 "c_ru_root_land_N_m", "c_r_root_land_N_m")
#: the same for a solid case (its c_rp comes from the plane cases)
SOLID_POSITIVE_KEYS = ("c_ru_N_m", "c_r_N_m", "c_ru_min_N_m", "c_ru_max_N_m", "c_ru_coarse_N_m",
                       "c_r_coarse_N_m", "c_ru_poor_half_N_m", "c_r_poor_half_N_m")


def case_label(case) -> str:
    if isinstance(case, tuple):
        return f"depth {1e3 * case[0]:.4g} mm, half-length {1e3 * case[1]:.4g} mm"
    return f"depth {1e3 * case:.4g} mm"


def case_inputs(sweep: CrackSweep, case) -> dict:
    """Everything that decides one case's FE values, as plain data."""
    if isinstance(case, tuple):
        from hubvib.meshing.levels import SOLID_LEVELS

        depth, half_length = case
        return {"design": sweep.reducer.fingerprint(), "crack": asdict(crack_of(sweep, depth)),
                "front": asdict(front_of(half_length)) if depth > 0 else None,
                "levels": SOLID_LEVELS[-3:], "tooth_samples": SAMPLES, "half_width": True,
                "quantities": "solid c_ru c_r pitch poor-half tooth-line-load half-width"}
    crack = crack_of(sweep, case)
    return {"design": sweep.reducer.fingerprint(), "crack": asdict(crack),
            "scale": ACCURACY[sweep.accuracy], "levels": PLANE_LEVELS,
            "ring": mesher_of(sweep, crack).__name__, "quantities": "c_ru c_r c_rp_engaged"}


def mesher_of(sweep: CrackSweep, crack):
    """The plane ring's mesher of ``crack``: along a predicted path the whole ring
    (``path_ring_mesh``), else the ring glued from pieces and solved by substructures
    (``ring_pieces``) unless ``sweep.substructure`` is False (``ring_mesh``)."""
    from hubvib.meshing.ring_mesh import ring_mesh

    if isinstance(crack, PathCrack):
        return path_ring_mesh
    return ring_pieces if sweep.substructure else ring_mesh


def fe_case(sweep: CrackSweep, case) -> PlaneCase | SolidCase:
    """c_ru, c_r, c_rp with error estimate and timing for one case (runs in a worker).

    Plane: per mesh level (three, for the error bars) one mesh, one assembly and one
    factorisation serve c_ru, c_r and the cracked tooth's compliance
    (``fem.estimate.estimate_crack_case``), the ring glued from pieces and solved by
    substructures unless ``sweep.substructure`` is False (``mesher_of``).  Solid:
    c_ru over every carrier position of one planet pitch and c_r (the work-conjugate rim
    parts, the root-land readings beside them) on the three
    ``SOLID_LEVELS``, and on the fine one again with its poorly shaped cells at half
    stiffness; every solid case is mirror-symmetric about the face width's mid-plane
    (crack centred, loads and supports uniform across the width), so half the width is
    meshed and solved (``fem.solid``)."""
    started = time.perf_counter()
    design = sweep.reducer
    if isinstance(case, tuple):
        from hubvib.fem.estimate import estimate_ring
        from hubvib.fem.ring_stiffness import default_carrier_teeth

        depth, half_length = case
        ring = ring_gear(design)
        result = estimate_ring(ring, crack_of(sweep, depth) if depth > 0 else None, solid=True,
                               front=front_of(half_length) if depth > 0 else None,
                               material=material(design), n_planets=design.n_planets,
                               carrier_teeth=default_carrier_teeth(ring, design.n_planets),
                               poor_cells_halved=True, definition="rim",
                               tooth=SolidToothLoad(sweep.tooth, tooth_radii(design)),
                               half_width=True)
        return SolidCase(result, float(depth), float(half_length),
                         time.perf_counter() - started)
    depth = case
    crack = crack_of(sweep, depth)
    result = estimate_crack_case(ring_gear(design), gear_body(design, "planet"), crack,
                                 ACCURACY[sweep.accuracy], mesher=mesher_of(sweep, crack),
                                 material=material(design), n_planets=design.n_planets)
    return PlaneCase(result, float(depth), time.perf_counter() - started)


def tooth_radii(design) -> tuple:
    """The flank radii [m] of the ring's tooth curve: the plane tooth model's Chebyshev
    radii over the ring-planet contact (``fem.tooth_stiffness``)."""
    ring = ring_gear(design)
    span = contact_radii(ring, [GearPair(gear_body(design, "planet"), ring)])
    return tuple(float(r) for r in chebyshev_radii(*span))


def cache_folder():
    return root_folder() / "stiffness"


def check_case(case):
    """The plausibility check of a cached case (a depth [m], or depth and half-length): the
    typed result reads back (``PlaneCase`` / ``SolidCase``.from_dict), then its values; the
    check returns that typed case."""
    if isinstance(case, tuple):
        return _check_solid_case(case)
    depth = case

    def check(result: dict) -> PlaneCase:
        case = _typed(PlaneCase, result)
        finite_positive(result, POSITIVE_KEYS)
        if case.depth != depth:
            raise CacheEntryError(f"depth_m = {case.depth!r}, the case is {depth!r}")
        e = case.estimate
        if not e.c_ru_min <= e.c_ru <= e.c_ru_max:
            raise CacheEntryError("c_ru outside its own min..max over carrier positions")
        for key in ("c_rp_engaged_ratio", "c_rp_engaged_min_ratio"):
            value = getattr(e, key)
            if not value <= 1 + 1e-6 or (depth == 0 and value != 1.0):
                raise CacheEntryError(f"{key} = {value!r}: a crack cannot stiffen the tooth")
        return case
    return check


def _check_solid_case(case):
    def check(result: dict) -> SolidCase:
        finite_positive(result, SOLID_POSITIVE_KEYS)
        solid = _typed(SolidCase, result)
        found = (solid.depth, solid.half_length)
        if found != case:
            raise CacheEntryError(f"(depth_m, half_length_m) = {found!r}, the case is {case!r}")
        e = solid.estimate
        if not e.c_ru_min <= e.c_ru <= e.c_ru_max:
            raise CacheEntryError("c_ru outside its own min..max over carrier positions")
        for key in ("tooth_compliance", "tooth_compliance_coarse"):
            values = getattr(e, key)
            if len(values) != len(e.tooth_radii) or not len(values) or not all(
                    0 < v < float("inf") for v in values):
                raise CacheEntryError(f"{key} = {list(values)!r}: allowed one finite value > 0 "
                                      f"per flank radius ({len(e.tooth_radii)})")
        return solid
    return check


def _typed(kind, result: dict):
    try:
        return kind.from_dict(result)
    except ValueError as exc:
        raise CacheEntryError(str(exc)) from None


def crack_cases(sweep: CrackSweep, progress: bool = True,
                execution: Execution = Execution(), pool=None,
                after_submit=None) -> tuple[list[PlaneCase | SolidCase], int]:
    """Every case of ``sweep`` typed (``sweep.cases`` order: ``PlaneCase`` or ``SolidCase``),
    from the cache or computed; returns them and how many ran.  ``pool``: a ``worker_pool``
    of ``sweep.workers`` to run them in (left open), ``after_submit``: called when they are
    queued there (``runtime.engines.run_cases``).  The cache holds each case's dict form:
    written from the worker's typed case, read back typed by its check (``check_case``)."""
    if sweep.design is not None and not sweep.reducer.equally_spaced:
        raise ValueError(f"design {sweep.reducer.name!r}: the FE ring model loads equally spaced "
                         "planets only; unequal planet_angles_deg work in the lumped model but "
                         "not in the crack study")
    folder = cache_folder()
    inputs = {d: case_inputs(sweep, d) for d in sweep.cases}
    paths = {d: folder / f"{entry_key(inputs[d], modules=SOURCE)}.json" for d in sweep.cases}
    results = {}

    def cached(case, notice):
        check, typed = check_case(case), []
        try:
            read_entry(paths[case], inputs[case], lambda entry: typed.append(check(entry)),
                       modules=SOURCE)
        except CacheEntryError as exc:
            if notice and str(exc) != "missing":
                print(f"hubvib: cache entry {paths[case].name} for {case_label(case)}: {exc}; "
                      "recomputing", file=sys.stderr)
            return False
        results[case] = typed[0]
        return True

    todo = [d for d in sweep.cases if not cached(d, notice=True)]
    if todo:
        check_reachable(execution)
    bar = (hubvib_progress(len(sweep.cases), "FE crack cases", "case",
                           len(sweep.cases) - len(todo)) if progress else _Silent())

    def store(case, result):
        result = typed_case(result)
        write_entry(paths[case], inputs[case], result.to_dict(), modules=SOURCE)
        results[case] = result
        bar.update(1, f"{case_label(case)}, {result.seconds_total:.1f} s")

    computed = 0
    try:
        for attempt in ("others may hold", "wait"):
            mine, busy = [], []
            with _locks(paths, todo, wait=attempt == "wait") as held:
                for case in todo:
                    if case in held and not cached(case, notice=False):
                        mine.append(case)
                    elif case not in held:
                        busy.append(case)
                    else:
                        bar.update(1)
                run_cases(_Case(sweep, source_key(*SOURCE)), mine, store, execution,
                          sweep.workers, pool, after_submit)
                computed += len(mine)
            todo = [d for d in busy if not cached(d, notice=False)]
            if not todo:
                break
    finally:
        bar.close()
    return [results[d] for d in sweep.cases], computed


def run_fe_cases(sweep: CrackSweep, progress: bool = True,
                 execution: Execution = Execution(), pool=None,
                 after_submit=None) -> tuple[list[dict], int]:
    """``crack_cases`` in the dict form of the cache and of ``results.json`` (keys with
    units, ``PlaneCase.to_dict``): for callers that hold rows, not typed cases."""
    cases, computed = crack_cases(sweep, progress, execution, pool, after_submit)
    return [case.to_dict() for case in cases], computed


@dataclass(frozen=True)
class _Case:
    """``fe_case`` bound to its sweep: one picklable callable of the case.  It refuses to
    run on a worker whose source differs from the client's (its result would be cached
    under the client's source key)."""

    sweep: CrackSweep
    source: str

    def __call__(self, case) -> PlaneCase | SolidCase:
        if source_key(*SOURCE) != self.source:
            raise RuntimeError(f"this worker's FE source (key {source_key(*SOURCE)[:16]}) is "
                               f"not the client's ({self.source[:16]}): install the same "
                               "hubvib on every worker")
        set_intact_store(shared_intact_curve)  # the intact tooth curves: once per stage
        try:
            with pieces_on_disk():  # the intact pieces: once per design and mesh level
                return fe_case(self.sweep, case)
        finally:
            set_intact_store(None)


class _locks:
    """Lock each entry of ``cases``; ``held`` is the set locked by this process."""

    def __init__(self, paths, cases, wait):
        self.stack, self.paths, self.cases, self.wait = None, paths, cases, wait

    def __enter__(self):
        self.stack = ExitStack()
        held = set()
        for case in self.cases:
            if self.stack.enter_context(case_lock(self.paths[case], self.wait)):
                held.add(case)
        return held

    def __exit__(self, *exc):
        self.stack.close()


class _Silent:
    def update(self, n: int = 1, note: str = "") -> None:
        pass

    def close(self) -> None:
        pass
