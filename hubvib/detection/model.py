"""The crack as the lumped model sees it: ring support and cracked mesh per depth (SI).

Built from the FE rows of a crack sweep (``hubvib.studies.crack_sweep.run_fe_cases``)
or from synthetic rows in tests.  ``c_ru`` and ``c_r`` of the lumped model
follow :func:`hubvib.detection.series.ring_support`; planet 1's ring mesh
keeps the FE ratio of the cracked tooth's ``c_rp`` (cracked / intact, the same
tooth pair: a physical ratio) while that tooth is in mesh.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from hubvib.lumped import PlanetaryParameters

from .series import SERIES, identify_mount, ring_support


@dataclass(frozen=True)
class CrackModel:
    """Stiffnesses of the cracked ring per depth and how they enter the lumped model.

    Attributes
    ----------
    params : PlanetaryParameters
        The reducer, intact (its ``c_ru``, ``c_r`` are the preset's totals).
    depths : tuple of float
        Crack depths [m], the first 0 (intact).
    apply : str
        ``"series"``, ``"ratio"`` or ``"direct"`` (see :mod:`hubvib.detection.series`).
    c_ru_body, c_ru_body_error, c_r_body, c_r_body_error : tuple of float
        FE ring body per depth and its error estimate [N/m].
    c_rp_ratio, c_rp_ratio_error, c_rp_min_ratio : tuple of float
        Planet 1's ring mesh while the cracked tooth is engaged: mean ratio cracked /
        intact, its error estimate and the ratio of the minima [-].
    c_ru_mount, c_r_mount : float or None
        Mounting in series with the body [N/m] (``"series"`` only; given or identified).
    method : str
        Eigensolver of single-point solves.
    """

    params: PlanetaryParameters
    depths: tuple[float, ...]
    apply: str
    c_ru_body: tuple[float, ...]
    c_ru_body_error: tuple[float, ...]
    c_r_body: tuple[float, ...]
    c_r_body_error: tuple[float, ...]
    c_rp_ratio: tuple[float, ...]
    c_rp_ratio_error: tuple[float, ...]
    c_rp_min_ratio: tuple[float, ...]
    c_ru_mount: float | None = None
    c_r_mount: float | None = None
    method: str = "jacobi"

    @classmethod
    def from_fe(cls, params: PlanetaryParameters, sweep, fe: list[dict],
                method: str = "jacobi") -> "CrackModel":
        """From a CrackSweep and its FE rows (keys as written by ``crack_sweep.fe_case``)."""
        def column(key):
            return tuple(float(row[key]) for row in fe)

        model = cls(params, tuple(float(d) for d in sweep.depths), sweep.apply,
                    column("c_ru_N_m"), column("c_ru_error_N_m"), column("c_r_N_m"),
                    column("c_r_error_N_m"), column("c_rp_engaged_ratio"),
                    column("c_rp_engaged_ratio_error"), column("c_rp_engaged_min_ratio"),
                    method=method)
        if sweep.apply != SERIES:
            return model
        return model.with_mounts(sweep.c_ru_mount, sweep.c_r_mount)

    def with_mounts(self, c_ru_mount: float | None = None,
                    c_r_mount: float | None = None) -> "CrackModel":
        """Series composition with these mountings [N/m]; ``None`` identifies the mounting
        so that the intact total equals the preset's ``c_ru`` / ``c_r``."""
        if c_ru_mount is None:
            c_ru_mount = identify_mount(self.params.c_ru, self.c_ru_body[0], "c_ru")
        if c_r_mount is None:
            c_r_mount = identify_mount(self.params.c_r, self.c_r_body[0], "c_r")
        return replace(self, apply=SERIES, c_ru_mount=float(c_ru_mount),
                       c_r_mount=float(c_r_mount))

    @property
    def c_ru(self) -> np.ndarray:
        """Lumped ``c_ru`` per depth [N/m]."""
        return ring_support(self.apply, np.array(self.c_ru_body), self.c_ru_body[0],
                            self.params.c_ru, self.c_ru_mount)

    @property
    def c_r(self) -> np.ndarray:
        """Lumped ``c_r`` per depth [N/m]."""
        return ring_support(self.apply, np.array(self.c_r_body), self.c_r_body[0],
                            self.params.c_r, self.c_r_mount)

    def parameters(self, k: int, engaged: bool = True) -> PlanetaryParameters:
        """Lumped parameters at depth index ``k``; ``engaged``: planet 1 meshes with the
        cracked tooth."""
        factor = self.c_rp_ratio[k] if engaged else 1.0
        others = (1.0,) * (self.params.n_planets - 1)
        return self.params.replace(c_ru=float(self.c_ru[k]), c_r=float(self.c_r[k]),
                                   c_rp_factors=(float(factor),) + others)

    def at_depths(self, depths) -> "CrackModel":
        """The same model at other depths [m], the first 0, the rest in ``[0, deepest]``;
        every FE quantity interpolated linearly in depth."""
        depths = np.asarray(depths, dtype=float)
        known = np.array(self.depths)
        if depths[0] != 0 or depths.min() < 0 or depths.max() > known[-1] * (1 + 1e-12):
            raise ValueError(f"depths {depths[0]:.4g}..{depths.max():.4g} m: they must start "
                             f"at 0 and stay within the sweep 0..{known[-1]:.4g} m")

        def interpolated(values):
            return tuple(float(v) for v in np.interp(depths, known, values))

        return replace(self, depths=tuple(float(d) for d in depths), **{
            name: interpolated(getattr(self, name)) for name in (
                "c_ru_body", "c_ru_body_error", "c_r_body", "c_r_body_error", "c_rp_ratio",
                "c_rp_ratio_error", "c_rp_min_ratio")})
