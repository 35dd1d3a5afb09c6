"""Classes and multiplicities of coupled modes follow one stated rule
(``hubvib.elastic.content``): a pair by the planets' cyclic symmetry is found by shape
(its turned shapes lie in the pair's span), not by a frequency gap; the class is 'ring'
where the ring holds the largest kinetic-energy share, else the symmetry type.

Checked against Lin & Parker (J. Sound Vib. 1999): for N equally spaced planets the
rigid-ring model has rotational modes of multiplicity 1, translational modes of
multiplicity 2 and planet modes of multiplicity N - 3 (central members at rest)."""
from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from hubvib.elastic.content import (BODIES, CLASS_SHARE, pair_multiplicities,
                                    symmetry_pairs)
from hubvib.lumped import natural_modes
from hubvib.lumped.network import dof_names
from hubvib.lumped.parameters import equally_spaced_angles

MY5 = Path(__file__).parent / "designs" / "my5.toml"
LIN_PARKER = "Lin & Parker (J. Sound Vib. 1999)"


def _my5():
    from hubvib.reducer import load_design

    return load_design(MY5)


def _rigid_ring_as_coupled(spectrum, probe_points: int = 32):
    """The 9 + 3N model's modes in the coupled model's layout: the lumped bodies without
    the ring's x_r, y_r, u_r, and the rigid ring as a mid-rim probe (radial, tangential
    displacement at ``probe_points`` angles) with its kinetic energy."""
    names = dof_names(spectrum.params.n_planets)
    ring = [names.index(n) for n in ("x_r", "y_r", "u_r")]
    keep = [i for i in range(len(names)) if i not in ring]
    x, y, u = spectrum.shapes[ring]
    phi = 2 * np.pi * np.arange(probe_points) / probe_points
    probe = np.vstack([np.outer(np.cos(phi), x) + np.outer(np.sin(phi), y),
                       -np.outer(np.sin(phi), x) + np.outer(np.cos(phi), y)
                       + np.outer(np.ones_like(phi), u)])
    kinetic = (spectrum.mass[ring][:, None] * spectrum.shapes[ring] ** 2).sum(axis=0)
    return SimpleNamespace(omega=spectrum.omega, lumped=spectrum.shapes[keep],
                           lumped_names=tuple(names[i] for i in keep),
                           lumped_mass=spectrum.mass[keep], ring_kinetic=kinetic, probe=probe)


@pytest.mark.parametrize("planets", [3, 4, 5])
def test_pairs_by_shape_are_lin_parkers_multiplicities(planets):
    """The rigid-ring model of the five-planet design with N = 3, 4, 5 equally spaced
    planets (exact cyclic symmetry, exactly repeated frequencies): the pairs found by
    shape are the solver's repeated frequencies (relative gap 1e-9), and their
    multiplicities are Lin & Parker's (rotational 1, translational 2, planet N - 3)."""
    from hubvib.reducer.stages import lumped_parameters
    from validation.theory import expected_pattern

    params = lumped_parameters(_my5())
    params = params.replace(theta=equally_spaced_angles(planets, 0.3))
    spectrum = natural_modes(params)
    modes = _rigid_ring_as_coupled(spectrum)
    partner = symmetry_pairs(modes, params.theta)
    found = pair_multiplicities(partner)
    assert found == spectrum.multiplicity, (
        f"N = {planets}: multiplicities by shape {found} vs the repeated frequencies "
        f"{spectrum.multiplicity} (Lin & Parker's types {spectrum.kind})")
    for a, b in enumerate(partner):
        if b is not None:
            gap = abs(spectrum.omega[a] - spectrum.omega[b]) / spectrum.omega[a]
            assert gap < 1e-9, f"mode {a + 1} paired with {b + 1}: relative gap {gap:.2e}"
    pattern = {}
    for g, kind, m in zip(spectrum.group, spectrum.kind, found):
        pattern[g] = (kind, m)
    counts = {}
    for value in pattern.values():
        counts[value] = counts.get(value, 0) + 1
    assert counts == expected_pattern(planets), (
        f"N = {planets}: (type, multiplicity) counts {counts} vs {LIN_PARKER} "
        f"{expected_pattern(planets)}")


def test_pairs_need_equal_spacing():
    """Unequally spaced planets have no cyclic symmetry: every mode counts 1."""
    from hubvib.reducer.stages import lumped_parameters

    params = lumped_parameters(_my5())
    modes = _rigid_ring_as_coupled(natural_modes(params))
    assert set(pair_multiplicities(symmetry_pairs(modes, params.theta, False))) == {1}


