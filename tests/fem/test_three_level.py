"""The three-level error bar (fem.three_level) against exact sequences f(h) = L + C h^p."""
import math

import pytest

from hubvib.fem.three_level import ORDER_RANGE, three_level_error


def levels(limit, constant, order, sizes):
    return [limit + constant * h ** order for h in sizes]


@pytest.mark.parametrize("order", [0.5, 1.0, 2.0, 2.86, 4.0])
@pytest.mark.parametrize("constant", [3e-2, -7e-3])
def test_richardson_recovers_the_limit_and_the_order(order, constant):
    """Sizes 4, 2, 1: the exact limit and order to 1e-9, the error |fine - limit|."""
    coarse, medium, fine = levels(1.25, constant, order, (4.0, 2.0, 1.0))
    result = three_level_error(coarse, medium, fine)
    assert result.rule == "richardson"
    assert result.order == pytest.approx(order, rel=1e-9), "observed order vs exact p (1e-9)"
    assert result.estimate == pytest.approx(1.25, rel=1e-9), "Richardson vs exact limit (1e-9)"
    assert result.error == pytest.approx(abs(fine - 1.25), rel=1e-7), "error = |fine - limit|"


def test_uneven_ratios_recover_the_order():
    """The solid levels' tooth sizes 4, 3, 2 mm: ratios 4/3 and 3/2 give p and L exactly."""
    coarse, medium, fine = levels(2.0e10, 5e12, 2.2, (4e-3, 3e-3, 2e-3))
    result = three_level_error(coarse, medium, fine, r_fine=1.5, r_coarse=4 / 3)
    assert result.rule == "richardson"
    assert result.order == pytest.approx(2.2, rel=1e-9), "observed order, uneven ratios (1e-9)"
    assert result.estimate == pytest.approx(2.0e10, rel=1e-12), "limit, uneven ratios"


def test_mixed_signs_take_the_larger_of_the_last_two_differences():
    result = three_level_error(1.0, 3.0, 2.0)
    assert result.rule == "larger_difference"
    assert result.error == 2.0 and result.estimate == 2.0
    assert math.isnan(result.order)


@pytest.mark.parametrize("order", [0.3, 5.0, 6.6])
def test_orders_outside_the_range_take_the_larger_difference(order):
    """An order outside 0.5..4 (a chance cancellation looks like a high order) is no
    Richardson estimate: the larger of |medium - coarse| and |fine - medium|."""
    assert not ORDER_RANGE[0] <= order <= ORDER_RANGE[1]
    coarse, medium, fine = levels(0.88, 1e-4, order, (4.0, 2.0, 1.0))
    result = three_level_error(coarse, medium, fine)
    assert result.rule == "larger_difference"
    assert result.order == pytest.approx(order, rel=1e-9)
    assert result.error == pytest.approx(max(abs(medium - coarse), abs(fine - medium)),
                                         rel=1e-12)
    assert result.estimate == fine


def test_chance_cancellation_is_not_a_small_bar():
    """A fine-medium difference 100 times below the coarse-medium one (order 6.6): the
    bar is the coarse-medium difference, not the Richardson correction."""
    result = three_level_error(0.8829, 0.8830, 0.883001)
    assert result.error == pytest.approx(1e-4, rel=1e-6)


def test_equal_levels_have_no_error():
    result = three_level_error(1.0, 1.0, 1.0)
    assert (result.error, result.estimate) == (0.0, 1.0)


def test_bad_ratio_and_values_are_refused():
    with pytest.raises(ValueError, match="r_fine"):
        three_level_error(1.0, 2.0, 3.0, r_fine=1.0)
    with pytest.raises(ValueError, match="finite"):
        three_level_error(1.0, float("nan"), 3.0)
