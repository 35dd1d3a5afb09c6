"""Results cross the stages typed (fem.estimate's frozen dataclasses, hubvib.cases' PlaneCase
and SolidCase); the dict form with unit keys exists only at the cache / JSON boundary, and the
rows each study writes are the typed values, exactly."""
from __future__ import annotations

import math

import pytest

from hubvib.design import preset_design
from hubvib.reducer import lumped_preset
from hubvib.detection.model import CrackModel
from hubvib.studies.crack_growth import CrackGrowthResult, solid_rows
from hubvib.cases.results import PlaneCase
from hubvib.cases.sweep import CrackSweep
from hubvib.studies.stiffness import _ring_rows
from tests.helpers.typed_cases import plane_case, solid_case


def test_crack_growth_grid_reads_the_typed_cases():
    sweep = CrackSweep((0.0, 0.003), model="solid", half_lengths=(0.004,),
                       design=preset_design("raba118"))
    plane = [plane_case(0.0, 1e9, 1.0), plane_case(0.003, 0.95e9, 0.9)]
    solid = [solid_case(0.0, 0.0, 1e9), solid_case(0.003, 0.004, 0.99e9)]
    result = CrackGrowthResult(None, solid_rows(sweep, solid, plane), plane, {}, 0)
    grid = result.grid_rows()
    row = grid[1]
    typed = solid[1]
    assert (row["depth_mm"], row["half_length_mm"]) == (3.0, 4.0)
    assert row["c_ru_N_m"] == typed.estimate.c_ru
    assert row["c_r_error_N_m"] == typed.estimate.c_r_error
    assert row["min_sicn"] == 0.3 and row["poor_cells"] == 2 and row["dofs"] == 5000
    assert row["fe_seconds"] == 4.0, "the whole case's wall time, not the estimate's"
    # by hand: the plane through case against the plane intact case
    assert row["plane_through_c_ru_change_percent"] == pytest.approx(-5.0, rel=1e-12)
    assert row["plane_through_c_rp_ratio"] == 0.9
    assert row["c_ru_change_percent"] == pytest.approx(-1.0, rel=1e-12)


def test_solid_row_read_as_a_plane_case():
    """A half-length's study reads each solid row as a plane case: the solid ring's
    estimate with the c_rp carried over and the whole case's wall time."""
    sweep = CrackSweep((0.0, 0.003), model="solid", half_lengths=(0.004,),
                       design=preset_design("raba118"))
    plane = [plane_case(0.0, 1e9, 1.0), plane_case(0.003, 0.95e9, 0.9)]
    solid = [solid_case(0.0, 0.0, 1e9), solid_case(0.003, 0.004, 0.99e9, c_r_root_land=3e9)]
    row = solid_rows(sweep, solid, plane)[1]
    case = row.plane_case()
    assert (case.depth, case.seconds_total, case.estimate.seconds_total) == (0.003, 4.0, 4.0)
    assert case.estimate.c_ru == 0.99e9 and case.estimate.c_r_error == solid[1].estimate.c_r_error
    assert case.estimate.c_r_root_land == 3e9 and case.estimate.dofs == 5000
    assert case.estimate.c_rp_engaged_ratio == row.sliced.mean < 1
    assert case.estimate.c_rp_engaged_intact_window == plane[0].estimate.c_rp_engaged_intact_window


def test_crack_model_from_typed_cases_equals_from_their_dict_form():
    cases = [plane_case(0.0, 1e9, 1.0), plane_case(0.003, 0.95e9, 0.9)]
    sweep = CrackSweep((0.0, 0.003), apply="direct")
    typed = CrackModel.from_fe(lumped_preset("raba118"), sweep, [c.estimate for c in cases])
    from_dicts = CrackModel.from_fe(lumped_preset("raba118"), sweep, [c.to_dict() for c in cases])
    assert typed == from_dicts
    assert typed.c_ru_body == (1e9, 0.95e9) and typed.c_rp_fe == (1.5e9, 1.5e9)
    assert typed.c_rp_ratio == (1.0, 0.9) and typed.c_r_body_error == (0.02e9, 0.019e9)


def test_plane_case_round_trip_and_stiffness_rows():
    case = plane_case(0.003, 0.95e9, 0.9)
    # the dict form is a fixed point; it holds one seconds_total (the whole case's wall
    # time, which the estimate's own fine+coarse time gives way to: one JSON key)
    back = PlaneCase.from_dict(case.to_dict())
    assert back.to_dict() == case.to_dict() and back.estimate.c_ru == case.estimate.c_ru
    assert back.seconds_total == case.seconds_total == 0.4
    assert case.to_dict()["c_ru_N_m"] == 0.95e9, "JSON keys keep their units"
    ring = solid_case(0.0, 0.0, 1e9).estimate
    rows = _ring_rows(ring, " 3D")
    assert rows["c_ru 3D"]["value_N_m"] == ring.to_dict()["c_ru_N_m"] == 1e9
    assert rows["c_r 3D"]["error_N_m"] == ring.c_r_error
    assert rows["c_ru 3D"]["min_N_m"] == ring.c_ru_min and rows["c_ru 3D"]["solver"] == "pardiso"
    assert math.isfinite(rows["c_ru 3D"]["seconds_total"])
