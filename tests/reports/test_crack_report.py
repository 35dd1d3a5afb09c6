"""The crack study's report and tables, assembled once from its typed result (synthetic FE
rows: fast)."""
from dataclasses import replace

import pytest
from tests.helpers.crack_scenes import synthetic_scene
from tests.helpers.synthetic_rows import synthetic_fe_rows

from hubvib.reports.crack_files import write_crack_study
from hubvib.studies import crack_result
from hubvib.studies.crack_study import crack_study_from_fe

LINK = "[signal/report.md](signal/report.md).\n"


@pytest.fixture(scope="module")
def result():
    scene = replace(synthetic_scene("series"), plots=False)
    return crack_study_from_fe(scene, synthetic_fe_rows(scene.crack.depths), detection=False)


def test_signal_section_is_part_of_the_report_written_once(result, tmp_path, monkeypatch):
    """With a signal study the link to its report is the last section of ``report.md``,
    written in one piece (no second write of the file)."""
    from hubvib.reports import crack_files

    writes = []
    original = crack_files.write_text
    monkeypatch.setattr(crack_files, "write_text",
                        lambda path, text: writes.append(path) or original(path, text))
    write_crack_study(result, tmp_path, signal=True)
    report = (tmp_path / "report.md").read_text(encoding="utf-8")
    assert writes == [tmp_path / "report.md"], "report.md is written exactly once"
    assert report.endswith("\n## Vibration signature\n\nThe signal a sensor on the ring "
                           "records, its order spectrum, spectrogram and condition "
                           "indicators against crack depth: " + LINK)
    assert report.count("## Vibration signature") == 1


def test_no_signal_section_without_a_signal_study(result, tmp_path):
    write_crack_study(result, tmp_path)
    assert "## Vibration signature" not in (tmp_path / "report.md").read_text(encoding="utf-8")


def test_mode_sensitivities_are_solved_once(result, monkeypatch):
    """``mode_rows`` (called by the tables, the report and the console lines) solves the
    three stiffness sensitivities once per result, and gives the same rows each call."""
    fresh = replace(result)  # a new object: its cached sensitivities are not filled yet
    calls = []
    solve = crack_result.frequency_sensitivity
    monkeypatch.setattr(crack_result, "frequency_sensitivity",
                        lambda *a: calls.append(a[1]) or solve(*a))
    first = fresh.mode_rows()
    assert fresh.mode_rows() == first
    assert calls == list(crack_result.STIFFNESSES)


def test_report_text_is_kept_and_its_page_written_from_it(result, tmp_path):
    """The text ``report.md`` gets is on the result, and ``report.html`` can be written
    from it without reading the file back."""
    from hubvib.render.html import write_html_report

    write_crack_study(result, tmp_path / "study")
    assert (tmp_path / "study" / "report.md").read_text(encoding="utf-8") == result.report
    page = write_html_report(tmp_path, result.report)  # no report.md in tmp_path
    assert f"<title>{result.scene.name}: ring-crack sensitivity study</title>" in \
        page.read_text(encoding="utf-8")
