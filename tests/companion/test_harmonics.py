"""Seed 000: kinematic-error harmonics (checks of shared/reference/seeds_000_002.md)."""
import json
import math

import numpy as np
import pytest

from hubvib.cli import main
from hubvib.companion.harmonics import (GearTrain, analyse, kinematic_error,
                                        position_locked_periods, read_periods)

SYNTHETIC_DEG = {1: 0.20, 2: 0.08, 6: 0.05, 12: 0.12, 294: 0.02}  # seeds_000_002.md


def _synthetic(revolutions=3, pulses=2048, harmonics=SYNTHETIC_DEG):
    return position_locked_periods({k: math.radians(a) for k, a in harmonics.items()}, pulses,
                                   revolutions, 1500 / 49)


def test_ratios_of_eq_2():
    assert GearTrain(1, 10).ratio == 11, "seed 000 eq. (2): (1 + 10) / 1 = 11"
    assert GearTrain(1, 6, stages=2).ratio == 49, "seed 000: two stages of (1 + 6) / 1 = 49"


def test_synthetic_record_comes_back():
    analysis = analyse(_synthetic(), 2048, GearTrain(1, 6, 2), count=5)
    found = {line.order: math.degrees(line.amplitude) for line in analysis.lines}
    assert set(found) == set(SYNTHETIC_DEG)
    for order, amplitude in SYNTHETIC_DEG.items():
        assert abs(found[order] - amplitude) < 1e-6, \
            f"order {order}: {found[order]} deg vs the synthetic {amplitude} deg (1e-6 deg)"
    pp = math.degrees(analysis.error.peak_to_peak)
    assert round(pp, 4) == 0.7523, f"peak-to-peak {pp} deg vs 0.7523 deg (seeds_000_002.md)"
    e = analysis.error
    np.testing.assert_allclose(e.error, e.error_eq4, rtol=0, atol=1e-15,
                               err_msg="seed 000: eq. (3) must equal eq. (4)")


@pytest.mark.parametrize("z2, stages, orders, labels", [
    (10, 1, (1, 10, 11, 22, 152), ("output", "z2", "i", "2xi", "unexplained")),
    (6, 2, (1, 2, 6, 12, 294), ("output", "2xoutput", "z2", "2xz2", "E2")),
])
def test_the_papers_dominant_harmonics_get_the_papers_labels(z2, stages, orders, labels):
    # seed 000: roller i = 11 (1, 10, 11, 22, 152) and ball i = 49 (1, 2, 6, 12, 294); the
    # paper ties 10 = z2, 11 = i, 22 = 2i, 6 = z2, 12 = 2 z2, 294 = z2 (z1 + z2) i_stage
    # and gives no rule for 152
    amplitudes = {k: 0.1 / (j + 1) for j, k in enumerate(orders)}
    analysis = analyse(_synthetic(harmonics=amplitudes), 2048, GearTrain(1, z2, stages),
                       count=len(orders))
    assert tuple(line.order for line in analysis.lines) == orders
    assert tuple(line.label for line in analysis.lines) == labels


def test_partial_revolution_and_orders_above_nyquist_are_named_not_reported():
    periods = _synthetic(revolutions=3, pulses=256)[:-100]
    analysis = analyse(periods, 256, GearTrain(1, 6, 2), count=5, max_order=400)
    assert any("not a whole number" in w for w in analysis.warnings)
    assert any("Nyquist order 127" in w for w in analysis.warnings)
    assert max(line.order for line in analysis.lines) <= 127, \
        "an order at or above N/2 must never be reported (it would be an alias)"
    # order 294 sits above the Nyquist order of 256 pulses: it is not in the list
    assert 294 not in [line.order for line in analysis.lines]


def test_timestamps_give_the_same_error(tmp_path):
    periods = _synthetic(revolutions=2, pulses=512)
    (tmp_path / "p.csv").write_text("period_s\n" + "\n".join(f"{t:.17g}" for t in periods))
    stamps = np.concatenate([[10.0], 10.0 + np.cumsum(periods)])
    (tmp_path / "t.csv").write_text("timestamp_s\n" + "\n".join(f"{t:.17g}" for t in stamps))
    a = kinematic_error(read_periods(tmp_path / "p.csv"), 512)
    b = kinematic_error(read_periods(tmp_path / "t.csv"), 512)
    np.testing.assert_allclose(a.error, b.error, atol=1e-9)


def test_cli_writes_files_and_standard_json(tmp_path, capsys):
    path = tmp_path / "ball.csv"
    path.write_text("\n".join(f"{t:.17g}" for t in _synthetic()))
    out = tmp_path / "out"
    assert main(["harmonics", "--periods", str(path), "--pulses-per-rev", "2048", "--z2", "6",
                 "--stages", "2", "--unit", "arcmin", "--json", "--out", str(out)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["ratio"] == 49 and data["unit"] == "arcmin"
    assert abs(data["peak_to_peak"] - 60 * 0.75228) < 1e-3
    for name in ("error.csv", "spectrum.csv", "harmonics.csv", "harmonics.png"):
        assert (out / name).stat().st_size > 0


@pytest.mark.parametrize("content, flags, message", [
    ("0.001\n-0.002\n" * 1024, [], "period 2 = -0.002 s; allowed: 1e-09..86400 s"),
    ("0.001\nnan\n" * 1024, [], "period 2 = nan s"),
    ("0.001\nabc\n", [], "line 2: 'abc' is not a number"),
    ("0.001\n" * 3000, [], "allowed: >= 2 revolutions"),
    ("0.001\n" * 5000, ["--z2", "0"], "--z2 = 0; allowed: an integer 1..10000"),
    ("0.001\n" * 5000, ["--stages", "0"], "--stages = 0; allowed: an integer 1..20"),
    ("0.001\n" * 5000, ["--z1", "0"], "--z1 = 0; allowed: an integer 1..10000"),
], ids=["negative", "nan", "text", "one-revolution", "z2", "stages", "z1"])
def test_bad_input_is_one_line_and_exit_2(tmp_path, capsys, content, flags, message):
    path = tmp_path / "p.csv"
    path.write_text(content)
    out = tmp_path / "out"
    argv = ["harmonics", "--periods", str(path), "--pulses-per-rev", "2048", "--z2", "6",
            "--out", str(out)] + flags
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err, err
    assert not out.exists(), "nothing may be written on bad input"
