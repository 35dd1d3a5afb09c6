"""A mode number means different modes in the two ring models: every table the committed
runs write that has a mode column names the mode with its model (a ``mode_label`` column,
or labels ``rigid K (...)`` / ``elastic n=N (...)`` in the mode column itself)."""
from __future__ import annotations

import csv
import re
from pathlib import Path

import pytest

DATA = Path(__file__).parents[2] / "docs" / "data"
TABLES = sorted(p for p in DATA.glob("**/*.csv") if "inputs" not in p.parts)
LABEL = re.compile(r"^(rigid \d+|elastic n=\d+) \([a-z]+, [\d.]+ Hz\)$")


@pytest.mark.parametrize("path", TABLES, ids=lambda p: str(p.relative_to(DATA)))
def test_a_mode_column_names_the_model(path):
    with path.open(newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "mode" not in rows[0]:
        pytest.skip("no mode column")
    column = "mode_label" if "mode_label" in rows[0] else "mode"
    bad = [r[column] for r in rows if not LABEL.match(r[column])]
    assert not bad, f"{path.name}: mode names without their model: {bad[:5]}"
