"""Stiff and extreme cases against an independent 50-digit reference.

The reference is built here from the paper's energy by polarisation in mpmath
(tests/helpers/energy_reference.py), sharing no code with the solver under test.
"""
import numpy as np
import pytest

from hubvib import lumped
from tests.helpers.energy_reference import mp_frequencies
from hubvib.reducer import lumped_preset
from hubvib.validation import stability

CASES = stability.cases(lumped_preset("raba118"))


#: the 12-planet case takes seconds in mpmath; the same check on 3..5 planets stays fast
SLOW_CASES = {"N = 12"}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW_CASES
                                  else n for n in CASES])
def test_default_method_within_1e6_of_50_digit_reference(name):
    params = CASES[name]
    s = lumped.natural_modes(params)
    reference = np.array(mp_frequencies(params, dps=50))
    elastic = slice(s.n_rigid, None)
    np.testing.assert_allclose(s.omega[elastic], reference[elastic], rtol=1e-6,
                               err_msg=f"{name}: jacobi vs 50-digit mpmath")
    assert np.all(s.omega[: s.n_rigid] == 0.0)
    assert np.all(reference[: s.n_rigid] < 1e-12 * reference[-1])


def test_plain_eigh_fails_where_jacobi_holds():
    """Why the default is not eigh: it loses the lowest frequency of a 1e14-stiff case."""
    params = CASES["mesh 1e14 / torsion 1 N/m"]
    reference = mp_frequencies(params)[0]
    error = abs(lumped.natural_modes(params, "eigh").omega[0] - reference) / reference
    assert error > 1e-3


@pytest.mark.slow
def test_stability_report_rows_cover_every_case_and_method():
    rows = stability.run(lumped_preset("raba118"), repeats=1)
    assert len(rows) == len(CASES) * len(lumped.METHODS) + 1
    default = [r for r in rows if r.method == "jacobi"]
    assert all(r.max_error <= stability.TARGET for r in default)
    assert rows[-1].note.startswith("detected: the stiffness matrix is indefinite")
