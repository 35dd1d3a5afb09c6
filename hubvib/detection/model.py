"""The crack as the lumped model sees it: ring support and cracked mesh per depth (SI).

Built from the FE cases of a crack sweep (``hubvib.cases.runner.crack_cases``)
or from synthetic rows in tests.  ``c_ru`` and ``c_r`` of the lumped model
follow :func:`hubvib.detection.series.ring_support`.

Planet 1's ring mesh while the cracked tooth is in mesh: the
crack adds the compliance ``dq = (1/ratio - 1) / c_rp_FE`` [m/N] to the tooth
pair, where ``ratio`` is the FE cracked / intact c_rp over the cracked tooth's contact
window and ``c_rp_FE`` the FE intact mean over the same window (the ratio's
denominator; formerly the mean over the whole mesh cycle, which the window's
exceeds by a factor 1.048 on the Raba stage, so dq was that much too large); in series
with the lumped ``c_rp`` it gives the factor ``1 / (1 + c_rp dq)`` (``C_RP_SERIES``, the primary method).
When the lumped ``c_rp`` equals that window mean this factor equals the FE ratio; the
FE c_rp of design-derived scenes (``with_fe_c_rp``) is the whole-cycle mean, so there
the factor is the ratio's crack effect times about 1 / 1.048 (Raba), and the two
methods differ (``c_rp_differs``).  ``C_RP_RATIO`` multiplies the lumped ``c_rp``
by the ratio itself (formerly: an upper bound of the crack's effect when
the lumped ``c_rp`` is below the FE one, as the paper's 3e8 N/m is).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from hubvib.cases.results import PlaneCase
from hubvib.fem.estimate import CrackCaseEstimate
from hubvib.lumped import PlanetaryParameters

from .series import SERIES, identify_mount, ring_support

#: the crack's extra compliance in series with the lumped c_rp (primary)
C_RP_SERIES = "series"
#: the lumped c_rp times the FE cracked / intact ratio (an upper bound below the FE c_rp)
C_RP_RATIO = "ratio"
C_RP_METHODS = (C_RP_SERIES, C_RP_RATIO)


def series_factor(ratio, c_rp_fe, c_rp_lumped):
    """Factor on the lumped ``c_rp_lumped`` [N/m] from the FE ratio cracked / intact [-]
    and the FE intact ``c_rp_fe`` [N/m]: ``1 / (1 + c_rp_lumped (1/ratio - 1) / c_rp_fe)``,
    the crack's extra compliance in series (equal to ``ratio`` when both c_rp agree)."""
    ratio = np.asarray(ratio, dtype=float)
    # the same as 1 / (1 + c_rp_lumped (1/ratio - 1) / c_rp_fe), written so that equal
    # c_rp give the ratio to the last bit
    rho = np.asarray(c_rp_lumped, dtype=float) / np.asarray(c_rp_fe, dtype=float)
    return ratio / (ratio + rho * (1.0 - ratio))


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
    c_rp_fe, c_rp_fe_min : tuple of float
        FE intact c_rp over the mesh cycle, mean and lowest, per depth [N/m] (empty:
        unknown, only ``C_RP_RATIO`` possible); see ``fem.estimate.CrackCaseEstimate``.
    c_rp_fe_window : tuple of float
        FE intact c_rp over the cracked tooth's contact window, mean per depth [N/m]: the
        denominator of ``c_rp_ratio`` and of the series method's compliance.
    c_rp_method : str
        ``C_RP_SERIES`` or ``C_RP_RATIO``: how the crack enters planet 1's c_rp.
    c_rp_source : str
        ``"given"`` (the lumped c_rp is the scene's / preset's value) or ``"fe"`` (the
        FE intact c_rp, every planet).
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
    c_rp_fe: tuple[float, ...] = ()
    c_rp_fe_min: tuple[float, ...] = ()
    c_rp_fe_window: tuple[float, ...] = ()
    c_rp_method: str = C_RP_SERIES
    c_rp_source: str = "given"

    def __post_init__(self):
        if self.c_rp_method not in C_RP_METHODS:
            raise ValueError(f"c_rp_method = {self.c_rp_method!r}; allowed: "
                             f"{', '.join(C_RP_METHODS)}")
        if self.c_rp_method == C_RP_SERIES and not (
                len(self.c_rp_fe) == len(self.c_rp_fe_window) == len(self.depths)):
            raise ValueError(f"c_rp_method = {C_RP_SERIES!r} needs the FE intact c_rp (mean "
                             f"over the cycle and over the contact window) at every depth: "
                             f"{len(self.c_rp_fe)} and {len(self.c_rp_fe_window)} values for "
                             f"{len(self.depths)} depths")

    @classmethod
    def from_fe(cls, params: PlanetaryParameters, sweep, fe: list,
                method: str = "jacobi", c_rp_given: bool = True) -> "CrackModel":
        """From a CrackSweep and its FE cases: ``cases.results.PlaneCase`` (what
        ``cases.runner.crack_cases`` gives) or ``fem.estimate.CrackCaseEstimate`` objects;
        rows in their dict form (read from a file, written by hand) are read once with
        ``CrackCaseEstimate.from_dict``.

        ``c_rp_given``: the lumped c_rp of ``params`` is a given value (a preset's table,
        a design's ``lumped.c_rp``, a scene override); otherwise every planet's c_rp is
        the FE intact c_rp (``with_fe_c_rp``)."""
        cases = [_estimate(case) for case in fe]

        def column(name):
            return tuple(float(getattr(case, name)) for case in cases)

        model = cls(params, tuple(float(d) for d in sweep.depths), sweep.apply,
                    column("c_ru"), column("c_ru_error"), column("c_r"), column("c_r_error"),
                    column("c_rp_engaged_ratio"), column("c_rp_engaged_ratio_error"),
                    column("c_rp_engaged_min_ratio"), method=method,
                    c_rp_fe=column("c_rp_engaged_intact"),
                    c_rp_fe_min=column("c_rp_engaged_intact_min"),
                    c_rp_fe_window=column("c_rp_engaged_intact_window"))
        if not c_rp_given:
            model = model.with_fe_c_rp()
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

    def with_fe_c_rp(self) -> "CrackModel":
        """Every planet's lumped c_rp set to the FE intact c_rp over the engagement (at
        depth 0) [N/m]: one mesh stiffness for the intact and the cracked tooth."""
        return replace(self, params=self.params.replace(c_rp=float(self.c_rp_fe[0])),
                       c_rp_source="fe")

    def with_c_rp_method(self, c_rp_method: str) -> "CrackModel":
        """The same model with the crack entering c_rp by ``c_rp_method``."""
        return replace(self, c_rp_method=c_rp_method)

    def c_rp_factor(self, k=None, ratio=None, c_rp_lumped=None,
                    minimum: bool = False) -> np.ndarray:
        """Factor on planet 1's lumped c_rp [-] while the cracked tooth is in mesh, at depth
        index ``k`` (an int, one index per sample, or None: every depth).  The series
        method divides the mean ratio's compliance by the FE intact mean over the contact
        window (``c_rp_fe_window``), the ratio of the minima's by the lowest intact value.  ``ratio``
        replaces the FE mean ratio there (or the ratio of the minima with ``minimum``)
        and ``c_rp_lumped`` [N/m] the model's c_rp (e.g. per sample)."""
        at = slice(None) if k is None else k
        if ratio is None:
            ratio = np.asarray(self.c_rp_min_ratio if minimum else self.c_rp_ratio)[at]
        if self.c_rp_method == C_RP_RATIO:
            return np.asarray(ratio, dtype=float)
        fe = np.asarray(self.c_rp_fe_min if minimum else self.c_rp_fe_window)[at]
        return series_factor(ratio, fe, self.params.c_rp if c_rp_lumped is None
                             else c_rp_lumped)

    @property
    def c_rp_differs(self) -> bool:
        """Whether the two methods give different factors: the lumped c_rp is not the FE
        intact mean over the contact window, the series method's denominator (relative
        difference above 1e-9)."""
        return bool(self.c_rp_fe_window
                    and abs(self.params.c_rp / self.c_rp_fe_window[0] - 1) > 1e-9)

    def mesh_stiffness(self) -> dict:
        """The ring-planet mesh stiffness the model uses, as the JSON outputs give it:
        ``c_rp_method``, ``c_rp_source``, ``c_rp_lumped_N_m`` (every planet intact),
        ``c_rp_fe_intact_N_m`` (FE, over the mesh cycle; None unknown),
        ``c_rp_fe_intact_window_N_m`` (FE, over the cracked tooth's contact window)."""
        return {"c_rp_method": self.c_rp_method, "c_rp_source": self.c_rp_source,
                "c_rp_lumped_N_m": float(self.params.c_rp),
                "c_rp_fe_intact_N_m": float(self.c_rp_fe[0]) if self.c_rp_fe else None,
                "c_rp_fe_intact_window_N_m": (float(self.c_rp_fe_window[0])
                                              if self.c_rp_fe_window else None)}

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
        factor = self.c_rp_factor(k) if engaged else 1.0
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

        names = ("c_ru_body", "c_ru_body_error", "c_r_body", "c_r_body_error", "c_rp_ratio",
                 "c_rp_ratio_error", "c_rp_min_ratio", "c_rp_fe", "c_rp_fe_min",
                 "c_rp_fe_window")
        return replace(self, depths=tuple(float(d) for d in depths), **{
            name: interpolated(getattr(self, name)) for name in names
            if len(getattr(self, name)) == len(known)})


def _estimate(case) -> CrackCaseEstimate:
    """The ``CrackCaseEstimate`` of a ``PlaneCase``, an estimate itself, or its dict form."""
    if isinstance(case, PlaneCase):
        return case.estimate
    if isinstance(case, dict):
        return CrackCaseEstimate.from_dict(case)
    return case
