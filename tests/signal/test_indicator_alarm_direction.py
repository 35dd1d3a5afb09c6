"""The signal report says which side of its threshold each indicator alarms on: a falling
indicator (kurtosis on the Raba scene) is claimed to detect by a decrease, never by growth."""
import json
from pathlib import Path

from hubvib.signal.report import roc_section

RESULTS = Path(__file__).parents[2] / "docs" / "data" / "raba118_signal" / "results.json"


def _roc():
    return json.loads(RESULTS.read_text())["roc"]


def _rows(lines):
    return {line.split(" | ")[0].lstrip("| "): line for line in lines
            if line.startswith("| ") and " | " in line}


def test_every_indicator_row_names_the_side_that_alarms():
    roc = _roc()
    rows = _rows(roc_section(roc))
    for name, indicator in roc["indicators"].items():
        side = "rises above" if indicator["direction"] == "increasing" else "falls below"
        assert f"| {side} {indicator['threshold']:.4g} |" in rows[name], rows[name]


def test_a_falling_indicator_is_said_to_detect_by_a_decrease():
    """Kurtosis on the committed Raba signal run falls with the crack and is seen from
    3 mm; its threshold lies below the intact records' values, so the report says the
    3 mm is a decrease, not growth."""
    roc = _roc()
    kurtosis = roc["indicators"]["kurtosis"]
    assert kurtosis["direction"] == "decreasing" and kurtosis["first_depth_seen_mm"] == 3
    lines = roc_section(roc)
    assert f"| falls below {kurtosis['threshold']:.4g} |" in _rows(lines)["kurtosis"]
    [sentence] = [line for line in lines if line.startswith("kurtosis:")]
    assert "detected by a decrease" in sentence, sentence


def test_no_decrease_sentence_when_every_indicator_rises():
    roc = _roc()
    for indicator in roc["indicators"].values():
        indicator["direction"] = "increasing"
    assert not [line for line in roc_section(roc) if "decrease" in line]
