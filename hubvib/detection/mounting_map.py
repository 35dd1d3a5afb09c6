"""One detectability map for every ring model: the smallest detectable crack depth against
how the ring is mounted (SI).

Each ring model says how its mounting is scaled and runs its own detection rule at each
point (:class:`Mounting`): the rigid ring (9 + 3N) sweeps its torsional and radial
mounting stiffness in series with the FE ring body (:mod:`.detectability`, Monte Carlo POD
per point, the stiffness carrying the signal per mode), the elastic ring scales the
Winkler foundation on its support arcs (:mod:`.elastic_map`, reduced rings per scale, the
family POD and the followed modes alone).  Both answer with a :class:`MountingMap`: per
swept mounting a :class:`MountingPanel` of axis values, the depth per point and mode, and
the line over all modes; the model's own result stays in ``detail`` (its ``rows()`` are the
CSV/JSON rows).  One report section writer (``hubvib.reports.mounting_map_sections``) and
one figure (:func:`.plots.map_figure`) draw either.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

__all__ = ["MountingPanel", "MountingMap", "Mounting", "RigidMounting", "ElasticMounting",
           "as_mounting_map", "rigid_mounting_map", "elastic_mounting_map"]

RIGID, ELASTIC = "rigid", "elastic"


@dataclass(frozen=True, eq=False)
class MountingPanel:
    """One swept mounting.

    Attributes
    ----------
    axis_name : str
        What is swept (``c_ru_mount``, ``foundation scale s``).
    axis_unit : str
        Its unit (``N/m``, ``-``).
    axis_values : ndarray (P,)
        The swept values, ascending; ``inf`` (last): the stiff limit (the elastic ring
        clamped on its arcs).
    held : str
        What is held meanwhile, in words (``c_r_mount 1e+09 N/m``; empty: nothing).
    depth : ndarray (P, M)
        Smallest detectable depth of each mode (column) alone [m] (NaN: none of the sweep).
    any_mode : ndarray (P,)
        Smallest detectable depth of the line over all modes [m] (NaN: none).
    mode_names : tuple of str
        One per column of ``depth``.
    carried_by : ndarray (P, M) of str or None
        The stiffness whose change carries each mode's signal (``c_ru``, ``c_r``, ``c_rp``,
        ``none``): the rigid ring's; None for a model that does not split it.
    """

    axis_name: str
    axis_unit: str
    axis_values: np.ndarray
    held: str
    depth: np.ndarray
    any_mode: np.ndarray
    mode_names: tuple
    carried_by: np.ndarray | None = None

    @property
    def detectable(self) -> np.ndarray:
        """(P,) bool: some crack of the sweep is detectable at the point."""
        return np.isfinite(self.any_mode)


@dataclass(frozen=True, eq=False)
class MountingMap:
    """A ring model's smallest detectable depth against its mounting.

    Attributes
    ----------
    ring : str
        ``"rigid"`` (9 + 3N) or ``"elastic"`` (FE ring coupled to the lumped bodies).
    panels : tuple of MountingPanel
        One per swept mounting.
    depths : tuple of float
        The sweep's depths [m], the first 0 (empty when the model did not give them).
    record_length : float
        [s] (NaN when the model did not give it).
    line_label : str
        What ``any_mode`` is: ``any mode`` (the smallest over the modes alone) or ``family
        (...)`` (the watched modes' family POD).
    detail : object
        The model's own map (``detectability.DetectabilityMap`` or
        ``elastic_map.ElasticMap``).
    """

    ring: str
    panels: tuple
    depths: tuple
    record_length: float
    line_label: str
    detail: object

    @property
    def shallowest(self) -> float | None:
        """The sweep's shallowest crack [m] (None: not known)."""
        cracked = [d for d in self.depths if d > 0]
        return min(cracked) if cracked else None

    @property
    def deepest(self) -> float | None:
        return max(self.depths) if self.depths else None

    def rows(self) -> list[dict]:
        """The model's rows (JSON/CSV-ready): ``detail.rows()``."""
        return self.detail.rows()


@runtime_checkable
class Mounting(Protocol):
    """A ring model that says how its mounting is scaled: ``axes()`` names what it sweeps,
    ``mounting_map(options, timing, workers)`` runs its detection rule at every point."""

    ring: str

    def axes(self) -> tuple: ...

    def mounting_map(self, options, timing, workers: int = 1) -> MountingMap: ...


