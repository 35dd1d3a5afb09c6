"""Stiff and extreme cases: each eigensolver against the 50-digit reference.

Run by ``hubvib stability``.  Error is the largest relative frequency error
over the elastic modes, ``max |omega - omega_ref| / omega_ref``, and
separately that of the lowest elastic frequency; time is the median of
repeated solves.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from hubvib.lumped.eigensolve import METHODS, IndefiniteStiffnessError, solve_assembled
from hubvib.lumped.network import mass_diagonal
from hubvib.lumped.parameters import PlanetaryParameters, equally_spaced_angles
from hubvib.lumped.printed import printed_stiffness_matrix
from hubvib.lumped.spectrum import natural_modes

from .reference import reference_eigenvalues

TARGET = 1e-6  # relative frequency error the default method must meet on every case


def cases(p: PlanetaryParameters) -> dict[str, PlanetaryParameters]:
    """Named parameter sets, from the paper's (``p``: the Raba 118/76 parameters) to the
    degenerate."""
    stiff_mesh = dict(c_sp=1e14, c_rp=1e14, c_su=1.0, c_cu=1.0, c_ru=1.0)
    return {
        "raba118 (paper)": p,
        "mesh 1e14 / torsion 1 N/m": p.replace(**stiff_mesh),
        "all supports+meshes 1e14 / torsion 1": p.replace(
            **stiff_mesh, c_p=1e14, c_c=1e14, c_r=1e14
        ),
        "stiff + planets 1e-6 kg": p.replace(**stiff_mesh, m_p=0.85e-6, mu_p=0.52e-6),
        "stiff + carrier 1e6 kg": p.replace(**stiff_mesh, m_c=1e6, mu_c=1e6),
        "masses 1e-3 .. 1e6 kg": p.replace(m_s=1e-3, mu_s=1e-3, m_r=1e6, mu_r=1e6),
        "torsion 0 (rigid-body mode)": p.replace(c_su=0.0, c_cu=0.0, c_ru=0.0),
        "torsion 1e-6 N/m (nearly rigid)": p.replace(c_su=1e-6, c_cu=1e-6, c_ru=1e-6),
        "N = 1": p.replace(theta=equally_spaced_angles(1)),
        "N = 2": p.replace(theta=equally_spaced_angles(2)),
        "N = 12": p.replace(theta=equally_spaced_angles(12)),
        "planets 1e-6 rad apart": p.replace(theta=(0.0, 1e-6, 2 * math.pi / 3)),
    }


@dataclass(frozen=True)
class StabilityRow:
    case: str
    method: str
    n_rigid: int
    max_error: float
    lowest_error: float
    lowest_omega: float
    seconds: float
    note: str = ""

    def as_dict(self) -> dict:
        return self.__dict__.copy()


def run(raba: PlanetaryParameters, repeats: int = 20, dps: int = 50,
        on_case=None) -> list[StabilityRow]:
    """Every case made from ``raba`` (the Raba 118/76 parameters; the layers above build
    them, ``hubvib.reducer.lumped_preset("raba118")``) with every method, plus the paper's
    printed (indefinite) matrix.  ``on_case(name)`` is called after each case (progress)."""
    rows = []
    for name, params in cases(raba).items():
        reference = np.sqrt(np.clip(reference_eigenvalues(params, dps), 0.0, None))
        for method in METHODS:
            seconds = _median_time(lambda: natural_modes(params, method), repeats)
            spectrum = natural_modes(params, method)
            rows.append(_compare(name, method, spectrum.omega, spectrum.n_rigid, reference, seconds))
        if on_case is not None:
            on_case(name)
    rows.append(_printed_row(raba))
    return rows


def _compare(name, method, omega, n_rigid, reference, seconds):
    elastic = slice(n_rigid, None)
    error = np.abs(omega[elastic] - reference[elastic]) / reference[elastic]
    rigid_ok = np.all(omega[:n_rigid] == 0.0)
    note = f"{n_rigid} rigid-body mode(s), reported as exactly 0" if n_rigid else ""
    if not rigid_ok:
        note = "rigid-body mode not exactly 0"
    return StabilityRow(
        name, method, n_rigid, float(error.max()), float(error[0]),
        float(reference[n_rigid]), seconds, note,
    )


def _printed_row(params: PlanetaryParameters) -> StabilityRow:
    try:
        solve_assembled(printed_stiffness_matrix(params), mass_diagonal(params))
    except IndefiniteStiffnessError as exc:
        note = f"detected: {exc}"
    else:  # pragma: no cover - would mean the printed matrix became definite
        note = "NOT detected"
    return StabilityRow("paper's printed matrix", "eigh", 0, math.nan, math.nan, math.nan, 0.0, note)


def _median_time(function, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def format_table(rows: list[StabilityRow]) -> str:
    lines = [
        f"{'case':<38} {'method':<7} {'rigid':>5} {'max rel err':>11} {'lowest err':>10} "
        f"{'time [ms]':>9}  note",
    ]
    for r in rows:
        lines.append(
            f"{r.case:<38} {r.method:<7} {r.n_rigid:>5} {r.max_error:>11.2e} "
            f"{r.lowest_error:>10.2e} {1e3 * r.seconds:>9.3f}  {r.note}"
        )
    return "\n".join(lines)
