"""The README: at most 250 lines, its worked example prints the figures its comments quote,
its set-up commands are the ones CI runs, its links resolve, its command table is the CLI's."""
import contextlib
import io
import re
from pathlib import Path

import pytest

from hubvib.cli import main

ROOT = Path(__file__).parents[2]
README = (ROOT / "README.md").read_text()
NUMBER = r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?"


def _slug(heading: str) -> str:
    """The anchor Python-Markdown's toc (MkDocs) and GitHub give a heading."""
    text = re.sub(r"[^\w\s-]", "", heading.replace("`", "")).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


def test_readme_is_at_most_250_lines():
    lines = README.count("\n")
    assert lines <= 250, f"README.md has {lines} lines; the house rule allows 250 (the rest is in docs/)"


def test_worked_example_prints_the_figures_its_comments_quote(capsys):
    """Each ``print(...)  # ... [a b] ...`` line: the printed numbers equal the quoted ones
    to the last digit quoted (half a unit of it), and the quoted words are printed."""
    blocks = re.findall(r"```python\n(.*?)```", README, re.S)
    assert len(blocks) == 1, "the README has one worked example (the rest is in docs/)"
    exec(compile(blocks[0], "README.md", "exec"), {})
    printed = capsys.readouterr().out.strip().splitlines()
    quoted = [line.split("#", 1)[1] for line in blocks[0].splitlines()
              if line.startswith("print(") and "#" in line]
    assert len(printed) == len(quoted) == 3, (printed, quoted)
    for output, comment in zip(printed, quoted):
        claimed = re.search(r"\[([^\]]*)\]", comment).group(1).split()
        got = [float(x) for x in re.findall(NUMBER, re.search(r"\[([^\]]*)\]", output).group(1))]
        assert len(got) == len(claimed), f"README quotes {claimed}, the example prints {output}"
        for value, text in zip(got, claimed):
            decimals = len(text.split(".")[1]) if "." in text else 0
            assert value == pytest.approx(float(text), abs=0.5 * 10 ** -decimals), (
                f"README comment {comment.strip()!r} against a fresh run: {output}")
        for word in re.findall(r"[a-z]{5,}", comment.split("]")[-1]):
            if word in {"rotational", "translational", "planet", "mixed"}:
                assert word in output, f"README says {word!r}; the run prints {output}"


def test_setup_commands_are_the_ones_ci_runs():
    commands = re.findall(r"```bash\n(.*?)\n```", README, re.S)
    assert commands[:2] == ['pip install ".[report,fem,render]" && hubvib run',
                            'pip install -e ".[test]" && python -m pytest']
    ci = (ROOT / ".ci" / "run").read_text()
    assert 'pip install -e ".[test]" && python -m pytest' in ci
    assert "hubvib run" in ci
    assert 'pip install -e ".[docs]" && mkdocs build --strict' in commands
    assert 'pip install -e ".[docs]" && mkdocs build --strict' in ci, "CI builds the docs"


def test_every_relative_link_resolves():
    links = re.findall(r"\]\(([^)\s]+)\)", README)
    relative = [link for link in links if not re.match(r"[a-z]+://", link)]
    assert len(relative) >= 12, "the README links the docs pages"
    for link in relative:
        path, _, anchor = link.partition("#")
        target = ROOT / path
        assert target.exists(), f"README links {link!r}, but {path} does not exist"
        if anchor:
            headings = re.findall(r"^#+ (.+)$", target.read_text(), re.M)
            assert anchor in {_slug(h) for h in headings}, (
                f"README links {link!r}; {path} has no heading with that anchor")


def test_command_table_is_the_cli():
    """Every command in the README's table exists in ``hubvib --help``, and every command of
    ``hubvib --help`` is in the table."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit):
        main(["--help"])
    available = set(re.search(r"\{([a-z,-]+)\}", out.getvalue()).group(1).split(","))
    table = README.split("## Commands", 1)[1].split("\n## ", 1)[0]
    listed = set(re.findall(r"^\| `hubvib ([a-z-]+)", table, re.M))
    assert listed, "the README has a command table"
    assert listed <= available, f"README lists commands hubvib lacks: {listed - available}"
    assert available <= listed, f"commands missing from the README table: {available - listed}"


def test_crack_answer_paragraph_quotes_the_committed_default_scene_run():
    """The README's "Can a frequency measurement see the crack?" figures are those of
    ``docs/data/raba118_crack/results.json`` (``hubvib run raba118_crack``), to the digits
    quoted: the 10 s identification scatter of the watched modes, mode 13's frequency and
    its record shifts (series), the first depth with family POD >= 0.9 per record length,
    and the ratio method's detectable depths."""
    import json

    run = json.loads((ROOT / "docs/data/raba118_crack/results.json").read_text())
    detection, depths = run["detection"], run["crack"]["depths"]
    sigma = [detection["sigma_hz"][m - 1] for m in detection["watched_modes"]]
    mode13 = run["modes"][12]
    at_3mm = next(r for r in run["c_rp_methods"] if r["mode"] == 13 and r["depth_mm"] == 3.0)

    def first_depth_mm(pod):
        seen = [1e3 * d for d, p in zip(depths, pod) if p >= 0.9]
        return round(seen[0]) if seen else None

    first = {s: first_depth_mm(detection["family_pod"][s]) for s in ("10", "60", "600")}
    ratio = run["c_rp_other_method_family_pod"]["family_detectable_depth_m"]
    expected = [f"scatters by {min(sigma):.2f}-{max(sigma):.2f} Hz",
                f"rigid mode 13 ({mode13['frequency_intact_hz']:.1f} Hz) moves "
                f"{at_3mm['record_shift_series_hz']:.2f} Hz at 3 mm and "
                f"{mode13['record_shift_at_deepest_hz']:.2f} Hz through the rim",
                f"detectable on that model, with 600 s records from {first['600']} mm",
                f"would give {round(1e3 * ratio['10'])} mm at 10 s and "
                f"{round(1e3 * ratio['60'])} mm at 60 s"]
    assert first["10"] is None and first["60"] is None, \
        "README: no crack of the sweep detectable with 10 or 60 s records"
    text = " ".join(README.split())
    for phrase in expected:
        assert phrase in text, f"README against docs/data/raba118_crack: {phrase!r}"


