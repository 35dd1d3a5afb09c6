"""When the crack study's pictures are drawn: in a pool worker beside the detection stage,
or here, each through the render cache.

The lumped modes' pictures (``render.modes``) need only the intact spectrum, the FE ring's
(``render.fe``) only the crack sweep: both can be queued behind the FE cases.  The scene is
passed in (``params``, ``crack``, ``renders``, ``gif``, ``vtm``); lengths in metres.
"""
from __future__ import annotations

from dataclasses import asdict
from pathlib import Path

from hubvib.cases.sweep import ACCURACY, CrackSweep, crack_of
from hubvib.meshing.levels import scaled_options
from hubvib.reducer.stages import ring_gear
from hubvib.render.cache import array_digest, cached_render, is_cached
from hubvib.render.fe import render_fe, ring_fields
from hubvib.render.modes import render_modes
from hubvib.runtime.engines import EngineError, submit

__all__ = ["ELASTIC_SOURCE", "FE_SOURCE", "MODES_SOURCE", "begin_renders",
           "render_elastic_modes", "render_fe_ring", "render_mode_shapes", "rendered_depth",
           "scene_mounting", "study_renders"]

#: the entry modules of the two renders (their cache entries are keyed on the source of
#: every hubvib module these import: the FE ring's includes the FE stage it solves)
MODES_SOURCE = (render_modes.__module__,)
FE_SOURCE = (render_fe.__module__,)
#: the watched coupled modes' pictures: the drawing and the elastic ring it builds
ELASTIC_SOURCE = ("hubvib.render.coupled", "hubvib.elastic.cases")
#: relative difference allowed between the rebuilt intact ring's frequencies and those the
#: detection reported for the same modes (the same model: round-off only)
SAME_MODE_RTOL = 1e-6


def rendered_depth(sweep) -> float:
    """The deepest crack of the sweep that still has a tip (not through the rim) [m]."""
    ring = ring_gear(sweep.reducer)
    open_ended = [d for d in sweep.depths if d > 0 and not crack_of(sweep, d).is_through(ring)]
    return max(open_ended, default=max(sweep.depths))


def _render_modes(scene, spectrum, folder: Path) -> list[Path]:
    """Every elastic lumped mode (``render.render_modes``), from the render cache when the
    same spectrum was rendered before."""
    return render_mode_shapes(scene.params, spectrum, scene.gif, scene.vtm, folder)


def _mode_render_inputs(params, spectrum, gif: bool, vtm: bool) -> dict:
    """The render cache's inputs of the lumped mode pictures."""
    return {"params": params.to_dict(), "omega": array_digest(spectrum.omega),
            "shapes": array_digest(spectrum.shapes), "kind": list(spectrum.kind),
            "gif": gif, "vtm": vtm}


def render_mode_shapes(params, spectrum, gif: bool, vtm: bool, folder: Path) -> list[Path]:
    """``_render_modes`` from picklable arguments (it may run in a worker)."""
    def render(target):
        return render_modes(params, spectrum, target, gif=gif, vtm=vtm)

    return cached_render("modes", _mode_render_inputs(params, spectrum, gif, vtm), folder,
                         render, MODES_SOURCE)


def scene_mounting(scene) -> tuple[str, tuple | None]:
    """The mounting the report's ring is on: its elastic ring's (``[elastic]`` mounting and
    foundation stiffness (k_n, k_t) [N/m^2], None: sized to the design's c_r and c_ru)."""
    options = scene.elastic.options
    foundation = (None if options.foundation_k_n is None
                  else (options.foundation_k_n, options.foundation_k_t))
    return options.mounting, foundation


def _render_fe(scene, folder: Path) -> list[Path]:
    """The FE ring at the rendered depth (``fe_render``), its modes on the scene's mounting,
    from the render cache when the same design, crack, mesh and mounting were rendered by
    this FE stage before."""
    return render_fe_ring(scene.crack, scene.vtm, folder, *scene_mounting(scene))


def _fe_render_case(sweep: CrackSweep, vtm: bool, mounting: str = "foundation",
                    foundation: tuple | None = None) -> tuple:
    """The crack and mesh options the FE ring is rendered with, and the render cache's
    inputs (everything that decides the pictures)."""
    depth = rendered_depth(sweep)
    crack = crack_of(sweep, depth) if depth > 0 else None
    options = scaled_options(ACCURACY[sweep.accuracy])
    inputs = {"design": sweep.reducer.fingerprint(),
              "crack": None if crack is None else asdict(crack), "options": asdict(options),
              "vtu": vtm, "mounting": mounting,
              "foundation": None if foundation is None else list(foundation)}
    return crack, options, inputs


def render_fe_ring(sweep: CrackSweep, vtm: bool, folder: Path, mounting: str = "foundation",
                   foundation: tuple | None = None) -> list[Path]:
    """``_render_fe`` from the sweep and the mounting (picklable arguments: it may run in
    a worker, ``begin_renders``); ``mounting``, ``foundation`` as ``render.fe.ring_fields``
    takes them."""
    crack, options, inputs = _fe_render_case(sweep, vtm, mounting, foundation)

    def render(target):
        return render_fe(ring_fields(sweep.reducer, crack, options, mounting=mounting,
                                     foundation=foundation), target, vtu=vtm)

    return cached_render("fe-ring", inputs, folder, render, FE_SOURCE)


