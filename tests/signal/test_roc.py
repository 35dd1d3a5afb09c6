"""Detection rates from many records: the AUC against its count
definition, the family-wise false-alarm rate measured on a noise model the thresholds
were not tuned on, and POD rising with the fault."""
import math

import numpy as np
import pytest

from hubvib.signal.indicators import GearOrders
from hubvib.signal.roc import auc, detection_rates, roc_curve

CARRIER_HZ, FS, REVS = 10.0, 4096.0, 8
GEAR = GearOrders(64, 3, 3)


def _clean(bump):
    t = np.arange(int(REVS * FS / CARRIER_HZ)) / FS
    phi = 2 * math.pi * CARRIER_HZ * t
    mesh = np.cos(63 * phi) + 0.5 * np.cos(129 * phi) + 0.3 * np.cos(192 * phi)
    wrapped = (phi % (2 * math.pi)) - math.pi
    return t, mesh * (1 + bump * np.exp(-(wrapped / 0.08) ** 2))  # a tooth's local AM


def test_auc_is_the_mann_whitney_count():
    intact = np.array([0.0, 1.0, 2.0, 3.0])
    cracked = np.array([1.0, 2.5, 4.0])
    # pairs cracked > intact: 1 -> 1 (+ tie 1/2), 2.5 -> 3, 4 -> 4: (1.5 + 3 + 4) / 12
    assert auc(intact, cracked) == (1.5 + 3 + 4) / 12
    curve = roc_curve(intact, cracked)
    assert curve[0] == [1.0, 1.0] and curve[-1] == [0.0, 0.0]


def _rates(records):
    depths = [0.0, 0.001, 0.002, 0.004]
    clean = [_clean(b) for b in (0.0, 0.02, 0.05, 0.3)]
    angle = 2 * math.pi * CARRIER_HZ * clean[0][0]
    return detection_rates(depths, clean, angle, 512, GEAR, 0.1, records, 0.1)


def _check(roc, records, alpha=0.1):
    # thresholds: max-T split-conformal calibration on Gaussian-noise intact records; the
    # family-wise rate is measured on independent intact records and must stay within
    # alpha + 3 binomial standard errors
    measured, se = roc["family_false_alarm_measured"], math.sqrt(alpha * (1 - alpha) / records)
    assert measured <= alpha + 3 * se, f"family-wise false alarms {measured} vs {alpha}"
    any_pod = roc["any_indicator_pod"]
    assert any_pod[-1] == 1.0, "a 30 % local modulation is seen in every record"
    fm4 = roc["indicators"]["fm4"]
    assert fm4["direction"] == "increasing" and fm4["auc"][-1] > 0.99, fm4["auc"]
    assert fm4["first_depth_seen_mm"] is not None


def test_false_alarms_and_pod_on_records():
    _check(_rates(25), 25)


@pytest.mark.slow
def test_false_alarms_and_pod_on_many_records():
    roc = _rates(300)
    _check(roc, 300)
    pod = roc["any_indicator_pod"]
    assert pod[1] <= pod[2] + 0.05 and pod[2] <= pod[3], "POD grows with the fault"


def test_too_few_records_for_the_rate_are_refused():
    with pytest.raises(ValueError, match="roc_records = 2"):
        detection_rates([0.0, 0.001], [_clean(0.0), _clean(0.3)],
                        2 * math.pi * CARRIER_HZ * _clean(0.0)[0], 512, GEAR, 0.1, 2, 0.05)
