"""``hubvib stiffness``'s typed case (hubvib.studies.stiffness.StiffnessCase): its JSON rows
are the estimates' own dict forms, and its named values the estimates' fields."""
from hubvib.fem.estimate import MeshEstimate, RingEstimate
from hubvib.reducer.stages import FE_MESH, FE_RING, ISO_MESH, labelled
from hubvib.studies.stiffness import BearingStiffness, StiffnessCase, _ring_rows


def _ring(c_ru: float) -> RingEstimate:
    return RingEstimate(c_ru=c_ru, c_ru_error=1e7, c_ru_min=0.6 * c_ru, c_ru_max=1.4 * c_ru,
                        c_r=3.7e10, c_r_error=2e7, dofs=100, solver="pardiso",
                        seconds_mesh=0.1, seconds_fe=0.2, seconds_total=0.5,
                        definition="rim", c_ru_root_land=1.6e10, c_ru_root_land_error=3e7,
                        c_r_root_land=3.8e10, c_r_root_land_error=1e7)


def _mesh(value: float, cracked: bool) -> MeshEstimate:
    engaged = dict(engaged=0.9 * value, engaged_intact=value, engaged_min=0.7 * value,
                   engaged_intact_min=0.8 * value) if cracked else {}
    return MeshEstimate(value=value, error=1e6, min=0.7 * value, max=1.3 * value,
                        single_pair_max=1.1 * value, contact_ratio=1.4, analytic=0.9 * value,
                        iso_c_gamma=0.8 * value, iso_c_single=0.6 * value, iso_in_range=True,
                        seconds_total=1.0, **engaged, levels=(0.98 * value, 0.99 * value, value),
                        level_ratios=(2.0, 2.0))


def test_rows_are_the_estimates_dict_forms():
    mesh = {"c_sp": _mesh(9.7e8, True), "c_rp": _mesh(1.43e9, True)}
    bearing = BearingStiffness(3.9e9, 3.5e9, 1.5e4, 16, 0.03, "tangent", "secant", 0.0, 1e3)
    for cracked in (False, True):
        case = StiffnessCase(_ring(1.07e10), mesh, {"c_p": bearing}, _ring(1.1e10), cracked)
        rows = case.to_dict()
        assert list(rows) == ["c_ru", "c_r", "c_ru 3D", "c_r 3D", "c_sp", "c_rp", "c_p"]
        assert rows["c_ru"] == _ring_rows(case.ring, "")["c_ru"]
        assert rows["c_rp"] == mesh["c_rp"].to_dict(engaged=cracked)
        assert ("engaged_N_m" in rows["c_rp"]) == cracked, "engaged values in the crack case"
        assert rows["c_p"]["value_N_m"] == bearing.tangent
        named = case.named_values()
        assert named[labelled("c_ru", FE_RING)] == case.ring.c_ru
        assert named[labelled("c_ru", f"{FE_RING}, solid")] == case.ring_solid.c_ru
        assert named[labelled("c_rp", FE_MESH)] == mesh["c_rp"].value
        assert named[labelled("c_sp", ISO_MESH)] == mesh["c_sp"].iso_c_gamma
        assert named[labelled("c_p", "secant")] == bearing.secant


def test_the_mesh_estimate_bar_is_its_three_level_error():
    """The stored levels (0.98, 0.99, 1) x value: differences 1 % and 1 %, order 0 (outside
    0.5..4): the larger difference, 1 % of the value."""
    e = _mesh(1e9, False)
    bar = e.error_of()
    assert bar.rule == "larger_difference"
    assert bar.error == 1e9 - 0.99e9
