"""Every null a results file writes says why: the committed runs the docs quote, checked
against the rule of ``tests.helpers.null_reasons``."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from hubvib.foundation.output import explained
from tests.helpers.null_reasons import unexplained_nulls

DATA = Path(__file__).parents[2] / "docs" / "data"
RESULTS = sorted(DATA.glob("**/results.json"))


def test_committed_results_are_found():
    assert len(RESULTS) >= 5, RESULTS


@pytest.mark.parametrize("path", RESULTS, ids=lambda p: str(p.relative_to(DATA)))
def test_every_null_in_a_committed_results_file_says_why(path):
    missing = unexplained_nulls(json.loads(path.read_text()))
    assert not missing, f"{path.relative_to(DATA)}: nulls without a reason: {missing[:10]}"


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
                    a="no a", b="no b", c="no c", d="no d")
    assert row == {"a": None, "b": 1.0, "c": [1.0, None], "d": [1.0],
                   "a_reason": "no a", "c_reason": "no c"}


def test_the_results_file_keeps_a_reason_only_where_a_null_is():
    """``results.json``'s pruning: a reason beside a value goes, one beside a null, a list
    holding a null or a mapping of reasons stays (at any depth)."""
    from hubvib.reports.crack_tables import _reasons_for_nulls

    kept = _reasons_for_nulls({"a": 1, "a_reason": "x", "b": None, "b_reason": "y",
                               "c": {"10": None}, "c_reason": {"10": "z"},
                               "d": [None], "d_reason": "w", "e": {"f": 2, "f_reason": "q"}})
    assert kept == {"a": 1, "b": None, "b_reason": "y", "c": {"10": None},
                    "c_reason": {"10": "z"}, "d": [None], "d_reason": "w", "e": {"f": 2}}
    assert unexplained_nulls(kept) == []
