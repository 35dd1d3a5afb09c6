"""Every null a results file writes says why: the committed runs the docs quote, checked
against the rule of ``tests.helpers.null_reasons``."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from hubvib.foundation.output import explained
from tests.helpers.null_reasons import stray_reasons, unexplained_nulls

DATA = Path(__file__).parents[2] / "docs" / "data"
RESULTS = sorted(DATA.glob("**/results.json"))


def test_committed_results_are_found():
    assert len(RESULTS) >= 5, RESULTS


@pytest.mark.parametrize("path", RESULTS, ids=lambda p: str(p.relative_to(DATA)))
def test_every_null_in_a_committed_results_file_says_why(path):
    payload = json.loads(path.read_text())
    missing = unexplained_nulls(payload)
    assert not missing, f"{path.relative_to(DATA)}: nulls without a reason: {missing[:10]}"
    stray = stray_reasons(payload)
    assert not stray, f"{path.relative_to(DATA)}: reasons beside no null: {stray[:10]}"


def test_the_rule_finds_each_kind_of_unexplained_null():
    """A bare null, a list holding one and a mapping's null are found; each explained its
    own way is not."""
    assert unexplained_nulls({"a": None, "b": [1, None], "c": {"10": None, "60": 1.0}}) == [
        "/a", "/b[]", "/c/10"]
    assert unexplained_nulls({"a": None, "a_reason": "why", "b": [1, None],
                              "b_reason": "why", "c": {"10": None},
                              "c_reason": {"10": "why"}}) == []
    assert unexplained_nulls({"rows": [{"x": None}]}) == ["/rows[0]/x"]
    assert unexplained_nulls({"d": {"e": {"f": None}}}) == ["/d/e/f"]


def test_explained_adds_a_reason_only_beside_a_null():
    row = explained({"a": None, "b": 1.0, "c": [1.0, None], "d": [1.0]},
                    a="no a", b="no b", c="no c", d="no d", e="no e")
    assert list(row.items()) == [("a", None), ("a_reason", "no a"), ("b", 1.0),
                                 ("c", [1.0, None]), ("c_reason", "no c"), ("d", [1.0])], \
        "a reason right after its null; none beside a value, none for a key not written"
    assert unexplained_nulls(row) == [] and stray_reasons(row) == []


def test_the_stray_reason_rule_finds_a_reason_beside_a_value():
    assert stray_reasons({"a": 1, "a_reason": "x", "b": None, "b_reason": "y",
                          "c": {"10": None}, "c_reason": {"10": "z"}, "d": [None],
                          "d_reason": "w", "e": [{"f": 2, "f_reason": "q"}],
                          "g_reason": "v"}) == ["/a_reason", "/e[0]/f_reason", "/g_reason"]
