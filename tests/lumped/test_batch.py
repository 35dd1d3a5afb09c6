"""Batched lumped solves (lumped/batch.py) against the single-point Jacobi solver."""
import numpy as np
import pytest

from hubvib.lumped import ParameterError, natural_modes
from hubvib.reducer import lumped_preset
from hubvib.lumped.batch import (batch_frequencies, benchmark_batch, blas_thread_counts,
                                 blas_threads)
from hubvib.lumped.parameters import MASS_FIELDS, STIFFNESS_FIELDS


def _scattered(params, points, seed):
    rng = np.random.default_rng(seed)
    changes = {n: getattr(params, n) * np.exp(0.3 * rng.standard_normal(points))
               for n in STIFFNESS_FIELDS if getattr(params, n) > 0}
    changes |= {n: getattr(params, n) * np.exp(0.1 * rng.standard_normal(points))
                for n in MASS_FIELDS}
    changes["c_rp_factors"] = np.exp(-0.2 * rng.random((points, params.n_planets)))
    return changes


def _one_at_a_time(params, changes):
    points = len(next(iter(changes.values())))
    return np.array([natural_modes(params.replace(**{
        n: (tuple(v[i]) if n == "c_rp_factors" else float(v[i])) for n, v in changes.items()}
    )).omega for i in range(points)])


def test_batch_agrees_with_jacobi_to_1e10():
    params = lumped_preset("raba118")
    changes = _scattered(params, 80, seed=1)
    batch = batch_frequencies(params, changes)
    reference = _one_at_a_time(params, changes)
    error = np.abs(batch.omega / reference - 1).max()
    assert error < 1e-10, f"batched vs natural_modes (Jacobi, ~1e-15): {error:.2e} > 1e-10"
    # 30 % scatter around the paper's values: the first tier nearly everywhere, never Jacobi
    assert (batch.tier == 1).mean() > 0.9 and not batch.fallback.any()
    assert (batch.error_bound <= 1e-10).all()


@pytest.mark.parametrize("mesh, torsion, tier", [(3e8, 1e4, 2), (1e14, 1.0, 3)])
def test_ill_conditioned_points_take_the_accurate_tiers(mesh, torsion, tier):
    # (1e14, 1): hubvib stability's "mesh 1e14 / torsion 1 N/m", where eigh of the assembled
    # matrix loses everything and the Jacobi SVD keeps ~1e-15
    params = lumped_preset("raba118")
    changes = {"c_sp": np.array([3e8, mesh]), "c_rp": np.array([3e8, mesh]),
               "c_su": np.array([1e6, torsion]), "c_cu": np.array([1e6, torsion]),
               "c_ru": np.array([1e6, torsion])}
    batch = batch_frequencies(params, changes)
    assert list(batch.tier) == [1, tier]
    reference = _one_at_a_time(params, changes)
    error = np.abs(batch.omega / reference - 1).max()
    assert error < 1e-10, f"tier {tier} vs Jacobi: {error:.2e} > 1e-10"


def test_mechanisms_give_exact_zeros_like_the_single_solver():
    params = lumped_preset("raba118")
    changes = {"c_su": np.array([0.0, 1e6]), "c_cu": np.array([0.0, 1e6])}
    batch = batch_frequencies(params, changes)
    for i in range(2):
        single = natural_modes(params.replace(c_su=float(changes["c_su"][i]),
                                              c_cu=float(changes["c_cu"][i])))
        assert np.count_nonzero(batch.omega[i] == 0) == single.n_rigid
        elastic = single.omega > 0
        np.testing.assert_allclose(batch.omega[i][elastic], single.omega[elastic], rtol=1e-10,
                                   err_msg="batched vs natural_modes with a mechanism")
    assert np.count_nonzero(batch.omega[0] == 0) >= 1  # free sun and carrier rotation


@pytest.mark.parametrize("changes, message", [
    ({"c_ru": [1e6, -1.0]}, r"c_ru\[1\] = -1.0, but it must be finite and >= 0"),
    ({"m_r": [6.8, 0.0]}, r"m_r\[1\] = 0.0, but it must be finite and > 0"),
    ({"c_ru": [1e6, np.nan]}, r"c_ru\[1\] = nan"),
    ({"c_ru": [1e6], "m_r": [1.0, 2.0]}, "one common length"),
    ({"theta": [0.0]}, r"batch changes \['theta'\]"),
    ({"c_rp_factors": np.ones((2, 2))}, r"c_rp_factors has shape \(2, 2\)"),
])
def test_bad_changes_name_the_field(changes, message):
    with pytest.raises(ParameterError, match=message):
        batch_frequencies(lumped_preset("raba118"), changes)


def test_blas_threads_are_one_inside_and_restored_after():
    before = blas_thread_counts()
    if not before:
        pytest.skip("no OpenBLAS loaded in this process")
    with blas_threads(1):
        assert blas_thread_counts() == [1] * len(before)
    assert blas_thread_counts() == before


def test_benchmark_reports_speed_and_agreement():
    result = benchmark_batch(lumped_preset("raba118"), points=300, single=10, workers=1)
    assert result["points"] == 300 and result["points_per_second"] > 0
    assert result["speedup"] > 0 and result["fallback_points"] == 0
    assert result["max_relative_difference"] < 1e-10, "benchmark's own agreement check"
