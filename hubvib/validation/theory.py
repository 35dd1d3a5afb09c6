"""Structural properties the lumped model must obey (Lin & Parker 1999).

For N >= 3 equally spaced planets: 6 rotational modes (single), 6
translational pairs (double), and 3 planet-mode frequencies of multiplicity
N - 3 that do not depend on the central members.  The energy stiffness
matrix is symmetric positive semidefinite.
"""
from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import numpy as np

from hubvib.lumped.network import stiffness_matrix
from hubvib.lumped.parameters import PlanetaryParameters, equally_spaced_angles
from hubvib.lumped.spectrum import natural_modes


@dataclass(frozen=True)
class TheoryCheck:
    name: str
    expected: str
    found: str
    passed: bool

    def as_dict(self) -> dict:
        return self.__dict__.copy()


def multiplicity_pattern(params: PlanetaryParameters) -> dict[tuple[str, int], int]:
    """Count of distinct frequencies per (mode type, multiplicity)."""
    spectrum = natural_modes(params)
    seen = {}
    for g, kind, mult in zip(spectrum.group, spectrum.kind, spectrum.multiplicity):
        seen[g] = (kind, mult)
    return dict(Counter(seen.values()))


def expected_pattern(n_planets: int) -> dict[tuple[str, int], int]:
    pattern = {("rotational", 1): 6, ("translational", 2): 6}
    if n_planets > 3:
        pattern[("planet", n_planets - 3)] = 3
    return pattern


def planet_frequencies(params: PlanetaryParameters) -> np.ndarray:
    spectrum = natural_modes(params)
    return np.unique(np.round(spectrum.omega[np.array(spectrum.kind) == "planet"], 6))


def run(base: PlanetaryParameters, planet_counts=range(3, 13)) -> list[TheoryCheck]:
    checks = []
    for n in planet_counts:
        params = base.replace(theta=equally_spaced_angles(n, 0.3))
        found = multiplicity_pattern(params)
        expected = expected_pattern(n)
        checks.append(TheoryCheck(
            f"multiplicities, N = {n}", _fmt(expected), _fmt(found), bool(found == expected),
        ))
    params = base.replace(theta=equally_spaced_angles(5))
    changed = params.replace(m_s=3 * base.m_s, mu_r=0.1 * base.mu_r, c_ru=1e3, c_r=7e7, c_cu=5e8)
    a, b = planet_frequencies(params), planet_frequencies(changed)
    same = a.size == 3 and b.size == 3 and np.allclose(a, b, rtol=1e-12)
    checks.append(TheoryCheck(
        "planet modes independent of central members (N = 5)", "3 equal frequencies",
        f"{np.round(a, 3).tolist()} vs {np.round(b, 3).tolist()}", bool(same),
    ))
    K = stiffness_matrix(base)
    asym = float(np.abs(K - K.T).max())
    lowest = float(np.linalg.eigvalsh(K).min())
    tol = K.shape[0] * np.finfo(float).eps * np.abs(K).max()
    checks.append(TheoryCheck(
        "energy C symmetric", "max|C - C^T| = 0", f"{asym:.1e}", bool(asym == 0.0)))
    checks.append(TheoryCheck(
        "energy C positive semidefinite", f"min eigenvalue >= -{tol:.1e} N/m",
        f"{lowest:.4e} N/m", bool(lowest >= -tol)))
    return checks


def _fmt(pattern):
    return ", ".join(f"{count} {kind} x{mult}" for (kind, mult), count in sorted(pattern.items()))