@dataclass(frozen=True, eq=False)
class RigidMounting:
    """The rigid ring's mounting: ``c_ru_mount`` and ``c_r_mount`` [N/m] in series with the
    FE ring body, each swept log-spaced over ``options.mount_min .. mount_max`` with the
    other held (``model``: the ``CrackModel``)."""

    model: object
    ring: str = RIGID

    def axes(self) -> tuple:
        from .detectability import SWEPT

        return tuple((name, "N/m") for name in SWEPT)

    def mounting_map(self, options, timing, workers: int = 1) -> MountingMap:
        from .detectability import detectability_map

        return rigid_mounting_map(detectability_map(self.model, options, timing, workers),
                                  self.model.depths, options.record_length)


@dataclass(frozen=True, eq=False)
class ElasticMounting:
    """The elastic ring's mounting: its support arcs' foundation ``(k_n, k_t)`` scaled by
    ``s`` together (``scales``, holding 1), arguments as :func:`.elastic_map.elastic_map`."""

    design: object
    depths: tuple
    crack_of: object
    scene: object
    pod: object = None
    k_rest: float | None = None
    scales: tuple | None = None
    rings: list | None = None
    clamped: bool = False
    ring: str = ELASTIC

    def axes(self) -> tuple:
        return (("foundation scale s", "-"),)

    def mounting_map(self, options, timing=None, workers: int = 1) -> MountingMap:
        from .elastic_map import SCALES, elastic_map
        from .pod import family_pod

        return elastic_mounting_map(elastic_map(
            self.design, self.depths, self.crack_of, self.scene, options,
            scales=SCALES if self.scales is None else self.scales,
            pod=family_pod if self.pod is None else self.pod, k_rest=self.k_rest,
            rings=self.rings, clamped=self.clamped))


def _held(name: str, value: float) -> str:
    return f"{name} {'rigid' if math.isinf(value) else f'{value:.3g} N/m'}"


def rigid_mounting_map(dmap, depths=(), record_length: float = math.nan) -> MountingMap:
    """The rigid ring's ``DetectabilityMap`` (or an object with its fields: ``mounts``,
    ``depth``, ``carried_by``, ``fixed``, ``smallest``) as a :class:`MountingMap`;
    ``depths`` [m] default the map's own."""
    from .mode_names import rigid_label

    if len(depths) == 0:
        depths = getattr(dmap, "depths", ())
    depths = tuple(float(d) for d in depths)
    kind = getattr(dmap, "kind", None)
    frequency = getattr(dmap, "frequency_hz", None)
    panels = []
    for swept in ("c_ru_mount", "c_r_mount"):
        other = "c_r_mount" if swept == "c_ru_mount" else "c_ru_mount"
        depth = np.asarray(dmap.depth[swept], dtype=float)
        names = (tuple(rigid_label(i, kind[i], frequency[swept][0, i])
                       for i in range(depth.shape[1]))
                 if kind is not None and frequency is not None else
                 tuple(f"rigid {i + 1}" for i in range(depth.shape[1])))
        panels.append(MountingPanel(swept, "N/m", np.asarray(dmap.mounts, dtype=float),
                                    _held(other, dmap.fixed[swept]), depth,
                                    np.asarray(dmap.smallest(swept), dtype=float), names,
                                    np.asarray(dmap.carried_by[swept])))
    return MountingMap(RIGID, tuple(panels), depths, float(record_length), "any mode", dmap)


def elastic_mounting_map(emap) -> MountingMap:
    """The elastic ring's ``ElasticMap`` as a :class:`MountingMap`: one panel over the
    foundation scale, the followed modes of s = 1 as columns, the family POD's depth as
    the line over all modes."""
    ref = emap.reference
    names = tuple(f"elastic {emap.modes_hz[ref, j]:.0f} Hz at s = 1"
                  for j in range(emap.modes_hz.shape[1]))
    held = (f"k_n {emap.foundation[0]:.3g}, k_t {emap.foundation[1]:.3g} N/m^2 at s = 1")
    panel = MountingPanel("foundation scale s", "-", np.asarray(emap.scales, dtype=float),
                          held, np.asarray(emap.mode_depth, dtype=float),
                          np.asarray(emap.family_depth, dtype=float), names)
    return MountingMap(ELASTIC, (panel,), tuple(emap.depths), float(emap.record_length),
                       "family (watched anew per scale)", emap)


def as_mounting_map(value, depths=(), record_length: float = math.nan) -> MountingMap:
    """``value`` as a :class:`MountingMap`: itself, an ``ElasticMap`` or a rigid
    ``DetectabilityMap`` (``depths``, ``record_length`` for the rigid one)."""
    if isinstance(value, MountingMap):
        return value
    if hasattr(value, "mounts"):
        return rigid_mounting_map(value, depths, record_length)
    return elastic_mounting_map(value)
