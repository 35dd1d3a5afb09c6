"""What an error line suggests, typed back as printed, is accepted: proposed planet angles,
shifts, bores, sample rates, time steps and depth limits."""
import dataclasses
import math
import re

import pytest

from hubvib.reducer import parse_design
from hubvib.design import DesignError
from hubvib.foundation.bounds import lower_bound, lower_bound_fixed, upper_bound

from tests.helpers.design_demo import demo


def _refusal(table) -> str:
    with pytest.raises(DesignError) as refused:
        parse_design(table)
    return str(refused.value)


def _angles(text: str, marker: str) -> list[float]:
    found = re.search(re.escape(marker) + r"\[([-0-9., ]+)\]", text)
    assert found, f"no angle list after {marker!r} in: {text}"
    return [float(a) for a in found.group(1).split(",")]


def test_proposed_planet_angles_assemble_as_printed():
    text = _refusal(demo(n_planets=4))
    angles = _angles(text, "planet_angles_deg = ")
    assert 91.7647 < angles[1] < 91.7648, text
    design = parse_design(demo(n_planets=4, planet_angles_deg=angles))
    assert not design.equally_spaced and len(design.angles) == 4


def test_angles_proposed_for_a_planet_that_does_not_assemble_assemble_as_printed():
    text = _refusal(demo(planet_angles_deg=[0, 100, 240]))
    angles = _angles(text, "allowed, e.g.: ")
    assert parse_design(demo(planet_angles_deg=angles)).n_planets == 3


def test_angles_typed_to_four_decimals_assemble():
    """The rule's tolerance is a fraction of the angle between assembly positions (well
    below a micrometre of pitch-circle arc here), not of the float's last digits."""
    design = parse_design(demo(n_planets=4, planet_angles_deg=[0, 91.7647, 180, 268.2353]))
    assert len(design.angles) == 4


def test_angles_a_tenth_of_a_degree_off_are_still_refused():
    assert "does not assemble" in _refusal(demo(n_planets=4,
                                                planet_angles_deg=[0, 91.86, 180, 268.2353]))


def test_suggested_ring_shift_gives_equal_centre_distances():
    text = _refusal(demo(**{"ring.shift": 0.5, "planet.shift": 0.25}))
    found = re.search(r"ring\.shift = ([-0-9.]+) gives equal distances", text)
    assert found, text
    parse_design(demo(**{"ring.shift": float(found.group(1)), "planet.shift": 0.25}))


@pytest.mark.parametrize("teeth", [21, 17, 25])
def test_undercut_limit_is_accepted_as_printed(teeth):
    """With 21 teeth the limit is -0.228299: printed to nearest (-0.2283) it undercut."""
    text = _refusal(demo(**{"sun.teeth": teeth, "sun.shift": -0.9}))
    found = re.search(r"design\.sun\.shift = -0\.9 undercuts .*allowed >= ([-0-9.]+)", text)
    assert found, text
    try:
        parse_design(demo(**{"sun.teeth": teeth, "sun.shift": float(found.group(1))}))
    except DesignError as exc:  # other rules may refuse the stage; the undercut rule not
        assert "undercut" not in str(exc), str(exc)


def test_bore_limit_is_accepted_as_printed():
    text = _refusal(demo(**{"sun.bore": 0.2}))
    found = re.search(r"design\.sun\.bore = 0\.2 m; allowed: > 0 and < ([0-9.e-]+) m", text)
    assert found, text
    parse_design(demo(**{"sun.bore": float(found.group(1))}))


@pytest.mark.parametrize("value", [0.228299019161611, 1.23456789e-5, 0.04475, 3.0, 7.4999999e3,
                                   0.1 + 0.2])
def test_directed_rounding_stays_inside_the_range(value):
    assert float(lower_bound(value)) >= value and float(upper_bound(value)) <= value
    assert float(lower_bound(value, 2, strict=True)) > value
    assert float(upper_bound(value, 2, strict=True)) < value
    assert float(lower_bound_fixed(-value, 4)) >= -value
    assert len(upper_bound(value, 4).replace("-", "").replace(".", "").lstrip("0")
               .split("e")[0]) <= 4


def test_exact_bounds_print_as_they_are():
    assert lower_bound(0.04475) == "0.04475" and upper_bound(3.0) == "3"
    assert upper_bound(3.0, strict=True) == "2.99999"


def test_sample_rate_limit_is_accepted_as_printed():
    from hubvib.design import preset_design
    from hubvib.foundation.errors import SceneError
    from hubvib.signal.options import check_sample_rate, parse_signal_table

    options = dataclasses.replace(parse_signal_table({}), sample_rate_hz=100.0)
    with pytest.raises(SceneError) as refused:
        check_sample_rate(options, preset_design("raba118"))
    found = re.search(r"allowed: >= ([0-9.e+]+) Hz", str(refused.value))
    assert found, str(refused.value)
    check_sample_rate(dataclasses.replace(options, sample_rate_hz=float(found.group(1))),
                      preset_design("raba118"))


@pytest.mark.parametrize("integrator", ["central", "newmark"])
def test_time_step_limits_are_accepted_as_printed(integrator):
    from hubvib.signal.options import parse_signal_table
    from hubvib.signal.simulation import steps_per_revolution

    base = parse_signal_table({})
    # both limits round up to 4 digits here (0.011907853 s, 4.1179387e-05 s)
    omega_max, speed, teeth = 2 * math.pi * 7353.0, 4.12227, 64
    options = dataclasses.replace(base, time_step_s=1.0, integrator=integrator)
    for _ in range(2):  # half a mesh period first, then the central scheme's limit
        try:
            steps_per_revolution(omega_max, speed, teeth, options)
            break
        except ValueError as exc:
            found = re.search(r"allowed: <=? ([0-9.e-]+) s", str(exc))
            assert found, str(exc)
            options = dataclasses.replace(options, time_step_s=float(found.group(1)))
    steps_per_revolution(omega_max, speed, teeth, options)
