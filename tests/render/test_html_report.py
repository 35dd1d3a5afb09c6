"""``report.html`` beside ``report.md``, one self-contained page, tested in
a real headless browser (Chromium from Debian's packages, driven by its command line).

The page is loaded with a probe added around it (errors and ``console.error`` recorded,
then, on load: how many figures there are and how many the browser decoded, and one
click on a column head); ``--dump-dom`` returns the probe's result.  A screenshot of the
page is kept as a test artefact in ``HUBVIB_TEST_ARTEFACTS`` (default: pytest's tmp
folder).
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from hubvib.cli import main

BROWSER = shutil.which("chromium") or shutil.which("chromium-browser")
needs_browser = pytest.mark.skipif(
    BROWSER is None, reason="Chromium is not installed (apt-get install -y chromium; .ci/run "
                            "installs it where apt can)")
HEADLESS = [BROWSER or "chromium", "--headless", "--no-sandbox", "--disable-gpu",
            "--virtual-time-budget=10000"]

PROBE_HEAD = """<script>
window.__errors = [];
window.addEventListener("error", function (e) { window.__errors.push(String(e.message)); });
var __console_error = console.error;
console.error = function () {
  window.__errors.push(Array.prototype.join.call(arguments, " "));
  __console_error.apply(console, arguments);
};
</script>"""
PROBE_BODY = """<script>
window.addEventListener("load", function () {
  var images = Array.prototype.slice.call(document.images);
  var shown = images.filter(function (i) { return i.complete && i.naturalWidth > 0; });
  var table = document.querySelectorAll("table")[SORTED_TABLE];
  var head = table.querySelectorAll("thead th")[0];
  head.click(); head.click();  // descending by the first column
  var column = Array.prototype.map.call(table.tBodies[0].rows,
                                        function (r) { return r.cells[0].textContent.trim(); });
  var external = Array.prototype.filter.call(document.querySelectorAll("[src]"),
      function (e) { return !e.getAttribute("src").startsWith("data:"); }).length;
  var page = document.body.getBoundingClientRect().right;
  var wide = Array.prototype.filter.call(document.querySelectorAll("table, img"),
      function (e) { return e.getBoundingClientRect().right > page + 1; }).length;
  var out = document.createElement("pre");
  out.id = "probe";
  out.textContent = JSON.stringify({images: images.length, shown: shown.length,
                                    errors: window.__errors, column: column,
                                    sort: head.getAttribute("aria-sort"), external: external,
                                    wide: wide});
  document.body.appendChild(out);
});
</script>"""


def _probe(page: Path, table: int) -> dict:
    text = page.read_text(encoding="utf-8")
    probed = page.with_name("probe.html")
    probed.write_text(text.replace("<head>", "<head>" + PROBE_HEAD, 1).replace(
        "</body>", PROBE_BODY.replace("SORTED_TABLE", str(table)) + "</body>", 1),
        encoding="utf-8")
    dom = subprocess.run([*HEADLESS, "--dump-dom", probed.as_uri()], capture_output=True,
                         text=True, timeout=120).stdout
    found = re.search(r'<pre id="probe">([^<]*)</pre>', dom)
    assert found, f"the probe did not run; the browser returned {dom[:300]!r}"
    return json.loads(found.group(1).replace("&quot;", '"').replace("&amp;", "&"))


def _screenshot(page: Path, name: str, tmp_path: Path) -> Path:
    folder = Path(os.environ.get("HUBVIB_TEST_ARTEFACTS", tmp_path))
    folder.mkdir(parents=True, exist_ok=True)
    shot = folder / name
    subprocess.run([*HEADLESS, "--window-size=1200,2400", f"--screenshot={shot}",
                    page.as_uri()], capture_output=True, timeout=120, check=True)
    return shot


@pytest.mark.slow  # a run and two browser starts: ~17 s
@needs_browser
def test_html_report_loads_shows_every_figure_and_sorts(tmp_path, capsys):
    """The lumped sweep's report.html loads without a console error, every figure
    is decoded by the browser (2 of 2, embedded: no external source), the baseline table
    sorts by mode (descending: 18 first, Raba preset has 18 modes), and a screenshot is
    kept."""
    out = tmp_path / "out"
    assert main(["run", "raba118_c_ru", "--out", str(out)]) == 0
    page = out / "report.html"
    figures = (out / "report.md").read_text(encoding="utf-8").count("![")
    result = _probe(page, table=0)
    assert result["errors"] == [], result["errors"]
    assert result["images"] == figures == 2 and result["shown"] == figures, result
    assert result["external"] == 0, "every figure embedded in the page"
    assert result["sort"] == "descending"
    assert [int(x) for x in result["column"]] == list(range(18, 0, -1)), result["column"]
    shot = _screenshot(page, "report_raba118_c_ru.png", tmp_path)
    assert shot.stat().st_size > 10_000, "the screenshot is an empty page"
    capsys.readouterr()


def test_html_report_embeds_animations_and_links_html(tmp_path):
    """A mode's GIF replaces its PNG in the page (the animation), and a link to
    another report.md points at its report.html; no browser needed."""
    import base64

    from hubvib.render.html import write_html_report

    (tmp_path / "renders").mkdir()
    png = base64.b64decode("iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk"
                           "YPhfDwAChwGA60e6kgAAAABJRU5ErkJggg==")  # 1 x 1 px
    gif = base64.b64decode("R0lGODlhAQABAIAAAAAAAP///yH5BAEAAAAALAAAAAABAAEAAAIBRAA7")
    (tmp_path / "renders" / "mode_01.png").write_bytes(png)
    (tmp_path / "renders" / "mode_01.gif").write_bytes(gif)
    (tmp_path / "report.md").write_text(
        "# t\n\n![mode_01.png](renders/mode_01.png)\n\n[signal](signal/report.md)\n\n"
        "| a | b |\n|---|---|\n| 1 | 2 |\n", encoding="utf-8")
    page = write_html_report(tmp_path).read_text(encoding="utf-8")
    assert f"data:image/gif;base64,{base64.b64encode(gif).decode()}" in page
    assert 'href="signal/report.html"' in page and "<table>" in page


@needs_browser
def test_a_table_wider_than_the_page_scrolls_inside_its_box(tmp_path):
    """A report table of 30 wide columns (wider than the page at any window size) stays
    inside the page's column in the browser: no table or figure reaches past the body's
    right edge (the page scrolls the table, not itself)."""
    from hubvib.render.html import write_html_report

    head = "| " + " | ".join(f"column {k} with a long head" for k in range(30)) + " |"
    rule = "|" + "---:|" * 30
    row = "| " + " | ".join(f"{k}.000000" for k in range(30)) + " |"
    (tmp_path / "report.md").write_text(f"# wide\n\n{head}\n{rule}\n{row}\n",
                                        encoding="utf-8")
    result = _probe(write_html_report(tmp_path), table=0)
    assert result["errors"] == [], result["errors"]
    assert result["wide"] == 0, "a table or figure reaches past the page's right edge"
