"""The elastic ring's closed loop from records (``hubvib.studies.record_loop``): its
counts, its binomial intervals and, on the real scene, one intact and one cracked record
diagnosed and kept in the result cache."""
import numpy as np
import pytest

from hubvib.studies import record_loop
from hubvib.studies.record_loop import LoopRow, loop_table, summary, wilson


def _row(depth, verdict, low=None, high=None, k=0):
    estimate = None if low is None else 0.5 * (low + high)
    return LoopRow(depth, k, verdict, estimate, low, high, 0.9, (22,))


def test_wilson_interval_equals_scipys():
    """The Wilson score interval against scipy.stats.binomtest(...).proportion_ci(method=
    "wilson"), an independent implementation, to 1e-6."""
    from scipy.stats import binomtest

    for k, n in ((0, 10), (3, 10), (27, 30), (81, 263), (30, 30)):
        ci = binomtest(k, n).proportion_ci(0.95, method="wilson")
        assert np.allclose(wilson(k, n), [ci.low, ci.high], atol=1e-6), (k, n)
    assert wilson(0, 0) is None


def test_a_record_without_an_interval_does_not_hold_its_depth():
    rows = [_row(0.0, "no crack indicated", 0.0, 0.002),
            _row(0.0, "crack indicated", 0.001, 0.004, k=1),
            _row(0.003, "crack indicated", 0.001, 0.005),
            _row(0.003, "no crack indicated", 0.0, 0.002, k=1),
            _row(0.003, "not explained by a ring crack", k=2)]
    s = summary(rows, 0.01)
    assert (s["cracked"], s["intact"], s["covered"]) == (3, 2, 1)
    assert s["coverage"] == pytest.approx(1 / 3)
    assert s["false_alarms"] == 1 and s["false_alarm_rate"] == 0.5
    assert s["verdicts"] == {"crack indicated": 1, "no crack indicated": 1,
                             "not explained by a ring crack": 1}
    assert rows[4].covered is None and rows[3].covered is False and rows[2].covered
    data = {"summary": s, "rows": [record_loop._row_dict(r) for r in rows]}
    table = loop_table(data)
    assert "| 3.00 | 3 | 1 | 1 | 2.00 | 3.50 |" in table, table
    assert "in 1 of 3 (33 %" in table and "1 of 2 (50 %" in table and "90 %" in table


def test_seeds_differ_from_the_shipped_records_and_between_records():
    seeds = {record_loop.record_seed(d, k) for d in (0.0, 0.0015, 0.0045) for k in range(15)}
    baselines = {record_loop.record_seed(0.0, k, baseline=True) for k in range(15)}
    assert len(seeds) == 45 and len(baselines) == 15 and not seeds & baselines
    assert all(s[0] != 0 for s in seeds | baselines), "the shipped records use seed 0"


@pytest.mark.slow
def test_one_intact_and_one_cracked_record_are_diagnosed_and_kept(tmp_path, monkeypatch):
    """The real scene: the first intact and 4.5 mm records give the committed loop's rows
    (docs/data/record_loop.json, the same seeds: verdict, estimate and interval to 1 um);
    a rerun reads both rows from the result cache (no record simulated)."""
    import json
    from pathlib import Path

    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    rows = record_loop.loop_rows(record_loop.DEFAULT_SCENE, [0.0045], 1, 1, workers=2)
    assert [(r.depth_m, r.k) for r in rows] == [(0.0, 0), (0.0045, 0)]
    committed = json.loads((Path(__file__).parents[2] / "docs" / "data"
                            / "record_loop.json").read_text())["rows"]
    want = {(r["depth_m"], r["k"]): r for r in committed}
    for row in rows:
        c = want[(row.depth_m, row.k)]
        assert row.verdict == c["verdict"], (row, c)
        for field in ("estimate_m", "low_m", "high_m"):
            got, then = getattr(row, field), c[field]
            assert (got is None) == (then is None), (field, row, c)
            assert got is None or abs(got - then) <= 1e-6, (field, row, c)

    def no_pool(*a, **k):
        raise AssertionError("a cached row simulated again")

    monkeypatch.setattr("hubvib.runtime.process_pool.worker_pool", no_pool)
    again = record_loop.loop_rows(record_loop.DEFAULT_SCENE, [0.0045], 1, 1)
    assert [record_loop._row_dict(r) for r in again] == \
        [record_loop._row_dict(r) for r in rows], "the cached rows (NaN as None)"


@pytest.mark.parametrize("depths", ["0,1.5", "1.5,1.5", "x", ""])
def test_bad_depths_are_one_line_and_exit_2(depths, capsys):
    with pytest.raises(SystemExit) as stop:
        record_loop.main(["--depths-mm", depths, "--records", "1", "--intact", "0"])
    err = capsys.readouterr().err
    assert stop.value.code == 2 and err.count("\n") == 1 and "--depths-mm" in err, err
