"""The synthetic FE rows of the detection tests (``tests/helpers/synthetic_rows.py``) look
like the FE stage's rows."""
import pytest

from tests.helpers.synthetic_rows import synthetic_fe_rows, synthetic_model


def test_synthetic_rows_pass_the_fe_cache_plausibility_check():
    from hubvib.cases.runner import check_case

    for row in synthetic_fe_rows():
        check_case(row["depth_m"])(row)  # raises CacheEntryError when implausible


def test_through_rim_crack_of_the_synthetic_rows_lowers_the_body_to_x0_942():
    model = synthetic_model()
    assert model.c_ru_body[-1] / model.c_ru_body[0] == pytest.approx(0.942), \
        "through-rim crack body x0.942 (the synthetic rows' c_ru_drop 0.058)"