def test_elastic_ring_answer_quotes_the_committed_default_scene_run():
    """The README's leading answer is the elastic ring's of
    ``docs/data/raba118_crack/results.json``: the model that leads (its validity band, the
    rigid ring's band and the lowest ring mode), the POD crossing per record length, the
    best watched mode's record and open change at 3 mm against its 10 s scatter, the open
    share of the loaded crack at 3 mm, the Monte Carlo's size and the answer with closure
    gaps of 1 and 2 um."""
    import json

    run = json.loads((ROOT / "docs/data/raba118_crack/results.json").read_text())
    assert run["short_answer"]["ring"] == "elastic", "the elastic ring leads the default run"
    elastic = run["elastic_ring"]
    crossing = {t: elastic["pod_crossing"][t]["words"] for t in ("10", "60", "600")}
    best = elastic["modes"][elastic["watched_modes"][0] - 1]
    at = elastic["depths_mm"].index(3.0)
    state = next(c for c in elastic["crack_state"] if c["depth_m"] == 0.003)
    lowest = elastic["lowest_ring_mode"]
    watched = [elastic["modes"][m - 1]["frequency_hz"] for m in elastic["watched_modes"]]
    gap = {(v["torque_fraction"], v["closure_gap_m"]): v["answer"]["10"]
           for v in run["load_sensitivity"]}
    pads = {v["place"]: v for v in run["pad_variant"]["variants"]}
    expected = [
        f"detected with 10 s records {crossing['10']} deep, with 60 s records "
        f"{crossing['60']}, with 600 s records {crossing['600']}",
        f"best watched mode, {best['label']}, moves {best['shift_record_hz'][at]:.1f} Hz at "
        f"3 mm in a record ({best['shift_open_hz'][at]:.1f} Hz with the faces held open) "
        f"against a 10 s scatter of {best['sigma_hz']['10']:.2f} Hz",
        f"apart at {100 * state['open_share']:.0f} % of the carrier positions",
        f"lowest elastic mode of its own at {lowest['frequency_hz']:.0f} Hz "
        f"(n = {lowest['nodal_diameter']})",
        f"9 + 3N model holds only below {elastic['validity']['band_top_hz']:.0f} Hz",
        f"POD >= 0.9 over {elastic['monte_carlo_samples']} reducers",
        f"the watched modes lie at {min(watched) / 1e3:.1f}-{max(watched) / 1e3:.1f} kHz",
        f"closure gap of 1 um (roughness, residual compression) it is {gap[1.0, 1e-06]} at "
        f"10 s, with 2 um {gap[1.0, 2e-06]}",
        f"the crack on a support pad (tooth {pads['on a support pad']['tooth']}) and between "
        f"pads (tooth {pads['between pads']['tooth']}) are both detected "
        f"{pads['on a support pad']['answer']['10']} at 10, 60 and 600 s"]
    assert all(v["answer"][t] == pads["on a support pad"]["answer"]["10"]
               for v in pads.values() for t in ("10", "60", "600")), \
        "the README says one answer for both places and every record length"
    text = " ".join(README.split())
    for phrase in expected:
        assert phrase in text, f"README against docs/data/raba118_crack: {phrase!r}"


def test_record_loop_sentence_quotes_the_committed_loop():
    """The README's closed-loop figures are those of docs/data/record_loop.json."""
    import json

    data = json.loads((ROOT / "docs" / "data" / "record_loop.json").read_text())
    s = data["summary"]
    text = " ".join(README.split())
    phrase = (f"hold the true depth in {s['covered']} of {s['cracked']} cracked records "
              f"({100 * s['coverage']:.0f} %)")
    assert phrase in text, f"README should say {phrase!r} (docs/data/record_loop.json)"
    assert f"{s['records']} simulated records" in text
    assert ("intact records are not called cracked" in text) == (s["false_alarms"] == 0), \
        f"{s['false_alarms']} false alarms in docs/data/record_loop.json"
