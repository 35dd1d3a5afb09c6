"""The reports and docs word the lumped model's standing against the published Raba
118/76 spectrum as ``hubvib validate raba118`` computes it: the paper's printed matrix gives
the published values, the energy-consistent model the studies use is off on the
translational modes; the numbers come from the same comparison."""
import re
from pathlib import Path

from hubvib.reducer import lumped_preset
from hubvib.reports.validation_status import lumped_model_status
from hubvib.validation.raba118 import validate

ROOT = Path(__file__).parents[2]
SOURCES = [p for folder in ("hubvib", "validation", "lumped") for p in (ROOT / folder).rglob("*.py")]
SOURCES += sorted((ROOT / "docs").glob("*.md")) + [ROOT / "README.md"]


def test_no_text_says_the_model_reproduces_the_published_spectrum():
    """Only the printed matrix gives the published values (lumped/printed.py says so); no
    report, page or docstring says the lumped model or hubvib does."""
    claim = re.compile(r"reproduces\s+(the\s+published\s+Raba|all\s+18\s+published)", re.I)
    found = [f"{p.relative_to(ROOT)}: {m.group(0)!r}" for p in SOURCES
             for m in [claim.search(p.read_text(encoding="utf-8"))] if m]
    assert not found, found


def test_the_status_sentence_carries_the_validation_numbers():
    result = validate(lumped_preset("raba118"))
    low, high = result.energy_deviation_percent("translational")
    text = lumped_model_status()
    assert low < -50 and f"{low:+.3g} %" in text and f"{high:+.3g} %" in text, text
    assert f"{100 * result.printed_max_deviation:.2g} %" in text
    assert "printed matrix" in text and "energy-consistent model" in text


def test_the_sweep_report_states_it(fig4_sweep):
    from hubvib.studies.sweep import report_markdown

    report = report_markdown(fig4_sweep, [])
    assert f"- Model: {lumped_model_status()}." in report
