"""Smallest detectable crack depth on the elastic ring against the ring's mounting (SI;
the elastic ring's side of :mod:`.mounting_map`, through ``ElasticMounting``).

The foundation of the elastic ring (``k_n`` and ``k_t`` per unit arc length on the
support arcs, by default sized to the design's lumped ``c_r`` and ``c_ru``) is scaled by
``s`` (both together, log-spaced).  Per crack depth the FE ring is reduced once for every
scale (:mod:`hubvib.elastic.mounting_basis`: its modes, the contact responses and the
arcs' reaction responses), so each ``(depth, s)`` is a small dense coupled problem; the
reduced ring equals full rebuilds over the scales served (``tests/elastic/test_elastic_map.py``).
The reference foundation is the intact ring's, for every depth (the crack does not touch
the support arcs).

The detection rule is :func:`.elastic_model.elastic_result`'s, at each scale: planet 1
half a pitch from the cracked tooth, the cracked modes tracked to the intact ones (subspace match of
at least ``MIN_MATCH``), the faces open; the reducer's own intact record is the baseline;
watched: the modes the sensor sees (``VISIBLE``), ranked by their largest drop against
the identification scatter (``DetectionOptions.sigma_hz``), Sidak per-mode rate.  The
POD is a callable ``pod(shift_hz, sigma_hz, watched, rate) -> (depths,)`` (default the
nominal reducer's ``family_pod``: identification noise only, no parameter scatter).
Beside the family, the watched modes of the reference scale (s = 1) are followed over the
scales (subspace match between neighbouring scales) and each one's smallest detectable
depth alone is given (at the family's per-mode rate).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubvib.elastic.mounting_basis import cached_family_ring, ring_operators_at
from hubvib.elastic.options import ElasticScene
from hubvib.elastic.tracking import track_modes
from hubvib.foundation.output import explained, finite_or_none

from .elastic_model import MIN_MATCH, VISIBLE, sensor_visibility, tracked_to
from .options import DetectionOptions
from .pod import family_pod, watched_by_drop
from .resolution import bracket

#: foundation scales of the map (both stiffnesses x s); s = 1 is the reference
SCALES = tuple(float(s) for s in np.geomspace(0.1, 100.0, 13))

__all__ = ["ElasticMap", "elastic_map", "SCALES"]


@dataclass(frozen=True)
class ElasticMap:
    """The elastic ring's smallest detectable depth against its foundation.

    Attributes
    ----------
    scales : ndarray (S,)
        Foundation scale s [-]; the foundation is ``s * foundation``; ``inf`` (last, when
        asked): the ring clamped on its support arcs, the stiff limit.
    foundation : tuple
        Reference ``(k_n, k_t)`` [N/m^2] (s = 1).
    depths : tuple of float
        [m], the first 0.
    family_depth : ndarray (S,)
        Smallest depth whose family POD reaches ``detection_probability`` [m] (NaN: none
        of the sweep).
    family_pod : ndarray (S, depths)
    watched : tuple of tuple
        Per scale, the watched modes' intact frequencies [Hz], best first.
    modes_hz : ndarray (S, K)
        The reference scale's watched modes followed over the scales [Hz] (NaN: lost).
    mode_depth : ndarray (S, K)
        Each followed mode's smallest detectable depth alone [m] (NaN: none).
    mode_drop_hz : ndarray (S, K)
        Its largest drop over the sweep [Hz].
    lowest_ring_mode_hz : ndarray (S,)
        The mounted ring's lowest elastic mode of its own [Hz] (NaN: none in the basis).
    lowest_ring_mode_n : tuple
        Its nodal diameters (None: none).
    record_length, detection_probability : float
        [s], [-].
    pod_name : str
        The POD used (the callable's name).
    """

    scales: np.ndarray
    foundation: tuple
    depths: tuple
    family_depth: np.ndarray
    family_pod: np.ndarray
    watched: tuple
    modes_hz: np.ndarray
    mode_depth: np.ndarray
    mode_drop_hz: np.ndarray
    lowest_ring_mode_hz: np.ndarray
    lowest_ring_mode_n: tuple
    record_length: float
    detection_probability: float
    pod_name: str

    @property
    def reference(self) -> int:
        """Index of s = 1 in ``scales``."""
        return _reference(self.scales)

    def rows(self) -> list[dict]:
        """One dict per scale (JSON-ready; NaN as None; the clamped ring's scale None)."""
        out = []
        clamped_why = "the clamped ring: no foundation to scale"
        undetected = "no depth of the sweep reaches the detection probability"
        untracked = "the mode is not tracked on this foundation"
        no_ring_mode = "no elastic mode of the ring's own in the basis"
        for k, s in enumerate(self.scales):
            clamped = bool(np.isinf(s))
            out.append(explained({
                "scale": None if clamped else float(s), "clamped": clamped,
                "k_n_N_m2": None if clamped else s * self.foundation[0],
                "k_t_N_m2": None if clamped else s * self.foundation[1],
                "smallest_detectable_depth_mm": _mm(self.family_depth[k]),
                "lowest_ring_mode_hz": finite_or_none(self.lowest_ring_mode_hz[k]),
                "lowest_ring_mode_n": self.lowest_ring_mode_n[k],
                "watched_hz": list(self.watched[k]),
                "modes": [explained({"frequency_hz": finite_or_none(self.modes_hz[k, j]),
                                     "smallest_detectable_depth_mm": _mm(self.mode_depth[k, j]),
                                     "largest_drop_hz": finite_or_none(self.mode_drop_hz[k, j])},
                                    frequency_hz=untracked, largest_drop_hz=untracked,
                                    smallest_detectable_depth_mm=undetected)
                          for j in range(self.modes_hz.shape[1])],
                "family_pod": [float(p) for p in self.family_pod[k]]},
                scale=clamped_why, k_n_N_m2=clamped_why, k_t_N_m2=clamped_why,
                smallest_detectable_depth_mm=undetected, lowest_ring_mode_hz=no_ring_mode,
                lowest_ring_mode_n=no_ring_mode, watched_hz=untracked))
        return out


def _mm(depth) -> float | None:
    return 1e3 * float(depth) if np.isfinite(depth) else None


def _reference(scales) -> int:
    with np.errstate(divide="ignore"):
        return int(np.argmin(np.abs(np.log(np.asarray(scales, dtype=float)))))


@dataclass(frozen=True, eq=False)
class _Spectrum:
    """The coupled modes as the tracking and the sensor read them."""

    modes: object

    @property
    def frequency_hz(self) -> np.ndarray:
        return self.modes.frequency_hz


def first_detectable(depths, pod, probability: float) -> float:
    """Smallest depth > 0 with ``pod >= probability`` [m] (NaN: none): the upper end of the
    crossing's bracket (:func:`.resolution.bracket`)."""
    high = bracket(depths, pod, probability).high
    return math.nan if high is None else high


def tracked_hz(intact, cracked, ring_mass: float) -> np.ndarray:
    """Each intact mode's frequency in ``cracked`` (NaN: no match of ``MIN_MATCH``), as
    :func:`.elastic_model.tracked_to`."""
    return tracked_to(intact, cracked, ring_mass)[0]


def lowest_ring_mode(ring, scale: float) -> tuple[float, int | None]:
    """The reduced ring's lowest elastic mode of its own at ``scale`` [Hz] and its nodal
    diameters (NaN, None: none in the basis)."""
    import scipy.linalg as sla

    from hubvib.elastic.content import diameter_content, is_elastic_ring_shape

    ops = ring_operators_at(ring, scale)
    values, vectors = sla.eigh(ops.K)
    probe = ring.probe @ vectors
    for j, value in enumerate(values):
        if is_elastic_ring_shape(probe[:, j]):
            return (math.sqrt(max(value, 0.0)) / (2 * math.pi),
                    int(np.argmax(diameter_content(probe[:, j]))))
    return math.nan, None


def elastic_map(design, depths, crack_of, scene: ElasticScene, options: DetectionOptions,
                scales=SCALES, pod=family_pod, k_rest: float | None = None,
                rings: list | None = None, clamped: bool = False) -> ElasticMap:
    """The elastic ring's detectability against the foundation scale (module docstring).

    ``depths`` [m] (the first 0), ``crack_of(depth)`` the ``Crack`` of a depth (as
    :func:`.elastic_model.elastic_result`); ``scales`` must hold 1 (the reference
    foundation, ``scene.options``'s: given or sized); ``pod(shift_hz (depths, modes),
    sigma_hz (modes,), watched, rate) -> (depths,)``; ``rings``: the ``ScaledRing`` of
    every depth when computed elsewhere (:func:`ring_arguments`); ``clamped``: add the
    ring clamped on its arcs as the stiff limit (scale ``inf``; one FE ring per depth
    more, rebuilt: the family's basis does not reach it)."""
    from hubvib.reducer.stages import lumped_parameters
    from hubvib.elastic.model import out_of_contact_tooth
    from hubvib.elastic.rest import rest_stiffness
    from hubvib.foundation.blas import blas_threads
    from hubvib.lumped.elastic_ring import coupled_modes

    scales = np.asarray(scales, dtype=float)
    if scales.ndim != 1 or scales.size == 0 or not np.all(np.isfinite(scales)) or np.any(
            scales <= 0) or not np.any(np.isclose(scales, 1.0, rtol=1e-9)):
        raise ValueError(f"scales = {scales!r}: positive finite foundation scales holding 1")
    if scene.options.mounting != "foundation":
        raise ValueError(f"[elastic] mounting = {scene.options.mounting!r}: the map scales "
                         "a foundation; it needs mounting 'foundation'")
    if depths[0] != 0:
        raise ValueError(f"depths[0] = {depths[0]!r} m: the sweep starts intact (0)")
    params = lumped_parameters(design)
    k_rest = rest_stiffness(design, scene.options.rest) if k_rest is None else float(k_rest)
    if rings is None:
        rings = [cached_family_ring(*a) for a in ring_arguments(design, depths, crack_of,
                                                                  scene)]
    tooth = _away_tooth(design, crack_of, depths, out_of_contact_tooth)
    mass = rings[0].ring_mass
    record = options.record_length
    n_depths = len(depths)
    spectra = []  # per scale: the intact spectrum and the tracked frequencies per depth
    with blas_threads(1):
        for s in scales:
            ops = [ring_operators_at(r, s) for r in rings]
            modes = [_Spectrum(coupled_modes(params, o, tooth, k_rest,
                                             max_hz=scene.options.band_hz)) for o in ops]
            intact = modes[0]
            f = np.vstack([intact.frequency_hz] + [tracked_hz(intact, m, mass)
                                                   for m in modes[1:]])
            spectra.append((intact, f))
        if clamped:
            spectra.append(_clamped(design, depths, crack_of, scene, params, k_rest, tooth,
                                    mass))
    lowest = [lowest_ring_mode(rings[0], s) for s in scales]
    if clamped:
        lowest.append(spectra[-1][2])
        scales = np.append(scales, np.inf)
        spectra[-1] = spectra[-1][:2]
    ref = _reference(scales)
    family_depth = np.full(scales.size, np.nan)
    family = np.zeros((scales.size, n_depths))
    watched_hz, per_scale = [], []
    for k, (intact, f) in enumerate(spectra):
        shift = f - f[0]
        sigma = options.sigma_hz(intact.frequency_hz, record)
        visibility = sensor_visibility(intact, scene.sensor_angle)
        drop = np.nan_to_num(np.clip(-shift, 0.0, None), nan=0.0).max(axis=0)
        watched = watched_by_drop(shift, sigma, np.flatnonzero(visibility >= VISIBLE),
                                  options.watched_modes)
        rate = options.per_mode_rate(len(watched)) if watched else options.false_alarm_rate
        family[k] = np.asarray(pod(shift, sigma, watched, rate), dtype=float)
        family_depth[k] = first_detectable(depths, family[k], options.detection_probability)
        watched_hz.append(tuple(float(intact.frequency_hz[i]) for i in watched))
        per_scale.append((shift, sigma, watched, rate, drop))
    followed = _follow(spectra, ref, per_scale[ref][2], mass)
    K = len(per_scale[ref][2])
    modes_hz = np.full((scales.size, K), np.nan)
    mode_depth = np.full((scales.size, K), np.nan)
    mode_drop = np.full((scales.size, K), np.nan)
    for k, (shift, sigma, _, rate, drop) in enumerate(per_scale):
        for j in range(K):
            i = followed[k, j]
            if i < 0:
                continue
            modes_hz[k, j] = spectra[k][0].frequency_hz[i]
            mode_drop[k, j] = drop[i]
            alone = np.asarray(pod(shift, sigma, (int(i),), rate), dtype=float)
            mode_depth[k, j] = first_detectable(depths, alone, options.detection_probability)
    return ElasticMap(
        scales, tuple(rings[0].foundation), tuple(float(d) for d in depths), family_depth,
        family, tuple(watched_hz), modes_hz, mode_depth, mode_drop,
        np.array([x[0] for x in lowest]), tuple(x[1] for x in lowest),
        float(options.record_length), float(options.detection_probability),
        getattr(pod, "__name__", type(pod).__name__))


def _clamped(design, depths, crack_of, scene, params, k_rest, tooth, mass):
    """The intact spectrum, the tracked frequencies per depth and the ring's lowest mode
    of its own with the ring clamped on its support arcs."""
    from dataclasses import replace

    from hubvib.elastic.model import elastic_ring, elastic_spectrum
    from hubvib.elastic.model import lowest_ring_mode as ring_alone

    options = replace(scene.options, mounting="clamped", foundation_k_n=None,
                      foundation_k_t=None)
    spectra, lowest = [], (math.nan, None)
    for d in depths:
        er = elastic_ring(design, crack_of(d) if d > 0 else None, False, options, (tooth,),
                          params, k_rest)
        if d == 0:
            lowest = ring_alone(er) or (math.nan, None)
        spectra.append(_Spectrum(elastic_spectrum(er, tooth).modes))
    f = np.vstack([spectra[0].frequency_hz] + [tracked_hz(spectra[0], m, mass)
                                               for m in spectra[1:]])
    return spectra[0], f, lowest


def _away_tooth(design, crack_of, depths, out_of_contact_tooth) -> int:
    """Planet 1's tooth half a planet pitch from the cracked tooth."""
    from hubvib.reducer.stages import ring_gear

    z = ring_gear(design).teeth
    crack = crack_of(next((d for d in depths if d > 0), 0.0))
    tooth = 0 if crack is None else crack.tooth
    return (tooth + out_of_contact_tooth(z, design.n_planets)) % z


def _follow(spectra, ref: int, watched, mass: float) -> np.ndarray:
    """(scales, watched): each reference-scale watched mode's index in every scale's
    intact spectrum, followed outward from ``ref`` between neighbouring scales (-1: lost)."""
    out = np.full((len(spectra), len(watched)), -1)
    out[ref] = watched
    for step in (1, -1):
        k = ref
        while 0 <= k + step < len(spectra):
            t = track_modes(spectra[k][0], spectra[k + step][0], mass)
            at = {r: (j, m) for j, (r, m) in enumerate(zip(t.reference, t.match)) if r >= 0}
            for j in range(len(watched)):
                i = out[k, j]
                hit = at.get(int(i)) if i >= 0 else None
                out[k + step, j] = hit[0] if hit is not None and hit[1] >= MIN_MATCH else -1
            k += step
    return out


def ring_arguments(design, depths, crack_of, scene: ElasticScene) -> list[tuple]:
    """The arguments of ``cached_family_ring`` for every depth (the first 0: intact), to
    compute in a worker pool; the reference foundation is the intact ring's (sized on it
    unless the scene gives one), so the intact ring is reduced first, here."""
    from hubvib.elastic.model import out_of_contact_tooth

    tooth = _away_tooth(design, crack_of, depths, out_of_contact_tooth)
    o = scene.options
    given = None if o.foundation_k_n is None else (o.foundation_k_n, o.foundation_k_t)
    intact = cached_family_ring(design, None, o, given, (tooth,))
    return [(design, None, o, given, (tooth,))] + [
        (design, crack_of(d), o, intact.foundation, (tooth,)) for d in depths[1:]]
