"""``report.html`` beside ``report.md``: one self-contained page a browser opens.

Figures are embedded as data URIs (a mode shape's GIF animation, when one was written,
replaces its still PNG), tables sort by a click on a column head (numbers as numbers), a table wider than the page
scrolls inside its own box,
and links to other reports (the signal study's ``report.md``) point at their HTML.  No network, no
external file: the page can be mailed or archived alone.
"""
from __future__ import annotations

import base64
import html
import re
from pathlib import Path

from hubvib.foundation.output import write_text

_TYPES = {".png": "image/png", ".gif": "image/gif", ".jpg": "image/jpeg", ".svg": "image/svg+xml"}
_STYLE = """
body { font-family: system-ui, sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em;
       line-height: 1.45; color: #222; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.9em; display: block;
        max-width: 100%; overflow-x: auto; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; }
th { background: #f0f0f0; cursor: pointer; user-select: none; }
th[aria-sort="ascending"]::after { content: " \\25B2"; }
th[aria-sort="descending"]::after { content: " \\25BC"; }
img { max-width: 100%; height: auto; display: block; margin: 1em 0 0.2em; }
code, pre { background: #f6f6f6; }
"""
#: click a column head: sort its rows (numbers as numbers, else text), click again: reverse
_SCRIPT = """
document.querySelectorAll("table").forEach(function (table) {
  var heads = table.querySelectorAll("thead th");
  heads.forEach(function (head, column) {
    head.title = "click to sort";
    head.addEventListener("click", function () {
      var body = table.tBodies[0];
      var up = head.getAttribute("aria-sort") !== "ascending";
      heads.forEach(function (h) { h.removeAttribute("aria-sort"); });
      head.setAttribute("aria-sort", up ? "ascending" : "descending");
      var rows = Array.prototype.slice.call(body.rows);
      function key(row) {
        var text = row.cells[column] ? row.cells[column].textContent.trim() : "";
        var number = parseFloat(text.replace(/[^0-9eE.+\\-]/g, ""));
        return isNaN(number) ? text.toLowerCase() : number;
      }
      rows.sort(function (a, b) {
        var x = key(a), y = key(b);
        if (typeof x !== typeof y) { x = String(x); y = String(y); }
        return (x < y ? -1 : x > y ? 1 : 0) * (up ? 1 : -1);
      });
      rows.forEach(function (row) { body.appendChild(row); });
    });
  });
});
"""


def write_html_report(folder: Path, text: str | None = None) -> Path:
    """Write ``folder/report.html`` from ``text``, the ``report.md`` written there (read
    from the file when None), and the figures it shows; returns its path."""
    import markdown

    folder = Path(folder)
    if text is None:
        text = (folder / "report.md").read_text(encoding="utf-8")
    body = markdown.markdown(text, extensions=["tables", "fenced_code"])
    body = re.sub(r'<img alt="([^"]*)" src="([^"]+)"',
                  lambda m: f'<img alt="{m.group(1)}" src="{_data_uri(folder, m.group(2))}"',
                  body)
    body = re.sub(r'href="([^":]+)\.md"', r'href="\1.html"', body)
    title = re.search(r"^#\s+(.+)$", text, re.M)
    page = ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{html.escape(title.group(1) if title else 'hubvib report')}</title>\n"
            f"<style>{_STYLE}</style>\n</head>\n<body>\n{body}\n"
            f"<script>{_SCRIPT}</script>\n</body>\n</html>\n")
    return write_text(folder / "report.html", page)


def write_html_reports(folder: Path, texts: dict | None = None) -> list[Path]:
    """``report.html`` beside every ``report.md`` under ``folder`` (a study with
    per-half-length or signal reports links to theirs); ``texts``: a ``report.md`` path ->
    the text written there, for the reports assembled in this process."""
    texts = texts or {}
    return [write_html_report(md.parent, texts.get(md))
            for md in sorted(Path(folder).rglob("report.md"))]


def _data_uri(folder: Path, source: str) -> str:
    """The figure ``source`` (relative to ``folder``) as a data URI; a mode's animation
    when its GIF sits beside the PNG."""
    path = folder / html.unescape(source)
    animated = path.with_suffix(".gif")
    if path.suffix == ".png" and animated.is_file():
        path = animated
    kind = _TYPES.get(path.suffix.lower())
    if kind is None or not path.is_file():
        raise ValueError(f"report figure {source!r} is missing or not an image")
    return f"data:{kind};base64,{base64.b64encode(path.read_bytes()).decode('ascii')}"