# ------------------------------------------------------------- the elastic ring (FE)

def _elastic(design):
    from dataclasses import replace

    from hubvib.elastic.model import elastic_ring, elastic_spectrum
    from hubvib.elastic.options import ElasticScene

    options = replace(ElasticScene().options, band_hz=10e3)
    return elastic_spectrum(elastic_ring(design, options=options, carrier_teeth=(0,)))


def _check_rule(spectrum, planets: int, name: str) -> None:
    """The module's rule, mode by mode, and what the theory says of it."""
    f = spectrum.frequency_hz
    top = f.size - 1
    for i, c in enumerate(spectrum.content):
        shares = dict(zip(BODIES, c.body_shares))
        assert abs(sum(c.body_shares) - 1) < 1e-9, (name, i, c.body_shares)
        if c.ring_share >= 0.5:
            assert c.kind == "ring", (
                f"{name} mode {i + 1} ({f[i]:.1f} Hz): {c.ring_share:.2f} of its kinetic "
                f"energy in the ring, classed {c.kind!r}")
        if c.kind == "planet":
            central = shares["sun"] + shares["carrier"]
            assert central < 0.01, (
                f"{name} mode {i + 1}: a planet mode with {central:.3f} of its energy in the "
                f"sun and carrier; {LIN_PARKER}: central members at rest")
        clean = c.harmonic_share >= CLASS_SHARE
        partner = spectrum.pair_partner[i]
        if clean and c.harmonic_index in (0, planets / 2):
            assert spectrum.multiplicity[i] == 1, (
                f"{name} mode {i + 1} ({f[i]:.1f} Hz, p = {c.harmonic_index}): single by "
                f"{LIN_PARKER} (rotational) / Wu & Parker 2008 (p = N/2)")
        elif clean and i != top:
            assert spectrum.multiplicity[i] == 2 and partner is not None, (
                f"{name} mode {i + 1} ({f[i]:.1f} Hz, p = {c.harmonic_index}, {c.kind}): a "
                f"pair by {LIN_PARKER} (translational 2, planet N - 3 = {planets - 3})")
        if partner is not None:
            assert spectrum.pair_partner[partner] == i
            assert spectrum.content[partner].harmonic_index == c.harmonic_index
            assert spectrum.content[partner].kind == c.kind, (name, i, partner)
    rows = spectrum.rows()
    for row in rows:
        if row["pair_mode"] is not None:
            other = rows[row["pair_mode"] - 1]
            assert row["pair_split_hz"] == pytest.approx(
                abs(other["frequency_hz"] - row["frequency_hz"]), abs=1e-9)


@pytest.mark.slow
def test_raba_classes_and_pairs():
    """Raba 118/76 (N = 3, 64 teeth: the tooth count breaks the symmetry a little): the
    302.3 / 303.2 Hz translational pair is one pair with its split printed, the 884 / 912 Hz
    pair too, though 28 Hz apart; no planet modes (N - 3 = 0)."""
    from hubvib.design.presets import preset_design

    spectrum = _elastic(preset_design("raba118"))
    _check_rule(spectrum, 3, "raba118")
    f = spectrum.frequency_hz
    assert spectrum.pair_partner[2] == 3 and spectrum.multiplicity[2:4] == (2, 2), \
        f"302/303 Hz ({f[2]:.1f}, {f[3]:.1f}): a translational pair ({LIN_PARKER})"
    assert 0.5 < spectrum.rows()[2]["pair_split_hz"] < 2.0
    near_900 = [i for i in range(f.size) if 850 < f[i] < 950]
    assert len(near_900) == 2 and spectrum.pair_partner[near_900[0]] == near_900[1]
    assert "planet" not in {c.kind for c in spectrum.content}, f"N - 3 = 0 ({LIN_PARKER})"


@pytest.mark.slow
def test_five_planet_design_classes_and_pairs():
    """The five-planet design (six support pads and 64 teeth: the symmetry holds only
    roughly): planet modes appear, in pairs (N - 3 = 2), with the sun and carrier at rest;
    a mode with most of its energy in the ring says 'ring'."""
    spectrum = _elastic(_my5())
    _check_rule(spectrum, 5, "my5")
    kinds = [c.kind for c in spectrum.content]
    planet = [i for i, k in enumerate(kinds) if k == "planet"]
    assert planet and all(spectrum.multiplicity[i] == 2 for i in planet), (
        f"planet modes {[i + 1 for i in planet]}: multiplicity N - 3 = 2 ({LIN_PARKER})")
    assert "ring" in kinds
