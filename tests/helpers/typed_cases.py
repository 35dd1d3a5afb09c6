"""Typed FE crack cases written by hand (no FE stage): a ``PlaneCase`` and a ``SolidCase``
with plausible estimates, any field given by keyword."""
from __future__ import annotations

from dataclasses import replace

from hubvib.cases.results import PlaneCase, SolidCase
from hubvib.fem.estimate import CrackCaseEstimate, RingEstimate


def plane_case(depth: float, c_ru: float, ratio: float, seconds_total: float = 0.4,
               **fields) -> PlaneCase:
    """A plane case at ``depth`` [m] with body stiffness ``c_ru`` [N/m] and c_rp ratio
    ``ratio`` [-]; ``fields`` replace the estimate's (``CrackCaseEstimate``)."""
    estimate = CrackCaseEstimate(
        c_ru=c_ru, c_ru_error=0.01 * c_ru, c_ru_min=0.9 * c_ru, c_ru_max=1.1 * c_ru,
        c_r=2 * c_ru, c_r_error=0.02 * c_ru, c_rp_engaged_ratio=ratio,
        c_rp_engaged_ratio_error=1e-3, c_rp_engaged_min_ratio=ratio - 0.05,
        c_rp_engaged_intact=1.5e9, c_rp_engaged_intact_min=1.2e9,
        c_rp_engaged_intact_window=1.5e9, dofs=1000, solver="splu",
        seconds_mesh=0.1, seconds_fe=0.2, seconds_total=0.3)
    return PlaneCase(replace(estimate, **fields), depth, seconds_total)


def solid_case(depth: float, half: float, c_ru: float, seconds_total: float = 4.0,
               **fields) -> SolidCase:
    """A solid case of depth ``depth`` and half-length ``half`` [m] with body stiffness
    ``c_ru`` [N/m]; ``fields`` replace the estimate's (``RingEstimate``)."""
    estimate = RingEstimate(
        c_ru=c_ru, c_ru_error=0.01 * c_ru, c_ru_min=0.9 * c_ru, c_ru_max=1.1 * c_ru, c_r=2 * c_ru,
        c_r_error=0.02 * c_ru, dofs=5000, solver="pardiso", seconds_mesh=1.0, seconds_fe=2.0,
        seconds_total=3.0, c_ru_coarse=1.01 * c_ru, c_r_coarse=2.02 * c_ru, min_quality=0.3,
        poor_cells=2, c_ru_poor_half=0.999 * c_ru, c_r_poor_half=2 * c_ru)
    return SolidCase(replace(estimate, **fields), depth, half, seconds_total)