def _rendered(future, what: str) -> list[Path]:
    """The files of a render run on a pool worker; a worker that died or failed there is
    one line naming the render, as a failed FE case is (``EngineError``)."""
    try:
        return future.result()
    except Exception as exc:  # noqa: BLE001 - the worker's error, reported as the case's
        raise EngineError(f"the {what} render failed on a pool worker: "
                          f"{type(exc).__name__}: {exc}") from None


def begin_renders(scene, folder: Path, pool, begun: dict, spectrum=None) -> None:
    """Submit to ``pool`` (a ``worker_pool``) the renders that the render cache does not
    hold: the FE ring's (``spectrum`` None: it needs only the scene) or the lumped modes'
    (of ``spectrum``, the intact one), into ``folder / "renders"``; ``begun`` gets their
    futures (``study_renders``; one already begun is not submitted again).  Queued
    behind the FE cases, they run on the pool's workers as the cases leave them idle,
    beside this process's detection stage and plots."""
    kind = "fe" if spectrum is None else "modes"
    if not scene.renders or pool is None or kind in begun:
        return
    target = Path(folder) / "renders"
    if spectrum is not None:
        inputs = _mode_render_inputs(scene.params, spectrum, scene.gif, scene.vtm)
        if not is_cached("modes", inputs, MODES_SOURCE):
            begun["modes"] = submit(pool, render_mode_shapes, scene.params, spectrum,
                                    scene.gif, scene.vtm, target)
    elif scene.crack.model == "plane" and not is_cached(
            "fe-ring", _fe_render_case(scene.crack, scene.vtm, *scene_mounting(scene))[2],
            FE_SOURCE):
        begun["fe"] = submit(pool, render_fe_ring, scene.crack, scene.vtm, target,
                             *scene_mounting(scene))


def study_renders(scene, spectrum, folder: Path, begun: dict) -> tuple[list, list]:
    """The mode shapes of ``spectrum`` and the FE ring's pictures in ``folder / "renders"``:
    those ``begin_renders`` began (``begun``) from their workers, the rest drawn here."""
    modes = (_rendered(begun["modes"], "mode shapes") if "modes" in begun else
             _render_modes(scene, spectrum, folder / "renders"))
    # the FE render is of the plane ring; a solid study's crack is part-width
    fe = ([] if scene.crack.model != "plane"
          else _rendered(begun["fe"], "FE ring") if "fe" in begun
          else _render_fe(scene, folder / "renders"))
    return modes, fe


def render_elastic_modes(design, elastic_scene, watched, intact_hz, k_rest: float,
                         folder: Path, tooth: int = 0) -> list[Path]:
    """Pictures of the elastic ring's watched coupled modes (``render.coupled``, files
    ``elastic_mode_RR_<class>_n<N>_<f>Hz_<mounting>.png``) in ``folder``, from the render
    cache when drawn before.

    The intact ring is rebuilt as the detection built it (``elastic.cases.elastic_case``:
    ``elastic_scene``'s options, ``k_rest`` [N/m], planet 1 half a planet pitch from the
    cracked ``tooth``); ``watched`` (0-based, best first) index its coupled modes and
    ``intact_hz`` [Hz] are their frequencies as the detection reported them: a mismatch
    beyond round-off raises ``ValueError`` (the picture would show another mode)."""
    watched = [int(j) for j in watched]
    intact_hz = [float(f) for f in intact_hz]
    if len(watched) != len(intact_hz):
        raise ValueError(f"render_elastic_modes: {len(watched)} watched modes but "
                         f"{len(intact_hz)} frequencies")
    options = elastic_scene.options
    inputs = {"design": design.fingerprint(), "options": repr(options), "watched": watched,
              "intact_hz": [round(f, 6) for f in intact_hz], "k_rest": float(k_rest),
              "tooth": int(tooth)}

    def render(target):
        from hubvib.elastic.cases import carrier_positions
        from hubvib.elastic.model import elastic_ring, elastic_spectrum
        from hubvib.render.coupled import render_watched_modes

        away, on = carrier_positions(design, tooth)
        er = elastic_ring(design, None, False, options, (away, on), k_rest=k_rest)
        spectrum = elastic_spectrum(er, away)
        for j, f in zip(watched, intact_hz):
            if j >= spectrum.frequency_hz.size or not abs(
                    spectrum.frequency_hz[j] - f) <= SAME_MODE_RTOL * f:
                got = (f"{spectrum.frequency_hz[j]:.6g} Hz"
                       if j < spectrum.frequency_hz.size else "no such mode")
                raise ValueError(f"render_elastic_modes: coupled mode {j + 1} of the rebuilt "
                                 f"intact ring is {got}, the detection reported {f:.6g} Hz")
        return render_watched_modes(er, spectrum, watched, target)

    return cached_render("elastic-modes", inputs, folder, render, ELASTIC_SOURCE)
