"""The rigid-ring model's computed validity band, the reduced ring over foundation scales,
and the elastic ring's detectability against its mounting."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from hubvib.detection.elastic_map import SCALES, ElasticMap, elastic_map
from hubvib.reports.elastic_map_sections import map_section, map_table
from hubvib.elastic.mounting_basis import _arcs
from hubvib.elastic.options import ElasticScene, parse_elastic_table
from hubvib.foundation.errors import SceneError

#: the report's watched rigid-ring modes of the Raba preset end at mode 18, 6900.9 Hz
RABA_WATCHED_TOP_HZ = 6900.9


def test_support_arcs_are_told_apart_across_pi():
    """Six arcs of 20 deg, one across +-180 deg: six groups, each whole."""
    centres = np.radians(np.arange(0, 360, 60) + 180.0)
    theta = np.concatenate([c + np.radians(np.linspace(-10, 10, 9)) for c in centres])
    theta = np.angle(np.exp(1j * theta))
    groups = _arcs(theta)
    assert len(groups) == 6
    assert sorted(g.size for g in groups) == [9] * 6
    for g in groups:
        spread = np.ptp(np.unwrap(np.sort(np.angle(np.exp(1j * (theta[g] - theta[g][0]))))))
        assert spread < np.radians(21), np.degrees(spread)


def test_map_key_parses_and_needs_a_foundation():
    assert parse_elastic_table({"map": True}).map
    assert not parse_elastic_table({}).map
    with pytest.raises(SceneError, match="mounting"):
        parse_elastic_table({"map": True, "mounting": "clamped"})
    with pytest.raises(SceneError, match="map"):
        parse_elastic_table({"map": 3})


def test_map_refuses_scales_without_the_reference():
    with pytest.raises(ValueError, match="holding 1"):
        elastic_map(None, (0.0, 0.003), None, ElasticScene(), None, scales=(0.5, 2.0))


def _synthetic_map() -> ElasticMap:
    scales = np.array([0.1, 1.0, 10.0])
    return ElasticMap(
        scales=scales, foundation=(7e8, 1.8e6), depths=(0.0, 0.003, 0.006),
        family_depth=np.array([0.003, 0.003, np.nan]),
        family_pod=np.array([[0.01, 0.95, 1.0], [0.01, 0.92, 1.0], [0.01, 0.2, 0.5]]),
        watched=((4668.0,), (4716.0,), (5056.0,)),
        modes_hz=np.array([[4668.0, 2682.0], [4716.0, 2831.0], [np.nan, 4167.0]]),
        mode_depth=np.array([[0.003, 0.006], [0.003, 0.003], [np.nan, np.nan]]),
        mode_drop_hz=np.array([[30.0, 5.0], [28.0, 20.0], [np.nan, 1.0]]),
        lowest_ring_mode_hz=np.array([1005.0, 1233.0, 2370.0]),
        lowest_ring_mode_n=(2, 2, 2), record_length=10.0, detection_probability=0.9,
        pod_name="family_pod")


def test_map_lines_name_every_scale_and_the_gaps():
    emap = _synthetic_map()
    table = map_table(emap)
    assert len(table) == 2 + emap.scales.size
    assert table[0].count("|") == table[1].count("|") == table[2].count("|")
    assert "(lost)" in table[-1] and "| none |" in table[-1]
    text = "\n".join(map_section(emap))
    assert "between 3 and 3 mm" in text or "3 mm" in text
    assert "none of the sweep at s = 10" in text
    rows = emap.rows()
    assert rows[2]["smallest_detectable_depth_mm"] is None
    assert rows[0]["modes"][1]["smallest_detectable_depth_mm"] == pytest.approx(6.0)
    from tests.helpers.null_reasons import unexplained_nulls

    assert unexplained_nulls({"rows": rows}) == [], "every null of the map says why"
    assert "reaches the detection probability" in rows[2]["smallest_detectable_depth_mm_reason"]


# --------------------------------------------------------------------- on the FE ring

@pytest.fixture(scope="module")
def raba():
    from hubvib.reducer.stages import lumped_parameters, ring_gear
    from hubvib.design.presets import preset_design
    from hubvib.elastic.model import out_of_contact_tooth
    from hubvib.elastic.rest import rest_stiffness

    design = preset_design("raba118")
    scene = ElasticScene(ring="both")
    away = out_of_contact_tooth(ring_gear(design).teeth, design.n_planets)
    return design, scene, lumped_parameters(design), rest_stiffness(design), away


@pytest.fixture(scope="module")
def families(raba):
    from hubvib.elastic.mounting_basis import family_ring
    from hubvib.meshing.crack import Crack

    design, scene, params, _, away = raba
    intact = family_ring(design, None, scene.options, None, (away,), params)
    cracked = family_ring(design, Crack(0, 0.009), scene.options, intact.foundation, (away,),
                          params)
    return intact, cracked


@pytest.mark.slow
def test_reduced_ring_equals_full_rebuilds_at_the_scales_ends(raba, families):
    """One reduced ring per depth for every foundation scale against the coupled model
    rebuilt from the FE ring on the scaled foundation (``elastic_ring``, its own basis):
    every coupled frequency below the band's top to 1e-5 relative and the crack's change
    of each (tracked) mode to 0.05 Hz, at s = 0.1 and 100 (the map's ends) and at 1."""
    from hubvib.detection.elastic_map import _Spectrum, tracked_hz
    from hubvib.elastic.model import elastic_ring, elastic_spectrum
    from hubvib.elastic.mounting_basis import ring_operators_at
    from hubvib.lumped.elastic_ring import coupled_modes
    from hubvib.meshing.crack import Crack

    design, scene, params, k_rest, away = raba
    intact, cracked = families
    band = scene.options.band_hz
    for s in (SCALES[0], 1.0, SCALES[-1]):
        options = replace(scene.options, foundation_k_n=s * intact.foundation[0],
                          foundation_k_t=s * intact.foundation[1])
        full, reduced = [], []
        for crack, family in ((None, intact), (Crack(0, 0.009), cracked)):
            er = elastic_ring(design, crack, False, options, (away,), params, k_rest)
            full.append(_Spectrum(elastic_spectrum(er, away).modes))
            reduced.append(_Spectrum(coupled_modes(params, ring_operators_at(family, s), away,
                                                   k_rest, max_hz=band)))
        for f, r in zip(full, reduced):
            assert f.frequency_hz.size == r.frequency_hz.size, s
            error = np.max(np.abs(r.frequency_hz / f.frequency_hz - 1))
            assert error < 1e-5, (s, error)
        shift_full = tracked_hz(full[0], full[1], intact.ring_mass) - full[0].frequency_hz
        shift_reduced = (tracked_hz(reduced[0], reduced[1], intact.ring_mass)
                         - reduced[0].frequency_hz)
        both = np.isfinite(shift_full) & np.isfinite(shift_reduced)
        assert both.sum() >= 0.9 * both.size, s
        assert np.max(np.abs(shift_full[both] - shift_reduced[both])) < 0.05, s


@pytest.mark.slow
def test_stiffer_foundation_raises_the_ring_modes(families):
    """K(s) = K_0 + s F with F positive semi-definite: every eigenvalue of the ring alone
    is non-decreasing in s (Courant-Fischer); the lowest elastic ring mode rises over the
    map's scales (1233 Hz at s = 1 on the Raba mounting, docs/elastic_ring.md)."""
    import scipy.linalg as sla

    from hubvib.detection.elastic_map import lowest_ring_mode
    from hubvib.elastic.mounting_basis import ring_operators_at

    intact, _ = families
    values = np.array([sla.eigvalsh(ring_operators_at(intact, s).K) for s in SCALES])
    assert np.all(np.diff(values, axis=0) >= -1e-9 * values.max()), "eigenvalue fell with s"
    lowest = np.array([lowest_ring_mode(intact, s)[0] for s in SCALES])
    assert np.all(np.diff(lowest) > 0), lowest
    assert lowest[list(SCALES).index(1.0)] == pytest.approx(1233, rel=0.01)


@pytest.mark.slow
def test_validity_band_below_the_ring_mode_and_above_the_watched_band_when_stiff(raba):
    """Raba on its mounting: the rigid-ring model cannot hold past the lowest elastic ring
    mode (the band's top lies below it). The ring's modulus x1e3 (its modes x ~32, its
    tooth rigid): every rigid-model mode up to the band's 10 kHz has its coupled twin
    within 1 %, so the band's top lies above the report's watched modes (top 6900.9 Hz,
    the rigid-ring limit of docs/elastic_ring.md's check, there to 1e-4 at x1e4)."""
    from hubvib.elastic.validity import validity_band, validity_lines, validity_record

    design, scene, *_ = raba
    nominal = validity_band(design, scene.options)
    assert nominal.band_top_hz < nominal.lowest_ring_mode_hz
    assert nominal.ring_modes and min(m.frequency_hz for m in nominal.ring_modes) \
        >= nominal.band_top_hz
    inside = [p for p in nominal.paired if p.rigid_hz < nominal.band_top_hz]
    assert inside and all(abs(p.relative_difference) <= nominal.rtol for p in inside)
    assert "holds below" in "\n".join(validity_lines(nominal))
    import json
    json.dumps(validity_record(nominal), allow_nan=False)

    stiff = replace(design, material=replace(design.material, E=design.material.E * 1e3))
    band = validity_band(stiff, scene.options)
    assert band.band_top_hz > RABA_WATCHED_TOP_HZ, band.band_top_hz
    compared = [p for p in band.paired if p.rigid_hz < scene.options.band_hz / 1.01]
    assert all(abs(p.relative_difference) < 0.01 for p in compared), [
        (p.rigid_hz, p.relative_difference) for p in compared]


@pytest.mark.slow
def test_map_at_the_reference_scale_is_the_elastic_result(raba, families):
    """At s = 1 the map's rule is ``elastic_result``'s (faces open) on the same rings: the same
    watched modes (frequencies to 0.5 Hz: the map keeps the intact ring's foundation for
    every depth, the detection sizes each depth's own) and the same smallest depth. The
    clamped ring closes the map as its stiff limit: clamping the arcs is the foundation's
    infinite limit, so the ring's lowest mode of its own lies above every finite scale's
    (Courant-Fischer; 8053 Hz clamped on the finer mesh, docs/elastic_ring.md)."""
    from hubvib.detection.elastic_model import elastic_result
    from hubvib.detection.options import DetectionOptions
    from hubvib.meshing.crack import Crack

    design, scene, params, k_rest, away = raba
    intact, cracked = families
    depths = (0.0, 0.009)
    crack_of = lambda d: Crack(0, d)  # noqa: E731
    options = DetectionOptions()
    emap = elastic_map(design, depths, crack_of, scene, options, scales=(0.1, 1.0, 100.0),
                       k_rest=k_rest, rings=[intact, cracked], clamped=True)
    # the map scales the open crack's rings (no contact states per scale): its rule is the
    # detection's with the faces open
    detection = elastic_result(design, depths, crack_of, scene, options, load=None)
    watched = sorted(detection.intact_hz[i] for i in detection.watched)
    assert np.allclose(sorted(emap.watched[1]), watched, atol=0.5), (emap.watched[1], watched)
    first = detection.first_detectable(options.record_length)
    assert (math.isnan(emap.family_depth[1]) and first is None) or \
        emap.family_depth[1] == pytest.approx(first)
    assert np.all(np.isfinite(emap.lowest_ring_mode_hz))
    assert np.isinf(emap.scales[-1]) and emap.reference == 1
    assert emap.lowest_ring_mode_hz[-1] > emap.lowest_ring_mode_hz[-2]
    assert emap.lowest_ring_mode_hz[-1] == pytest.approx(8053, rel=0.01)
    assert "| clamped |" in "\n".join(map_table(emap))
    import json
    assert json.loads(json.dumps(emap.rows(), allow_nan=False))[-1]["clamped"]


@pytest.mark.slow
def test_reduced_ring_equals_full_rebuilds_on_the_thin_rim():
    """hub4 (thin rim, eight support arcs, a foundation six times Raba's): the intact
    coupled frequencies below the band's top of the reduced ring against full rebuilds at
    the map's ends, to 1e-5 relative."""
    from hubvib.reducer.stages import lumped_parameters, ring_gear
    from hubvib.design.presets import preset_design
    from hubvib.elastic.model import elastic_ring, elastic_spectrum, out_of_contact_tooth
    from hubvib.elastic.mounting_basis import family_ring, ring_operators_at
    from hubvib.elastic.rest import rest_stiffness
    from hubvib.lumped.elastic_ring import coupled_modes

    design = preset_design("hub4")
    scene, params, k_rest = ElasticScene(), lumped_parameters(design), rest_stiffness(design)
    away = out_of_contact_tooth(ring_gear(design).teeth, design.n_planets)
    family = family_ring(design, None, scene.options, None, (away,), params)
    for s in (SCALES[0], SCALES[-1]):
        options = replace(scene.options, foundation_k_n=s * family.foundation[0],
                          foundation_k_t=s * family.foundation[1])
        full = elastic_spectrum(elastic_ring(design, None, False, options, (away,), params,
                                             k_rest), away).frequency_hz
        reduced = coupled_modes(params, ring_operators_at(family, s), away, k_rest,
                                max_hz=scene.options.band_hz).frequency_hz
        assert full.size == reduced.size, s
        assert np.max(np.abs(reduced / full - 1)) < 1e-5, s


@pytest.mark.slow
def test_rigid_equivalent_shares_the_static_stiffness_so_low_modes_agree(raba):
    """The comparison model carries the ring's statically condensed contact compliance in
    series with k_rest: its static stiffness is the elastic ring's, so modes far below the
    lowest ring mode differ only by the ring's inertia beyond its rigid motions, of order
    (f / f_ring)^2 times the ring's deformation share. Raba: the modes below a tenth of the
    lowest ring mode agree to 1e-3 (they differ by 1.3 % against ``lumped_equivalent``,
    whose ring-planet spring is k_rest alone). The local compliance is positive (the full
    contact compliance exceeds its rigid-ring part, Rayleigh-Ritz) and, on a clamped ring
    (no foundation sized to the design), scales as 1/E."""
    from hubvib.elastic.model import (elastic_ring, elastic_spectrum, lowest_ring_mode,
                                      lumped_equivalent)
    from hubvib.elastic.validity import local_contact_compliance, rigid_equivalent
    from hubvib.lumped import natural_modes
    from hubvib.lumped.elastic_ring import engagement

    design, scene, *_ = raba
    er = elastic_ring(design, options=scene.options, carrier_teeth=(0,))
    spectrum_hz = np.sort(natural_modes(rigid_equivalent(er, 0)).frequency_hz)
    coupled_hz = elastic_spectrum(er, 0).frequency_hz
    low = spectrum_hz < 0.1 * lowest_ring_mode(er)[0]
    assert low.sum() >= 2
    np.testing.assert_allclose(coupled_hz[:low.sum()], spectrum_hz[low], rtol=1e-3,
                               err_msg="same static stiffness: low modes to 1e-3")
    teeth = engagement(er.params, er.operators, 0).teeth
    local = local_contact_compliance(er, teeth)
    assert np.all(local > 0), local
    c_rp = rigid_equivalent(er, 0).c_rp
    assert c_rp < lumped_equivalent(er, 0).c_rp == pytest.approx(er.k_rest)

    clamped = replace(scene.options, mounting="clamped")
    er1 = elastic_ring(design, options=clamped, carrier_teeth=(0,), k_rest=er.k_rest)
    stiff = replace(design, material=replace(design.material, E=design.material.E * 10))
    er10 = elastic_ring(stiff, options=clamped, carrier_teeth=(0,), k_rest=er.k_rest)
    np.testing.assert_allclose(local_contact_compliance(er10, teeth),
                               local_contact_compliance(er1, teeth) / 10, rtol=1e-9,
                               err_msg="clamped ring, linear elasticity: compliance ~ 1/E")
