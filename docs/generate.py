"""Every figure the hubvib docs quote, generated: no number in docs/*.md is typed by hand.

``table(name)`` returns the Markdown of one generated table (the pages hold the marker
``<!-- gen: name -->``, replaced by ``docs/hooks.py`` at build time); ``console(argv)``
runs one ``hubvib`` command in-process and returns a console block with its output.

Two kinds of source:

* computed now by the library (lumped spectra, the Raba 118/76 validation, the stability
  table, the design check, the series mounting, batched solves): cheap and deterministic;
* read from files in ``docs/data/`` that a named ``hubvib`` command wrote (benchmark timings,
  the FE stiffness table, the default crack study, the signal scene and its variants, the
  crack paths and the backup-ratio variants, the c_ru convergence); each such table says
  which command regenerates its file (``DATA_SOURCES``, read from the entry's
  ``docs/data/<entry>.meta.json``) and when it ran; ``docs/data/regenerate.sh`` reruns them.
  Scene and design variants the commands read sit in ``docs/data/inputs/``.

The pages keep what the markers generate, committed between the marker and its end, so
that they read in full in the repository::

    <!-- gen: NAME -->
    ...the table's Markdown as generated...
    <!-- /gen -->

(``<!-- cli: hubvib ARGS -->`` ... ``<!-- /cli -->`` the same); the docs build replaces
every marker and its block by what the generator gives then, and a marker without a block
(its data not committed yet) is generated at build time as well.  ``python
docs/generate.py --write [PAGE.md ...]`` refills the blocks of the pages (all of
``docs/*.md`` by default); ``tests/docs/test_docs_site.py`` fails when a committed block is not what
its generator gives now, except the tables in ``LIVE`` (measured while the docs are built:
timings) and, outside the slow run, those in ``SLOW``.

Run ``python docs/generate.py NAME`` to print one table.
"""
from __future__ import annotations

import atexit
import contextlib
import csv
import hashlib
import io
import json
import math
import os
import re
import shlex
import shutil
import sys
import tempfile
from functools import lru_cache
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "docs" / "data"

# Every entry of docs/data (a file, or a folder "name/") has a meta file
# docs/data/<name>.meta.json: "command", the exact shell commands, run from the repository
# root, that (re)write it (docs/data/regenerate.sh runs them all, in order); "keep", for a
# folder a scene writes, the files kept of its output; "measured", when and on what.
def _data_sources() -> dict[str, str]:
    sources = {}
    for path in sorted(DATA.glob("*.meta.json")):
        name = path.name.removesuffix(".meta.json")
        key = name + "/" if (DATA / name).is_dir() else name
        meta = json.loads(path.read_text())
        keep = f" (then keep {', '.join(meta['keep'])})" if meta.get("keep") else ""
        sources[key] = "; ".join(meta["command"]) + keep
    return sources


#: data entry ("file" or "folder/") -> its regenerating commands, as the provenance line of
#: every table read from it names them
DATA_SOURCES = _data_sources()


def data_entries() -> list[str]:
    """Every entry of docs/data (a file or folder name), each with its meta file."""
    return sorted(p.name.removesuffix(".meta.json") for p in DATA.glob("*.meta.json"))


def command_modules(command: str) -> list[str]:
    """The modules a regenerating command runs: ``hubvib CMD ...`` the CLI and the command's
    module, ``python -m MODULE ...`` that module (each with what it imports)."""
    argv = shlex.split(command)
    if argv[:2] == ["python", "-m"]:
        return [argv[2]]
    if argv[0] == "hubvib":
        return ["hubvib.cli", f"hubvib.commands.{argv[1].replace('-', '_')}"]
    raise ValueError(f"a docs/data command runs hubvib or python -m, not {command!r}")


#: what a command's output is written to (the word after these is not an input)
_OUTPUT_FLAGS = {"--out", ">"}


def command_inputs(command: str) -> list[Path]:
    """The repository files a regenerating command reads besides the code: every shipped
    scene (a command may name one, or read its default scene) and each argument that is a
    file of the repository, the word after ``--out`` or ``>`` left out."""
    argv = shlex.split(command)
    named = {ROOT / word for i, word in enumerate(argv)
             if not (i and argv[i - 1] in _OUTPUT_FLAGS) and (ROOT / word).is_file()}
    return sorted(named | set((ROOT / "scenes").glob("*.toml")))


def data_source_key(entry: str) -> str:
    """The source key (``hubvib.foundation.source_graph``) of every hubvib module the
    entry's commands import, hashed with the bytes of every input file they read
    (:func:`command_inputs`): what its "source_key" must be for the data to be current."""
    from hubvib.foundation.source_graph import source_key

    commands = _meta(entry)["command"]
    modules = sorted({m for c in commands for m in command_modules(c)})
    digest = hashlib.sha256(source_key(*modules).encode())
    for path in sorted({p for c in commands for p in command_inputs(c)}):
        digest.update(str(path.relative_to(ROOT)).encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


#: docs/data entries the docs build does not hold to a source key, each with the reason (what
#: its page says under every block read from it); every other entry must carry one
UNKEYED_EXEMPT = {
    "benchmark.json": "its figures are timings of the machine that ran the benchmark, not "
                      "outputs the code reproduces: a rerun measures anew rather than checks, "
                      "so no source key could say they are current",
}


def stale_data() -> list[str]:
    """The docs/data entries whose meta file's "source_key" is not the current source's
    (recorded by ``python docs/generate.py --record-source ENTRY`` after its commands ran,
    as ``docs/data/regenerate.sh`` does): each written by other code than the one now.
    An entry with no key recorded yet is :func:`unkeyed_data`, not stale."""
    return [entry for entry in data_entries()
            if "source_key" in _meta(entry)
            and _meta(entry)["source_key"] != data_source_key(entry)]


def unkeyed_data() -> list[str]:
    """The docs/data entries with no source key recorded, leaving out those of
    :data:`UNKEYED_EXEMPT`: their age against the code is unknown, so the docs build fails
    on them as on a stale one (``regenerate.sh ENTRY`` keys one)."""
    return [entry for entry in data_entries()
            if "source_key" not in _meta(entry) and entry not in UNKEYED_EXEMPT]


def data_problems() -> list[str]:
    """Why the committed docs/data cannot be trusted as the current code's output, one
    sentence per kind (stale, unkeyed), or nothing: what the docs build fails on."""
    problems = []
    stale = stale_data()
    if stale:
        problems.append(f"docs/data entries written by other code than the current: "
                        f"{', '.join(stale)}")
    unkeyed = unkeyed_data()
    if unkeyed:
        problems.append(f"docs/data entries with no source key (not exempt in "
                        f"docs/generate.py UNKEYED_EXEMPT): {', '.join(unkeyed)}")
    if problems:
        problems.append(f"regenerate with docs/data/regenerate.sh {' '.join(stale + unkeyed)} "
                        f"(or docs/data/regenerate.sh --stale)")
    return problems


def stale_or_unkeyed() -> list[str]:
    """Every entry :func:`stale_data` or :func:`unkeyed_data` names, and every entry whose
    commands read the files of one of those (:func:`readers_of`: rerunning it rewrites
    their input), sorted: what ``docs/data/regenerate.sh --stale`` reruns."""
    return sorted(readers_of(set(stale_data()) | set(unkeyed_data())))


def readers_of(entries: set[str]) -> set[str]:
    """``entries`` and, transitively, every docs/data entry whose commands read a file of
    one of them (an input of :func:`command_inputs` inside ``docs/data/<entry>``)."""
    found = set(entries)
    while True:
        written = {(DATA / e).resolve() for e in found}
        more = {e for e in data_entries() if e not in found
                and any(_inside(path.resolve(), written)
                        for c in _meta(e)["command"] for path in command_inputs(c))}
        if not more:
            return found
        found |= more


def _inside(path: Path, places: set[Path]) -> bool:
    return path in places or any(p in places for p in path.parents)


def record_source(entries: list[str]) -> None:
    """Write the current source key into the meta files of ``entries`` (just regenerated)."""
    for entry in entries:
        path = DATA / f"{entry}.meta.json"
        meta = json.loads(path.read_text())
        meta["source_key"] = data_source_key(entry)
        path.write_text(json.dumps(meta, indent=1) + "\n")
        print(f"recorded: {path.name}")


# ---------------------------------------------------------------- helpers

def markdown_table(header: list[str], rows: list[list], align: str | None = None) -> str:
    """A Markdown table; ``align`` is one character per column, ``l`` or ``r``."""
    align = align or "l" * len(header)
    rule = ["---:" if a == "r" else "---" for a in align]
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join(rule) + "|"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def provenance(name: str, measured: str | None = None) -> str:
    """The source line under a table read from ``docs/data/name``: when it ran and the
    commands that regenerate it (more than three: the script that runs them)."""
    when = f", measured {measured}" if measured else ""
    command = DATA_SOURCES[name]
    how = f"`{command}`"
    if command.count("; ") >= 3:
        entry = name.rstrip("/")
        how = (f"`docs/data/regenerate.sh {entry}` (the {command.count('; ') + 1} "
               f"commands of `docs/data/{entry}.meta.json`)")
    return f"\n\n*Source: `docs/data/{name}`{when}; regenerate with {how}.*"


def _meta(name: str) -> dict:
    path = DATA / f"{name.rstrip('/')}.meta.json"
    return json.loads(path.read_text()) if path.exists() else {}


def _small(value: float, digits: int = 3) -> str:
    """``0`` for round-off (|x| < 1e-12), else ``digits`` significant digits."""
    return "0" if abs(value) < 1e-12 else f"{value:.{digits}g}"


def _g(value: float, digits: int = 4) -> str:
    return f"{value:.{digits}g}"


# ---------------------------------------------------------------- lumped model

def lumped_spectrum() -> str:
    """The energy-consistent spectrum of the Raba 118/76 preset, with the c_ru shift and
    the relative sensitivity of every mode."""
    from hubvib import lumped
    from hubvib.reducer import lumped_preset

    params = lumped_preset("raba118")
    spectrum = lumped.natural_modes(params)
    shift = lumped.frequency_shift(params, "c_ru", 1e5)
    sens = lumped.frequency_sensitivity(params, "c_ru")
    rows = [[i + 1, spectrum.kind[i], spectrum.multiplicity[i], f"{w:.2f}",
             f"{w / (2 * math.pi):.2f}", f"{shift.percent[i]:+.2f}", _small(sens.relative[i])]
            for i, w in enumerate(spectrum.omega)]
    return markdown_table(["mode", "type", "multiplicity", "ω [rad/s]", "f [Hz]",
                           "shift, c_ru 1e6 → 1e5 N/m [%]", "(dω/ω)/(dk/k) for c_ru"],
                          rows, "rlrrrrr")


def raba_validation() -> str:
    """Published spectrum against the printed (indefinite) matrix and the energy model."""
    from hubvib.reducer import lumped_preset
    from hubvib.validation.raba118 import validate

    rows = [[r["mode"], f"{r['published_rad_s']:.0f}",
             f"{r['printed_rad_s']:.1f}" + (" (λ<0)" if r["printed_lambda_sign"] == "-" else ""),
             f"{r['printed_vs_published_percent']:+.3f}", r["kind"], f"{r['energy_rad_s']:.1f}"]
            for r in validate(lumped_preset("raba118")).rows]
    return markdown_table(["#", "published [rad/s]", "printed matrix", "deviation [%]", "type",
                           "energy model"], rows, "rrrrlr")


def raba_claim() -> str:
    """What the comparison with the published Raba 118/76 spectrum shows, in words with its
    numbers (the study reports' validation-status sentence)."""
    from hubvib.reports.validation_status import lumped_model_status

    return lumped_model_status() + "."


def raba_summary() -> str:
    """The headline figures of ``hubvib validate raba118``."""
    from hubvib.reducer import lumped_preset
    from hubvib.validation.raba118 import PUBLISHED_TOLERANCE, validate

    result = validate(lumped_preset("raba118"))
    negative = ", ".join(f"{v:.4g}" for v in result.negative_eigenvalues)
    rows = [
        ["largest deviation, printed matrix against the published values",
         f"{100 * result.printed_max_deviation:.3f} % (tolerance {100 * PUBLISHED_TOLERANCE:g} %)"],
        ["negative eigenvalues of the printed matrix [rad²/s²]",
         f"{len(result.negative_eigenvalues)}: {negative}"],
        ["ω₁ at c_ru = 1e5 N/m over ω₁ at 1e6 N/m (lowered by a factor)",
         f"{result.fig4_ratio_first:.3g} ({1 / result.fig4_ratio_first:.3g}×)"],
        ["ω₂ at c_ru = 1e5 N/m over ω₂ at 1e6 N/m (lowered by a factor)",
         f"{result.fig4_ratio_second:.3g} ({1 / result.fig4_ratio_second:.3g}×)"],
        ["theory checks passed", f"{sum(c.passed for c in result.theory)} of {len(result.theory)}"],
    ]
    return markdown_table(["figure", "value"], rows, "lr")


def stability() -> str:
    """Error against the 50-digit mpmath reference per case and solver, and the time of
    the default solver, measured while the docs are built."""
    from hubvib.reducer import lumped_preset
    from hubvib.validation.stability import run

    rows = [r for r in run(lumped_preset("raba118"), repeats=5)
            if not math.isnan(r.max_error)]
    methods = list(dict.fromkeys(r.method for r in rows))
    cases = list(dict.fromkeys(r.case for r in rows))
    by = {(r.case, r.method): r for r in rows}
    out = [[case] + [f"{by[case, m].max_error:.1e}" for m in methods]
           + [f"{1e3 * by[case, methods[0]].seconds:.2f}"] for case in cases]
    header = ["case"] + [f"{m}{' (default)' if i == 0 else ''}" for i, m in enumerate(methods)]
    return markdown_table(header + [f"time, {methods[0]} [ms]"], out,
                          "l" + "r" * (len(methods) + 1)) + (
        "\n\n*Computed while these docs were built (`hubvib.validation.stability.run`); the "
        "times are medians of 5 calls on the build machine.*")


def batch() -> str:
    """The batched solve of the worked example in *Crack detection*."""
    from hubvib import lumped
    from hubvib.reducer import lumped_preset
    from hubvib.lumped.batch import batch_frequencies

    values = np.geomspace(1e5, 1e7, 10_000)
    params = lumped_preset("raba118")
    result = batch_frequencies(params, {"c_ru": values})
    exact = [lumped.natural_modes(params.replace(c_ru=v)).omega[0] / (2 * math.pi)
             for v in values[[0, -1]]]
    rows = [[f"{v:.0e}", f"{b:.2f}", f"{e:.2f}"]
            for v, b, e in zip(values[[0, -1]], result.frequency_hz[[0, -1], 0], exact)]
    return markdown_table(["c_ru [N/m]", "mode 1, batch [Hz]", "mode 1, natural_modes [Hz]"],
                          rows, "rrr")


# ---------------------------------------------------------------- design and detection

def design_file() -> str:
    """The example design file ``docs/data/inputs/demo.toml``, as the commands read it."""
    return f"```toml\n{(DATA / 'inputs' / 'demo.toml').read_text().rstrip()}\n```"


def series_mounting() -> str:
    """The paper's soft mounting in series with the FE ring body (the example's numbers)."""
    from hubvib.detection.series import identify_mount, series

    body = _stiffness()["intact"]["c_ru"]["value_N_m"]
    cracked = body * (1 + _stiffness_change("c_ru"))
    mount = identify_mount(1e6, body)
    rows = [["FE ring body c_ru, intact / 10 mm crack [N/m]", f"{body:.4g} / {cracked:.4g}"],
            ["mounting identified so that the total is 1e6 [N/m]", f"{mount:.6g}"],
            ["change of the total c_ru with the 10 mm crack",
             f"{series(mount, cracked) / series(mount, body) - 1:.2g}"],
            ["change of the ring body's c_ru", f"{cracked / body - 1:.3g}"]]
    return markdown_table(["figure", "value"], rows, "lr") + provenance(
        "stiffness_10mm.json", _meta("stiffness_10mm.json").get("measured"))


# ---------------------------------------------------------------- files written by commands

@lru_cache(maxsize=None)
def _benchmark() -> dict:
    return json.loads((DATA / "benchmark.json").read_text())


def _benchmark_note() -> str:
    meta = _meta("benchmark.json")
    return (provenance("benchmark.json", meta.get("measured"))
            + (f" *{meta['machine']}.*" if "machine" in meta else "")
            + f" *Not checked against the code like the other generated figures: "
              f"{UNKEYED_EXEMPT['benchmark.json']}.*")


#: what a table cell says for a figure the committed benchmark run does not hold (a run of
#: an older hubvib, ``--quick``, or a figure that failed)
NOT_MEASURED = "not measured"


class _Figures(dict):
    """The committed benchmark JSON; ``fig(key, fmt)`` formats one figure, or says
    ``NOT_MEASURED`` when the run does not hold it (None or absent)."""

    def fig(self, *keys: str, fmt: str = "{:.2f}") -> str:
        value = self
        for key in keys:
            value = value.get(key) if isinstance(value, dict) else None
        return NOT_MEASURED if value is None else fmt.format(value)


def benchmark_fe() -> str:
    """The FE and lumped speed figures of the committed ``hubvib benchmark`` run."""
    b = _Figures(_benchmark())
    lumped = b.get("lumped") or {}
    single = lumped.get("single_seconds_per_point")
    previous_1e4, now_1e4 = b.get("c_ru_2d_1e4_previous_seconds"), b.get("c_ru_2d_1e4_seconds")
    rows = [
        [f"2D c_ru, mesh + FE ({b.fig('c_ru_2d_dofs', fmt='{:,}')} DOFs, error "
         f"{b.fig('c_ru_2d_rel_error', fmt='{:.1e}')} against the "
         f"{b.get('c_ru_2d_reference') or NOT_MEASURED})",
         b.fig("c_ru_2d_previous_seconds", fmt="{:.2f} s"), b.fig("c_ru_2d_seconds", fmt="{:.2f} s"),
         b.fig("c_ru_2d_speedup")],
        ["the same, FE only", "", "", b.fig("c_ru_2d_fe_speedup")],
        [f"2D work-conjugate c_ru to a verified 1e-4: {b.get('c_ru_2d_1e4_route') or NOT_MEASURED} "
         f"(before: the whole ring's first three levels, "
         f"{b.fig('c_ru_2d_1e4_previous_rel_error', fmt='{:.1e}')} from the reference)",
         b.fig("c_ru_2d_1e4_previous_seconds", fmt="{:.2f} s"),
         b.fig("c_ru_2d_1e4_seconds", fmt="{:.2f} s"),
         f"{previous_1e4 / now_1e4:.3g}" if previous_1e4 and now_1e4 else ""],
        [f"crack case: c_ru, c_r, engaged c_rp, 2 levels (scale "
         f"{b.fig('crack_case_scale', fmt='{:g}')})",
         b.fig("crack_case_previous_seconds", fmt="{:.2f} s"),
         b.fig("crack_case_seconds", fmt="{:.2f} s"), b.fig("crack_case_speedup")],
        ["lumped spectra, batched against one at a time (points/s)",
         NOT_MEASURED if not single else f"{1 / single:.0f}",
         b.fig("lumped", "points_per_second", fmt="{:.0f}"),
         b.fig("lumped", "speedup", fmt="{:.0f}")],
    ]
    skipped = ", ".join(k.removesuffix("_skipped").replace("_", " ") for k in b
                        if k.endswith("_skipped") and b[k])
    return markdown_table(["figure", "before (previous path)", "now", "ratio"], rows, "lrrr") + (
        f"\n\nShared against separate solves differ by "
        f"{b.fig('crack_case_max_rel_difference', fmt='{:.1e}')}; "
        f"the previous 2D path gives the same c_ru to "
        f"{b.fig('c_ru_2d_previous_max_rel_difference', fmt='{:.1e}')}; "
        f"batched against Jacobi: {b.fig('lumped', 'max_relative_difference', fmt='{:.1e}')}. "
        + (f"Not in this run: {skipped}." if skipped else "")
        + _benchmark_note())


def benchmark_full() -> str:
    """The figures only a full ``hubvib benchmark`` measures: the 3D race against CalculiX and
    the previous path, peak memory, the main job fresh and cached, the test command, the 3D
    crack-growth scene; a figure the committed run does not hold says ``NOT_MEASURED``."""
    b = _Figures(_benchmark())

    def row(label, before, now, ratio=None, unit="s"):
        cell = "{:.3g} " + unit
        return [label, b.fig(before, fmt=cell) if before else "", b.fig(now, fmt=cell),
                b.fig(ratio, fmt="{:.3g}") if ratio else ""]

    dofs = f" ({b['solid_dofs']:,} DOFs)" if b.get("solid_dofs") else ""
    fresh, cached = b.get("main_job_fresh_seconds"), b.get("main_job_cached_seconds")
    rows = [
        row(f"3D c_ru: model + loads + solve{dofs}, against the previous path",
            "solid_previous_seconds", "solid_seconds", "solid_previous_speedup"),
        row("3D c_ru: CalculiX 2.20 on the same mesh and loads", "calculix_seconds",
            "solid_seconds", "calculix_speedup"),
        row("peak memory, 3D solve", "solid_solve_peak_memory_gb_previous",
            "solid_solve_peak_memory_gb", "solid_solve_memory_ratio", "GB"),
        row("peak memory, `hubvib stiffness --solid`", None, "solid_peak_memory_gb", None, "GB"),
        row("main job (`hubvib run`): empty cache, then FE cases and renders cached",
            "main_job_fresh_seconds", "main_job_cached_seconds")[:3]
        + [f"{fresh / cached:.3g}" if fresh and cached else ""],
        row("default test command (`python -m pytest`)", None, "tests_seconds"),
        row("3D crack-growth scene (`hubvib run raba118_crack_3d`)", None,
            "crack_growth_3d_seconds"),
    ]
    notes = []
    if b.get("calculix_max_rel_difference") is not None:
        notes.append(f"CalculiX's displacements differ from ours by "
                     f"{b['calculix_max_rel_difference']:.1e} of the largest (its print "
                     f"precision) and its c_ru by {b.fig('calculix_c_ru_rel_difference', fmt='{:.1e}')}.")
    if b.get("tests_summary"):
        notes.append(f"The test command printed: `{b['tests_summary']}`.")
    notes += [f"Skipped: {v}." for k, v in b.items() if k.endswith("_skipped") and v]
    return (markdown_table(["figure", "before (baseline)", "now", "ratio"], rows, "lrrr")
            + ("\n\n" + " ".join(notes) if notes else "") + _benchmark_note())


def benchmark_solid_mesh() -> str:
    """3D Raba ring (P2 tetrahedra) meshing time against element count, from the committed
    full ``hubvib benchmark`` run (``solid_mesh``: ``tables.solid_mesh_table``)."""
    rows = _benchmark().get("solid_mesh")
    if not rows:
        return (f"*3D meshing times: {NOT_MEASURED} in the committed benchmark run (a full "
                "`hubvib benchmark` measures them).*" + _benchmark_note())
    body = [[r["case"], f"{r['tooth_size_mm']:g}", f"{r['elements']:,}", f"{r['nodes_p2']:,}",
             f"{r['seconds']:.3g}"] for r in rows]
    return markdown_table(["3D ring (P2 tetrahedra)", "tooth element size [mm]", "tetrahedra",
                           "nodes", "time [s]"], body, "lrrrr") + _benchmark_note()


SMALL_3D = "raba118_crack_3d_small"


def crack_growth_3d_small() -> str:
    """The committed run of the 3D crack-growth scene cut to three solid cases (the slow
    scene test's): the ring body's c_ru and c_r change, and the cracked tooth's c_rp ratio
    in 3D (used) against the slice method and the plane crack through the width
    (``stiffness_3d.csv`` of the run)."""
    with open(DATA / SMALL_3D / "stiffness_3d.csv", newline="") as handle:
        grid = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(handle)]
    rows = []
    for r in grid[1:]:
        rows.append([f"{r['depth_mm']:g}", f"{r['half_length_mm']:g}",
                     f"{r['c_ru_change_percent']:+.3f} ± {r['c_ru_change_error_percent']:.3f} "
                     f"({r['c_ru_change_poor_cells_percent']:+.2f})",
                     f"{r['plane_through_c_ru_change_percent']:+.3f}",
                     f"{r['c_r_change_percent']:+.3f} ± {r['c_r_change_error_percent']:.3f}",
                     f"{r['c_rp_3d_ratio']:.4f} ± {r['c_rp_3d_ratio_error']:.4f}",
                     f"{r['c_rp_slice_ratio']:.4f}", f"{r['plane_through_c_rp_ratio']:.4f}",
                     f"{r['dofs']:,.0f}"])
    return markdown_table(
        ["depth [mm]", "half-length [mm]", "c_ru change [%] ± (½ poor)",
         "plane through: c_ru change [%]", "c_r change [%] ±", "c_rp ratio, 3D (used) ±",
         "c_rp ratio, slices", "c_rp ratio, plane through", "DOFs (half width)"], rows,
        "rrrrrrrrr") + (
        f"\n\nIntact solid ring: c_ru {_g(grid[0]['c_ru_N_m'])} ± "
        f"{_g(grid[0]['c_ru_error_N_m'], 2)} N/m, c_r {_g(grid[0]['c_r_N_m'])} ± "
        f"{_g(grid[0]['c_r_error_N_m'], 2)} N/m (rim parts)." + provenance(f"{SMALL_3D}/"))


def benchmark_crack_growth_3d() -> str:
    """The run time of the 3D crack-growth scene in the committed benchmark run."""
    seconds = _benchmark().get("crack_growth_3d_seconds")
    told = (f"took {seconds / 60:.3g} minutes" if seconds is not None
            else f"run time: {NOT_MEASURED}")
    return f"*`hubvib run raba118_crack_3d` {told} in the committed `hubvib benchmark` run.*" + (
        _benchmark_note())


def benchmark_signal() -> str:
    """Cost and accuracy of the ways to compute the sensor signal."""
    s = _benchmark()["signal"]
    rows = [
        ["periodic steady state, one revolution, record extended (what `hubvib signal` does)",
         f"{s['periodic_s']:.2f}", f"{100 * s['newmark_error']:.2g} %"],
        ["the same, at a quarter of the step", f"{s['periodic_quarter_step_s']:.2f}",
         f"{100 * s['periodic_quarter_step_error']:.2g} %"],
        [f"average acceleration, all {s['revolutions']} revolutions marched",
         f"{s['newmark_s']:.2f}", f"{100 * s['newmark_error']:.2g} % (the same steady state)"],
        [f"`scipy.integrate.solve_ivp` {s['solve_ivp_method']}, rtol {s['solve_ivp_rtol']:g} "
         f"({s['solve_ivp_evaluations']:,} right-hand-side evaluations)",
         f"{s['solve_ivp_s']:.2f}", f"{100 * s['solve_ivp_error']:.2g} %"],
    ]
    return markdown_table(["way", "time [s]", "error of the sensor signal"], rows, "lrr") + (
        f"\n\n{s['revolutions']} carrier revolutions, {s['steps_per_revolution']:,} steps per "
        f"revolution (h = {s['time_step_s']:.3g} s), recorded at {s['sample_rate_hz']:g} Hz "
        f"({s['samples_per_mesh_period']:.1f} samples per mesh period); errors relative to the "
        "largest signal value, against the Richardson extrapolation of the h and h/2 steady "
        "states." + _benchmark_note())


@lru_cache(maxsize=None)
def _stiffness() -> dict:
    return json.loads((DATA / "stiffness_10mm.json").read_text())["cases"]


def _stiffness_change(name: str) -> float:
    """Relative change of ``c_ru`` or ``c_r`` with the 10 mm crack of the committed run."""
    cases = _stiffness()
    return cases["crack 0.01 m"][name]["value_N_m"] / cases["intact"][name]["value_N_m"] - 1


def stiffness() -> str:
    """``hubvib stiffness --crack-depth 10e-3 --json``: every stiffness of the intact ring with
    its error, range over the cycle and independent checks; then the crack's changes."""
    intact = _stiffness()["intact"]
    rows = []
    for name in ("c_ru", "c_r", "c_sp", "c_rp"):
        q = intact[name]
        spread = (f"{q['min_N_m']:.3g}..{q['max_N_m']:.3g}" if "min_N_m" in q else "")
        if "contact_ratio" in q:
            spread += f" (ε = {q['contact_ratio']:.3g})"
        check = ""
        if "analytic_N_m" in q:
            check = (f"analytical {q['analytic_N_m']:.3g} ({q['value_N_m'] / q['analytic_N_m'] - 1:+.0%}); "
                     f"ISO 6336-1 c_γα b {q['iso_c_gamma_N_m']:.3g} "
                     f"({q['value_N_m'] / q['iso_c_gamma_N_m'] - 1:+.0%}"
                     f"{'' if q['iso_in_range'] else ', shifts outside ISO fitted range'})")
        rows.append([f"`{name}`", f"{q['value_N_m']:.4g}",
                     f"{100 * q['error_N_m'] / q['value_N_m']:.2g} %", spread, check])
        if "root_land_N_m" in q:
            rows.append([f"`{name}` root-land reading (secondary)", f"{q['root_land_N_m']:.4g}",
                         f"{100 * q['root_land_error_N_m'] / q['root_land_N_m']:.2g} %", "", ""])
    for name in ("c_p", "c_c"):
        q = intact[name]
        rows.append([f"`{name}`", f"{q['tangent_N_m']:.3g} tangent, {q['secant_N_m']:.3g} secant",
                     "formula", f"at {q['load_N'] / 1e3:.3g} kN", f"{q['rollers']} rollers"])
    table = markdown_table(["", "value [N/m]", "±", "over the cycle / load", "independent check"],
                           rows, "lrrll")
    cracked = _stiffness()["crack 0.01 m"]
    rp = cracked["c_rp"]
    changes = [
        ["`c_ru` (mean over carrier positions)", f"{_stiffness_change('c_ru'):+.2%}"],
        ["`c_r`", f"{_stiffness_change('c_r'):+.2%}"],
        ["`c_ru` root-land reading",
         f"{cracked['c_ru']['root_land_N_m'] / intact['c_ru']['root_land_N_m'] - 1:+.2%}"],
        ["highest `c_ru` over carrier positions",
         f"{cracked['c_ru']['max_N_m'] / intact['c_ru']['max_N_m'] - 1:+.2%}"],
        ["`c_rp` over the cracked tooth's contact and one base pitch either side, mean",
         f"{rp['engaged_N_m'] / rp['engaged_intact_N_m'] - 1:+.2%}"],
        ["`c_rp` over the cracked tooth's contact and one base pitch either side, minimum",
         f"{rp['engaged_min_N_m'] / rp['engaged_intact_min_N_m'] - 1:+.2%}"],
    ]
    return (table + "\n\nWhat a 10 mm root crack changes:\n\n"
            + markdown_table(["stiffness", "change"], changes, "lr")
            + provenance("stiffness_10mm.json", _meta("stiffness_10mm.json").get("measured")))


def _convergence_rows(path: Path) -> list[list]:
    import csv

    with path.open(newline="") as handle:
        rows = list(csv.DictReader(handle))
    return [[f"{float(r['scale']):.3g}", f"{int(float(r['dofs'])):,}",
             f"{float(r['seconds_total']):.2f}", f"{float(r['value']):.6g}",
             f"{float(r['relative_error']):.2g}" if float(r["relative_error"]) else "(reference)"]
            for r in rows]


def _convergence(path: Path) -> str:
    return markdown_table(["scale", "DOFs", "mesh + assembly + solve [s]", "value",
                           "relative error"], _convergence_rows(path), "rrrrr")


def _live_convergence(quantity: str, reference: str) -> str:
    from hubvib.validation.convergence import run_study

    folder = Path(tempfile.mkdtemp(prefix="hubvib-docs-conv-"))
    try:
        table = run_study(quantity, folder, progress=lambda *args: None)
        return _convergence(table) + (
            f"\n\n*Computed while these docs were built (`hubvib convergence {quantity}`); "
            f"the reference is {reference}.*")
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def convergence_annulus() -> str:
    """``hubvib convergence annulus``, run while the docs are built (a few seconds): curved P2
    against the exact k_theta [N m/rad] of the annulus in torsion."""
    return _live_convergence("annulus", "the exact solution")


def convergence_edge_crack() -> str:
    """``hubvib convergence edge_crack``, run while the docs are built (seconds): the
    compliance of the edge-cracked strip."""
    return _live_convergence("edge_crack", "the Brown-Srawley handbook integral (the fit "
                             "itself holds to 2e-3)")


def convergence_c_ru() -> str:
    """``hubvib convergence c_ru`` from its committed table [N/m]."""
    return _convergence(DATA / "convergence" / "convergence_c_ru.csv") + provenance(
        "convergence/", _meta("convergence").get("measured"))


def convergence_work() -> str:
    """``hubvib convergence`` of the work-conjugate c_ru, c_r and the rim part on the
    nested levels, from the committed tables [N/m]: value, observed order per triple and
    how the reference was obtained (``validation.convergence.study_note``)."""
    from hubvib.validation.convergence import study_note

    parts = []
    for quantity in ("c_ru_work", "c_r_work", "c_ru_rim", "c_ru_sector", "c_r_sector"):
        path = DATA / "convergence_work" / f"convergence_{quantity}.csv"
        with path.open(newline="") as handle:
            orders = [r.get("observed_order", "") for r in csv.DictReader(handle)]
        rows = [row + [f"{float(o):.2f}" if o and math.isfinite(float(o)) else ""]
                for row, o in zip(_convergence_rows(path), orders)]
        note = study_note(quantity, path).splitlines()[0]
        parts.append(f"`{quantity}` ({note}):\n\n" + markdown_table(
            ["relative size", "DOFs", "mesh + assembly + solve [s]", "value [N/m]",
             "relative error", "observed order"], rows, "rrrrrr"))
    return "\n\n".join(parts) + provenance("convergence_work/",
                                           _meta("convergence_work").get("measured"))


def meshing_2d() -> str:
    """2D Raba ring meshing time against element count, intact and cracked, measured while
    the docs are built (``hubvib.benchmarks.tables.mesh_table``)."""
    from hubvib.benchmarks.tables import mesh_table

    rows = [[r["case"], f"{r['tooth_size_mm']:g}", f"{r['elements']:,}", f"{r['nodes_p2']:,}",
             f"{r['seconds']:.2f}"] for r in mesh_table()]
    return markdown_table(["2D ring (P2)", "tooth element size [mm]", "triangles", "nodes",
                           "time [s]"], rows, "lrrrr") + (
        "\n\n*Measured while these docs were built (one gmsh thread); times follow the "
        "build machine's load.*")


def report_section(folder: str, heading: str) -> str:
    """One ``## heading`` section of the ``report.md`` a scene wrote into ``docs/data/folder``
    (the report's text is generated from the run's data), without its pictures."""
    report = (DATA / folder / "report.md").read_text()
    marker = f"\n## {heading}\n"
    if marker not in report:
        raise KeyError(f"docs/data/{folder}/report.md has no section {heading!r}")
    body = report.split(marker, 1)[1].split("\n## ", 1)[0]
    body = body.split("\n### Plots\n", 1)[0]
    body = "\n".join(line for line in body.splitlines() if not line.startswith("!["))
    run = json.loads((DATA / folder / "results.json").read_text())
    when = (f"{run['date']}, hubvib {run['hubvib_version']}" if "date" in run
            else _meta(folder).get("measured"))
    return body.strip() + provenance(f"{folder}/", when)


def signal_report() -> str:
    """The vibration signature of the shipped signal scene (``hubvib signal``)."""
    return report_section("raba118_signal", "Vibration signature")


def crack_study_short_answer() -> str:
    """The short answer of the default scene (``hubvib run``)."""
    return report_section("raba118_crack", "Short answer")


def crack_study_detectability() -> str:
    """Smallest detectable depth against the mounting stiffness, default scene."""
    return report_section("raba118_crack", "Detectability against the ring mounting")


def crack_study_threshold() -> str:
    """The detection threshold and the POD set-up of the default scene."""
    return report_section("raba118_crack", "Detection threshold and probability of detection")


def crack_study_carrier() -> str:
    """When the cracked tooth is in mesh and what a record sees, default scene."""
    return report_section("raba118_crack", "Carrier position")


def crack_study_stiffness() -> str:
    """FE stiffness against crack depth of the default scene."""
    return report_section("raba118_crack", "FE stiffness against crack depth")


def ring_definitions() -> str:
    """The ring body's c_ru and c_r of both Raba crack scenes per depth, as the lumped model
    uses them (work-conjugate rim parts) and as the root lands read them, each with its
    relative change against the intact ring, from the committed runs' ``results.json``."""
    parts = []
    for folder, name in (("raba118_crack", "radial crack (default scene)"),
                         ("raba118_crack_path", "crack along the predicted path")):
        rows_in = json.loads((DATA / folder / "results.json").read_text())["stiffness"]
        intact = rows_in[0]
        rows = []
        for r in rows_in:
            change = {k: 100 * (r[k] / intact[k] - 1) for k in
                      ("fe_c_ru_N_m", "fe_c_ru_root_land_N_m", "fe_c_r_N_m",
                       "fe_c_r_root_land_N_m")}
            rows.append([f"{r['depth_mm']:.4g}", _g(r["fe_c_ru_N_m"]),
                         f"{change['fe_c_ru_N_m']:+.3f}", _g(r["fe_c_ru_root_land_N_m"]),
                         f"{change['fe_c_ru_root_land_N_m']:+.3f}", _g(r["fe_c_r_N_m"]),
                         f"{change['fe_c_r_N_m']:+.3f}", _g(r["fe_c_r_root_land_N_m"]),
                         f"{change['fe_c_r_root_land_N_m']:+.3f}"])
        parts.append(f"{name}:\n\n" + markdown_table(
            ["depth [mm]", "c_ru rim [N/m]", "change [%]", "c_ru root land [N/m]",
             "change [%]", "c_r rim [N/m]", "change [%]", "c_r root land [N/m]",
             "change [%]"], rows, "rrrrrrrrr") + provenance(f"{folder}/"))
    return "\n\n".join(parts)


def fe_substructure() -> str:
    """The plane crack cases by substructures against the figures the whole-ring path
    published (the default scene): old, new, the old error bar and the distance in old
    error bars, from the committed comparison."""
    data = json.loads((DATA / "fe_substructure.json").read_text())
    names = {"c_ru_N_m": "c_ru [N/m]", "c_r_N_m": "c_r [N/m]",
             "c_rp_engaged_ratio": "c_rp ratio [-]"}
    rows = [[f"{r['depth_mm']:.4g}", names[r["quantity"]], _g(r["old"], 7), _g(r["new"], 7),
             _g(r["old_error"], 3), _g(r["new_error"], 3),
             "-" if r["in_old_errors"] is None else f"{r['in_old_errors']:.2f}"]
            for r in data["rows"]]
    return markdown_table(["depth [mm]", "quantity", "old (whole ring)", "new (pieces)",
                           "old error", "new error", "change in old errors"], rows,
                          "rlrrrrr") + provenance("fe_substructure.json")


# ---------------------------------------------------------------- signal route (issue 24)

#: the committed ``hubvib signal`` runs of the detection page: the shipped scene and its
#: variants (scene files in ``docs/data/inputs/signal/``)
SIGNAL_RUNS = ("raba118_signal", "raba118_signal_planet_error", "raba118_signal_noise0.5",
               "raba118_signal_noise2")
INDICATOR_NAMES = {"rms": "RMS", "crest_factor": "crest factor", "kurtosis": "kurtosis",
                   "fm0": "FM0", "fm4": "FM4", "na4": "NA4", "nb4": "NB4", "m6a": "M6A",
                   "m8a": "M8A", "er": "ER", "ser": "SER"}


@lru_cache(maxsize=None)
def _signal_run(folder: str) -> dict:
    return json.loads((DATA / folder / "results.json").read_text())


def _signal_case(run: dict) -> str:
    """What sets a run apart: its noise and its manufacturing errors."""
    o = run["options"]
    errors = [f"{1e6 * e:g} um on planet {i + 1}"
              for i, e in enumerate(o["planet_position_errors_m"]) if e]
    shipped = " (shipped scene)" if run["scene"] == SIGNAL_RUNS[0] else ""
    return ", ".join([f"{o['noise_level']:g}{shipped}"] + errors)


def _signal_provenance(folders) -> str:
    return "".join(provenance(f"{folder}/", _meta(folder).get("measured")) for folder in folders)


def _first_depths(roc: dict) -> str:
    """Indicators grouped by the first depth with POD >= 0.9 (``first_depth_seen_mm``)."""
    by_depth: dict = {}
    for key, name in INDICATOR_NAMES.items():
        by_depth.setdefault(roc["indicators"][key]["first_depth_seen_mm"], []).append(name)
    deepest = max(roc["depth_mm"])
    parts = [f"{', '.join(names)} {depth:g} mm" for depth, names in
             sorted((d, n) for d, n in by_depth.items() if d is not None)]
    if None in by_depth:
        if len(by_depth) == 1:
            auc = max(ind["auc"][-1] for ind in roc["indicators"].values())
            return f"none by {deepest:g} mm (AUC at {deepest:g} mm <= {auc:.2f})"
        parts.append(f"{', '.join(by_depth[None])} not by {deepest:g} mm")
    return "; ".join(parts)


def signal_detection_rates() -> str:
    """Family-wise false alarms and the first depth each indicator detects (POD >= 0.9)
    of the shipped signal scene and its variants (other noise, a planet position error),
    with the false-alarm rates of the same thresholds under coloured and heavy-tailed
    noise (``roc`` of each run's ``results.json``)."""
    rows = []
    for folder in SIGNAL_RUNS:
        run = _signal_run(folder)
        roc, o = run["roc"], run["options"]
        rows.append([_signal_case(run), ", ".join(f"{d:g}" for d in roc["depth_mm"]),
                     f"{roc['family_false_alarm_measured']:.2f} ± "
                     f"{roc['family_false_alarm_standard_error']:.2f}",
                     f"{roc['family_false_alarm_coloured']:.2f}",
                     f"{roc['family_false_alarm_heavy_tail']:.2f}", _first_depths(roc)])
    run = _signal_run(SIGNAL_RUNS[0])
    o, roc = run["options"], run["roc"]
    header = ["noise (x intact RMS), errors", "depths [mm]",
              "family-wise false alarms (measured)", "same thresholds, coloured noise",
              "same thresholds, heavy-tailed noise", "first depth with POD >= 0.9"]
    return (markdown_table(header, rows, "llrrrl")
            + f"\n\nEvery run: FE curves, {o['sun_speed_rpm']:g} min^-1, "
            f"{o['sun_torque_N_m']:g} N m, {o['revolutions']:g} revolutions, "
            f"{roc['records_per_depth']} records per depth, {roc['training_records']} "
            f"training records, alpha = {roc['false_alarm_rate']:g}; coloured: "
            f"{roc['coloured_noise']}; heavy-tailed: {roc['heavy_tail_noise']}."
            + _signal_provenance(SIGNAL_RUNS))


def _indicator_means(depths: list, keys, at_mm) -> list[str]:
    by = {round(d["depth_mm"], 6): d["indicators"] for d in depths}
    return [" -> ".join(f"{by[d][key]['mean']:.3g}" for d in at_mm if d in by) for key in keys]


SIGNAL_INDICATOR_DEPTHS = (0.0, 3.0, 12.0)


def signal_indicators() -> str:
    """FM4, NA4 and ER (mean over the noise seeds) at 0, 3 and 12 mm, without and with a
    planet position error (``depths`` of the two runs' ``results.json``)."""
    keys = ("fm4", "na4", "er")
    rows = []
    for folder in SIGNAL_RUNS[:2]:
        run = _signal_run(folder)
        rows.append([_signal_case(run)] + _indicator_means(run["depths"], keys,
                                                           SIGNAL_INDICATOR_DEPTHS))
    depths = ", ".join(f"{d:g}" for d in SIGNAL_INDICATOR_DEPTHS)
    return (markdown_table(["noise (x intact RMS), errors"]
                           + [f"{INDICATOR_NAMES[k]} at {depths} mm" for k in keys],
                           rows, "lrrr")
            + f"\n\nMeans over {_signal_run(SIGNAL_RUNS[0])['options']['noise_seeds']} "
            "noise seeds." + _signal_provenance(SIGNAL_RUNS[:2]))


def signal_sensors() -> str:
    """FM4 and NA4 at 0, 3 and 12 mm seen by sensors at other angles from the crack, with
    a planet position error (``sensors`` of the run's ``results.json``)."""
    folder = SIGNAL_RUNS[1]
    run = _signal_run(folder)
    keys = ("fm4", "na4")
    rows = [["0 (the study's sensor)"] + _indicator_means(run["depths"], keys,
                                                          SIGNAL_INDICATOR_DEPTHS)]
    rows += [[f"{sensor['angle_from_crack_deg']:g}"]
             + _indicator_means(sensor["depths"], keys, SIGNAL_INDICATOR_DEPTHS)
             for sensor in run["sensors"]]
    depths = ", ".join(f"{d:g}" for d in SIGNAL_INDICATOR_DEPTHS)
    return (markdown_table(["sensor angle from the crack [deg]"]
                           + [f"{INDICATOR_NAMES[k]} at {depths} mm" for k in keys], rows, "lrr")
            + f"\n\nNoise and errors: {_signal_case(run)}." + _signal_provenance([folder]))


def signal_non_multiple() -> str:
    """Energy share off the multiples of N (smallest and largest over the depths), without
    and with a planet position error (``non_multiple_fraction`` of the runs)."""
    rows = []
    for folder in SIGNAL_RUNS[:2]:
        run = _signal_run(folder)
        values = [r["fraction"] for r in run["non_multiple_fraction"]]
        depths = ", ".join(f"{r['depth_mm']:g}" for r in run["non_multiple_fraction"])
        low, high = f"{min(values):.2g}", f"{max(values):.2g}"
        rows.append([_signal_case(run), depths, low if low == high else f"{low} to {high}"])
    return (markdown_table(["noise (x intact RMS), errors", "depths [mm]",
                            "non-multiple energy share"], rows, "llr")
            + _signal_provenance(SIGNAL_RUNS[:2]))


def signal_contact() -> str:
    """The smallest total-over-static mesh force of the linear model over every mesh and
    depth, where it occurs, and the largest separated share of the revolution, per run
    (``contact`` of each depth)."""
    rows = []
    for folder in SIGNAL_RUNS[:2]:
        run = _signal_run(folder)
        ratio, depth, mesh = min((r, d["depth_mm"], m) for d in run["depths"]
                                 for m, r in d["contact"]["min_force_ratio"].items())
        separated = max(max(d["contact"]["separated_fraction"].values())
                        for d in run["depths"])
        rows.append([_signal_case(run), f"{ratio:.2f}", f"{mesh}, {depth:g} mm",
                     f"{100 * separated:.3g}"])
    o = _signal_run(SIGNAL_RUNS[0])["options"]
    return (markdown_table(["noise (x intact RMS), errors",
                            "smallest total/static mesh force (linear)", "mesh, depth",
                            "largest separated share [% of a revolution]"], rows, "lrlr")
            + f"\n\nSun torque {o['sun_torque_N_m']:g} N m." + _signal_provenance(SIGNAL_RUNS[:2]))


# ---------------------------------------------------------------- seed companions

BALL49_SNIPPET = """\
import math, numpy as np
from hubvib.companion.harmonics import position_locked_periods
deg = {1: 0.20, 2: 0.08, 6: 0.05, 12: 0.12, 294: 0.02}
T = position_locked_periods({k: math.radians(a) for k, a in deg.items()}, 2048, 3, 1500 / 49)
np.savetxt('ball49.csv', T, header='period_s', comments='', fmt='%.15e')
"""


def harmonics_ball49() -> str:
    """The synthetic two-stage ball reducer record of the seed-000 page, written by
    ``BALL49_SNIPPET`` and analysed by ``hubvib harmonics``."""
    def prepare(folder):
        here = Path.cwd()
        os.chdir(folder)
        try:
            exec(compile(BALL49_SNIPPET, "ball49 snippet", "exec"), {})
        finally:
            os.chdir(here)

    snippet = f"```python\n{BALL49_SNIPPET}```\n\n"
    return snippet + console(["hubvib", "harmonics", "--periods", "ball49.csv",
                              "--pulses-per-rev", "2048", "--z1", "1", "--z2", "6",
                              "--stages", "2", "--top", "6"], prepare=prepare)


# ---------------------------------------------------------------- diagnosis (issue 22)

def diagnosis_identification_scatter() -> str:
    """Frequencies identified from simulated records: Monte Carlo against the bound of the
    shipped method and Au's law."""
    text = (DATA / "diagnosis" / "identification_scatter.md").read_text().strip()
    return text + provenance("diagnosis/")


def diagnosis_check() -> str:
    """Verdict rates, interval coverage and the impossible patterns of ``hubvib diagnose``
    on errors drawn from a heavier-tailed distribution than the diagnosis assumes."""
    text = (DATA / "diagnosis" / "diagnosis_check.md").read_text().strip()
    return text + provenance("diagnosis/")


def diagnosis_check_elastic() -> str:
    """``diagnosis_check`` on the elastic ring's watched coupled modes of the default scene
    (its command names them by number: checked against the default run's labels)."""
    text = (DATA / "diagnosis" / "diagnosis_check_elastic.md").read_text().strip()
    watched = _default_run()["elastic_ring"]["watched_labels"]
    if f"modes {'; '.join(watched)}," not in text.splitlines()[0]:
        raise ValueError(f"docs/data/diagnosis/diagnosis_check_elastic.md is not of the "
                         f"default scene's watched coupled modes {watched}: rerun its command "
                         "with their numbers (results.json elastic_ring.watched_modes)")
    return text + provenance("diagnosis/")


def diagnosis_family_pod() -> str:
    """Family POD of the watched modes per depth and record length, default scene, with
    and without drift between the records (``pod_family.csv`` of ``hubvib run``)."""
    import csv

    with open(DATA / "raba118_crack" / "pod_family.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    records = sorted({float(r["record_s"]) for r in rows})
    depths = sorted({float(r["depth_mm"]) for r in rows})
    cell = {(float(r["depth_mm"]), float(r["record_s"])): r for r in rows}
    header = ["depth [mm]"] + [f"{T:g} s: no drift / drift / compensated" for T in records]
    body = [[f"{d:g}"] + [" / ".join(f"{float(cell[d, T][k]):.3f}" for k in
                                    ("pod", "pod_with_drift", "pod_drift_compensated"))
                          for T in records] for d in depths]
    run = json.loads((DATA / "raba118_crack" / "results.json").read_text())
    return (markdown_table(header, body, "r" * len(header))
            + provenance("raba118_crack/", f"{run['date']}, hubvib {run['hubvib_version']}"))


def diagnosis_figures() -> str:
    """The figures the diagnosis page's text quotes, from the default scene's run
    (``results.json`` of ``hubvib run raba118_crack``): each watched mode's intact
    frequency, identification scatter of one record and time-averaged shift at 3 mm and
    the deepest crack (series method), and its drift per kelvin and per 0.1 % of mesh
    stiffness (``hubvib.detection.drift.drift_model`` on the preset)."""
    from types import SimpleNamespace

    from hubvib.reducer import lumped_preset
    from hubvib.detection.drift import drift_model

    run = json.loads((DATA / "raba118_crack" / "results.json").read_text())
    options = run["detection"]["options"]
    modes = {m["mode"]: m for m in run["modes"]}
    shifts = {(round(r["depth_mm"], 6), r["mode"]): r["record_shift_series_hz"]
              for r in run["c_rp_methods"]}
    deepest = max(d for d, _ in shifts)
    frequency = [m["frequency_intact_hz"] for m in run["modes"]]
    drift = drift_model(lumped_preset("raba118"), frequency, SimpleNamespace(
        modulus_per_K=options["modulus_per_K"], expansion_per_K=options["expansion_per_K"],
        temperature_std=1.0, mesh_load_std=0.0))
    rows = [[k, f"{modes[k]['frequency_intact_hz']:.1f}", f"{modes[k]['sigma_hz']:.2f}",
             f"{shifts[3.0, k]:+.2f}", f"{shifts[deepest, k]:+.2f}",
             f"{drift.per_kelvin_hz[k - 1]:+.2f}", f"{1e-3 * drift.per_load_hz[k - 1]:+.2f}"]
            for k in run["detection"]["watched_modes"]]
    header = ["mode", "intact [Hz]",
              f"sigma of one {options['record_length']:g} s record [Hz]",
              "shift at 3 mm [Hz]", f"shift at {deepest:.3g} mm [Hz]", "per K [Hz]",
              "per 0.1 % of mesh stiffness [Hz]"]
    return (markdown_table(header, rows, "rrrrrrr")
            + f"\n\nDamping {options['damping_ratio']:g}, modal SNR {options['snr']:g}."
            + provenance("raba118_crack/", f"{run['date']}, hubvib {run['hubvib_version']}"))


def diagnosis_mode13() -> str:
    """Mode 13 of the default scene: planet 1's lumped c_rp factor by the series and the
    ratio method and the time-averaged shift a record sees, at 3 mm, 12 mm and the deepest
    crack (``results.json`` of ``hubvib run raba118_crack``: stiffness rows, c_rp_methods)."""
    run = json.loads((DATA / "raba118_crack" / "results.json").read_text())
    rows = {round(r["depth_mm"], 6): r for r in run["stiffness"]}
    shifts = {round(r["depth_mm"], 6): r for r in run["c_rp_methods"] if r["mode"] == 13}
    depths = [d for d in (3.0, 12.0, max(rows)) if d in rows]
    body = [[f"{d:.3g}", f"{rows[d]['lumped_c_rp_factor']:.4f}",
             f"{rows[d]['fe_c_rp_engaged_ratio']:.4f}",
             f"{shifts[d]['record_shift_series_hz']:.3g}",
             f"{shifts[d]['record_shift_ratio_hz']:.3g}"] for d in depths]
    return (markdown_table(["depth [mm]", "factor series", "factor ratio",
                            "rigid mode 13 series [Hz]", "rigid mode 13 ratio [Hz]"], body, "rrrrr")
            + provenance("raba118_crack/", f"{run['date']}, hubvib {run['hubvib_version']}"))


# ---------------------------------------------------------------- closed loop, records to depth

@lru_cache(maxsize=None)
def _loop_folder() -> Path:
    """The scratch folder the walk-through's commands share (records written by one, read
    by the next), removed when the build ends."""
    folder = Path(tempfile.mkdtemp(prefix="hubvib-docs-loop-"))
    atexit.register(shutil.rmtree, folder, True)
    return folder


def closed_loop_records() -> str:
    """``hubvib signal raba118_closed_loop``: the scene's records, 45 s each (what it
    prints; the progress lines on stderr are left out)."""
    return console(["hubvib", "signal", "raba118_closed_loop", "--out", "loop"],
                   folder=_loop_folder(), stderr=False)


def closed_loop_diagnosis() -> str:
    """``hubvib diagnose`` of the closed-loop scene's 12 mm record against its intact one."""
    table("closed_loop_records")  # the records, once per build
    return console(["hubvib", "diagnose", "--scene", "raba118_closed_loop", "--record",
                    "loop/signal_12mm.csv", "--baseline-record", "loop/signal_0mm.csv"],
                   folder=_loop_folder(), stderr=False)


def closed_loop_not_identifiable() -> str:
    """The shipped signal scene's records (10 revolutions, no ambient forcing) through the
    same command: the verdict ``not identifiable from these records``."""
    console(["hubvib", "signal", "raba118_signal", "--out", "short"], folder=_loop_folder())
    return console(["hubvib", "diagnose", "--scene", "raba118_signal", "--record",
                    "short/signal_12mm.csv", "--baseline-record", "short/signal_0mm.csv"],
                   folder=_loop_folder(), stderr=False)


# ---------------------------------------------------------------- key references

def command_flags() -> str:
    """Every command with every flag and its help, from the parser the CLI runs (so the
    reference cannot drift from it)."""
    import argparse

    from hubvib.cli import _parser

    parts = []
    for name, parser in _parser()._subparsers._group_actions[0].choices.items():
        rows = []
        for action in parser._actions:
            if isinstance(action, argparse._HelpAction):
                continue
            if isinstance(action, argparse._SubParsersAction):
                for sub, subparser in action.choices.items():
                    rows.append([f"`{sub}`", (subparser.description or "").replace("|", "\\|")
                                 or "subcommand"])
                continue
            label = ", ".join(action.option_strings) or action.dest
            if action.metavar and action.option_strings:
                label += f" {action.metavar if isinstance(action.metavar, str) else ' '.join(action.metavar)}"
            elif action.choices and not action.option_strings:
                label += f" ({', '.join(map(str, action.choices))})"
            text = " ".join((action.help or "").split()).replace("|", "\\|") or (
                "print the result as JSON" if "--json" in action.option_strings else "")
            if action.choices and action.option_strings:
                text += f" (one of {', '.join(map(str, action.choices))})"
            rows.append([f"`{label}`".replace("|", "\\|"), text])
        parts.append(f"**`hubvib {name}`**\n\n" + markdown_table(["argument", "meaning"], rows))
    return "\n\n".join(parts)



def _schema_tables(schemas) -> str:
    """One Markdown table per schema: key, default, allowed, unit, meaning, read from the
    same fields the parser checks (``hubvib.foundation.schema``)."""
    parts = []
    for schema in schemas:
        title = schema.table if schema.table.startswith("design") else f"[{schema.table}]"
        parts.append(f"**`{title}`**\n\n" + markdown_table(
            ["key", "default", "allowed", "unit", "meaning"], schema.rows()))
    return "\n\n".join(parts)


def scene_keys() -> str:
    """Every key of every scene table with its default and allowed range, generated from the
    schemas the scene parser checks (so the reference cannot drift from the parser)."""
    from hubvib.detection.options import SCHEMA as DETECTION
    from hubvib.elastic.options import SCHEMA as ELASTIC
    from hubvib.runtime.engines import SCHEMA as EXECUTION
    from hubvib.signal.options import SCHEMA as SIGNAL
    from hubvib.studies.crack_table import SCHEMA as CRACK
    from hubvib.studies.scene import OUTPUT, REDUCER, STUDY

    return _schema_tables((REDUCER, STUDY, OUTPUT, CRACK, DETECTION, SIGNAL, EXECUTION,
                           ELASTIC))


def design_keys() -> str:
    """Every key of a design file with its default and allowed range, from the schemas
    ``hubvib.design.parse`` checks."""
    from hubvib.design.parse import SCHEMAS

    return _schema_tables(SCHEMAS)


# ---------------------------------------------------------------- crack path (issue 23)

def _crack_path_run(name: str) -> dict:
    return json.loads((DATA / "crack_path" / f"{name}.json").read_text())


CRACK_PATH_RUNS = (("worst position (single-contact point)", "tooth0"),
                   ("envelope over the mesh cycle", "tooth0_envelope"))


def crack_path_default() -> str:
    """The LEFM path of the default scene's crack (Raba 118/76, tooth 0) under the worst
    load position and under the envelope over the mesh cycle (``hubvib crack-path``)."""
    from hubvib.reducer.stages import ring_gear
    from hubvib.design.presets import raba118

    root = ring_gear(raba118()).profile.root_radius
    rows = []
    for label, name in CRACK_PATH_RUNS:
        run = _crack_path_run(name)
        radii = np.hypot(*np.asarray(run["path_m"]).T)
        x, y = run["exit_m"]
        fracture = run["fracture"] + ("" if run["severed"] else " (not severed)")
        drivers = sorted({round(1e3 * r, 2) for r in run.get("step_load_radius_m", [])})
        rows.append([label, run["steps"], fracture, f"{1e3 * run['depth_m'][-1]:.4g}",
                     f"({1e3 * x:.2f}, {1e3 * y:.2f})", f"{run['kink_angle_deg'][0]:.1f}",
                     f"{run['k_i_mpa_sqrt_m'][0]:.2f} .. {run['k_i_mpa_sqrt_m'][-1]:.1f}",
                     f"{1e3 * (radii.max() - root):.2f}",
                     ", ".join(f"{r:g}" for r in drivers) if drivers
                     else f"{1e3 * run['load_radius_m']:.2f}"])
    header = ["load", "FE solutions", "fracture", "last crack [mm along the path]",
              "exit (x, y) [mm]", "first kink [deg]", "K_I first .. last [MPa m^0.5]",
              "deepest tip below the root circle [mm]", "load radius driving the steps [mm]"]
    run = _crack_path_run("tooth0")
    return (markdown_table(header, rows, "lrlrrrrrr")
            + f"\n\nBackup ratio {run['backup_ratio']:.2f} (rim {1e3 * run['rim_thickness_m']:.2f}"
            f" mm, tooth height {1e3 * run['tooth_height_m']:.2f} mm), mesh force "
            f"{run['force_N']:.0f} N, steps of {1e3 * run['step_m']:g} mm."
            + provenance("crack_path/", _meta("crack_path/").get("measured")))


def crack_path_steps() -> str:
    """Every step of the default scene's crack path (worst load position)."""
    run = _crack_path_run("tooth0")
    tips = run["path_m"][1:]
    rows = [[i, f"{1e3 * d:.1f}", f"{1e3 * tips[i][0]:.3f}", f"{1e3 * tips[i][1]:.3f}",
             f"{k1:.3f}", f"{k2:.3f}", f"{kink:.2f}"]
            for i, (d, k1, k2, kink) in enumerate(zip(run["depth_m"], run["k_i_mpa_sqrt_m"],
                                                      run["k_ii_mpa_sqrt_m"],
                                                      run["kink_angle_deg"]))]
    header = ["step", "depth [mm]", "tip x [mm]", "tip y [mm]", "K_I [MPa m^0.5]",
              "K_II [MPa m^0.5]", "kink [deg]"]
    return (markdown_table(header, rows, "rrrrrrr")
            + provenance("crack_path/", _meta("crack_path/").get("measured")))


def _backup_ratio_runs() -> dict[tuple[int, float], dict]:
    """(tooth, backup ratio) -> the ``hubvib crack-path --json`` run of that Raba variant
    (``crack_path_backup_ratio/``; the Raba ring itself at tooth 0 from ``crack_path/``)."""
    runs = [json.loads(path.read_text())
            for path in sorted((DATA / "crack_path_backup_ratio").glob("*.json"))]
    runs.append(_crack_path_run("tooth0"))
    return {(run["tooth"], round(run["backup_ratio"], 6)): run for run in runs}


def crack_path_backup_ratio() -> str:
    """What the crack severs, tooth or rim, against the backup ratio m_B (rim below the root
    circle over the tooth height) of Raba variants, midway between two support pads (tooth
    5) and over a pad (tooth 0), with the transition each row shows."""
    runs = _backup_ratio_runs()
    ratios = sorted({ratio for _, ratio in runs})
    raba = max(ratios)  # the preset's own rim, thicker than every variant
    teeth = {5: "midway between pads", 0: "over a pad"}

    def cell(run):
        return "" if run is None else run["fracture"] + ("" if run["severed"] else
                                                            " (not severed)")

    rows = [[f"tooth {tooth}, {where}"] + [cell(runs.get((tooth, r))) for r in ratios]
            for tooth, where in teeth.items()]
    header = ["backup ratio m_B"] + [f"{r:.4g}" + (" (Raba)" if r == raba else "")
                                     for r in ratios]
    notes = []
    for tooth in teeth:
        found = sorted((r, run["fracture"]) for (t, r), run in runs.items()
                       if t == tooth and run["severed"])
        rim = [r for r, f in found if f == "rim"]
        tooth_ = [r for r, f in found if f == "tooth"]
        if rim and tooth_ and max(rim) < min(tooth_):
            notes.append(f"tooth {tooth}: rim fracture up to m_B = {max(rim):.4g}, tooth "
                         f"fracture from {min(tooth_):.4g}")
        elif not rim:
            notes.append(f"tooth {tooth}: tooth fracture at every ratio run, down to "
                         f"m_B = {min(tooth_):.4g}")
        else:
            notes.append(f"tooth {tooth}: rim and tooth fracture alternate: {found}")
    height = runs[5, raba]["tooth_height_m"]
    return (markdown_table(header, rows, "l" * len(header))
            + f"\n\nTooth height {1e3 * height:.4g} mm; {'; '.join(notes)}. The default mesh "
            f"and step of `hubvib crack-path` ({1e3 * runs[5, raba]['step_m']:g} mm)."
            + provenance("crack_path_backup_ratio/",
                         _meta("crack_path_backup_ratio").get("measured"))
            + provenance("crack_path/", _meta("crack_path").get("measured")))


def _scene_rows(folder: str) -> tuple[dict, dict]:
    run = json.loads((DATA / folder / "results.json").read_text())
    return run, {round(r["depth_mm"], 6): r for r in run["stiffness"]}


def crack_path_fe() -> str:
    """The FE quantities of the default scene's radial crack against the same lengths along
    the predicted path (``hubvib run raba118_crack`` and ``raba118_crack_path``): ring
    body c_ru, c_r over their intact values, the cracked tooth's engaged c_rp ratio (mean
    and minimum over the mesh cycle)."""
    radial_run, radial = _scene_rows("raba118_crack")
    path_run, path = _scene_rows("raba118_crack_path")

    def cells(rows, depth):
        if depth not in rows:
            return ["-"] * 4
        row, intact = rows[depth], rows[0.0]
        return [f"{row['fe_c_ru_N_m'] / intact['fe_c_ru_N_m']:.4f}",
                f"{row['fe_c_r_N_m'] / intact['fe_c_r_N_m']:.4f}",
                f"{row['fe_c_rp_engaged_ratio']:.3f}", f"{row['fe_c_rp_engaged_min_ratio']:.3f}"]

    body = []
    for depth in sorted(d for d in path if d > 0):
        p, r = cells(path, depth), cells(radial, depth)
        body.append([f"{depth:g}"] + [f"{a} / {b}" for a, b in zip(p, r)])
    header = ["length along the path [mm]", "c_ru predicted / radial", "c_r predicted / radial",
              "c_rp mean predicted / radial", "c_rp min predicted / radial"]
    return (markdown_table(header, body, "rrrrr")
            + provenance("raba118_crack_path/", f"{path_run['date']}, hubvib "
                         f"{path_run['hubvib_version']}")
            + provenance("raba118_crack/", f"{radial_run['date']}, hubvib "
                         f"{radial_run['hubvib_version']}"))


def crack_path_detection() -> str:
    """Family POD of the watched modes per depth and record length, the default scene's
    radial crack against the predicted path (``results.json`` of the two runs)."""
    rows = []
    for label, folder in (("radial", "raba118_crack"), ("predicted", "raba118_crack_path")):
        run = json.loads((DATA / folder / "results.json").read_text())
        pod = run["detection"]["family_pod"]
        records = sorted(pod, key=float)
        for k, depth in enumerate(run["crack"]["depths"]):
            if depth > 0:
                rows.append([label, f"{1e3 * depth:.3g}"]
                            + [f"{pod[T][k]:.3f}" for T in records]
                            + [", ".join(str(m) for m in run["detection"]["watched_modes"])])
    header = ["path", "depth [mm]"] + [f"POD, {float(T):g} s records" for T in records] + [
        "watched modes"]
    return (markdown_table(header, rows, "lrrrrl")
            + provenance("raba118_crack_path/") + provenance("raba118_crack/"))


def crack_path_short_answer() -> str:
    """The short answer of the scene whose crack follows the predicted path."""
    return report_section("raba118_crack_path", "Short answer")


# ---------------------------------------------------------------- elastic ring

def _elastic() -> dict:
    return json.loads((DATA / "elastic_ring.json").read_text())


def _families(modes: list[dict]) -> dict[int, list[float]]:
    out: dict[int, list[float]] = {}
    for m in modes:
        if m["frequency_hz"] >= 1.0:  # a free ring's rigid-body modes are no family
            out.setdefault(m["nodal_diameter"], []).append(m["frequency_hz"])
    return out


def elastic_ring_families() -> str:
    """The ring's own in-plane modes per nodal-diameter family: free, on the design's
    foundation and clamped on the pads (no planets)."""
    data = _elastic()
    parts = []
    for name, d in data["designs"].items():
        rows = []
        fam = {k: _families(d[f"families_{k}"]) for k in ("free", "mounted", "clamped")}
        for n in sorted(set().union(*[set(f) for f in fam.values()])):
            if n == 1:
                continue
            cells = [" / ".join(f"{f:.1f}" for f in fam[k].get(n, [])[:2]) or "-"
                     for k in ("free", "mounted", "clamped")]
            rows.append([str(n) + (" (breathing)" if n == 0 else ""), *cells])
        f = d["foundation_N_m2"]
        parts.append(f"**{name}** (foundation k_n = {f['normal']:.4g}, k_t = "
                     f"{f['tangential']:.4g} N/m^2, sized to the design's c_r and c_ru)\n\n"
                     + markdown_table(["nodal diameters n", "free [Hz]", "on the foundation [Hz]",
                                       "clamped on the pads [Hz]"], rows, "lrrr"))
    return "\n\n".join(parts) + "\n\nModes of one family below the band's cut-off, the two "\
        "members of a pair where the mounting splits it; n = 0 at low frequency on the " \
        "foundation is the ring's rigid motion on it, not breathing." + provenance(
            "elastic_ring.json", data["measured"])


def elastic_ring_changes() -> str:
    """The coupled modes with a strong ring part (ring share >= 0.3) and their change by the
    crack, faces open, closed and the bilinear estimate, on two mesh levels."""
    data = _elastic()
    parts = []
    for name, d in data["designs"].items():
        rows = []
        intact = {r["mode"]: r for r in d["coarse"]["intact"]}
        for depth_c, depth_f in zip(d["coarse"]["depths_mm"], d["fine"]["depths_mm"]):
            fine = {r["mode"]: r for r in depth_f["modes"]}
            for r in depth_c["modes"]:
                info = intact[r["mode"]]
                if info["ring_share"] < 0.3 or r["open_hz"] is None:
                    continue
                f = fine.get(r["mode"])
                d_open = r["open_hz"] - r["intact_hz"]
                d_open_f = (f["open_hz"] - f["intact_hz"]) if f and f["open_hz"] else None
                error = "-" if d_open_f is None else f"{abs(d_open - d_open_f):.1f}"
                rows.append([f"{depth_c['depth_mm']:g}", r["mode"], info["class"],
                             info["nodal_diameter"], f"{r['intact_hz']:.1f}", f"{d_open:+.1f}",
                             f"{r['closed_hz'] - r['intact_hz']:+.2f}",
                             f"{r['bilinear_hz'] - r['intact_hz']:+.1f}", error,
                             "split pair" if r["open_split_pair"] else ""])
        parts.append(f"**{name}** ({d['coarse']['dofs']} ring DOFs; the finer level "
                     f"{d['fine']['dofs']}; ring-planet spring without the ring "
                     f"{d['k_rest_N_m']:.4g} N/m)\n\n" + markdown_table(
                         ["depth [mm]", "mode", "class", "n", "intact [Hz]", "open [Hz]",
                          "closed [Hz]", "bilinear [Hz]", "mesh error [Hz]", ""], rows,
                         "rrlrrrrrrl"))
    return "\n\n".join(parts) + (
        "\n\nChanges from the intact coupled mode each cracked mode tracks (planet 1 on the "
        "cracked tooth). Mesh error: the open change's difference between the two mesh "
        "levels (element sizes / sqrt 2). The detection uses the open crack (an upper "
        "bound of the change); a breathing crack gives about the bilinear value.") + \
        provenance("elastic_ring.json", data["measured"])


def elastic_ring_validity() -> str:
    """The lowest elastic ring mode on the mounting and the computed band where the
    rigid-ring model holds, per design."""
    from hubvib.elastic.validity import validity_table

    data = _elastic()
    return validity_table({name: d["validity"] for name, d in data["designs"].items()}) + \
        provenance("elastic_ring.json", data["measured"])


def _default_run() -> dict:
    return json.loads((DATA / "raba118_crack" / "results.json").read_text())


def elastic_crack_state() -> str:
    """The default scene's loaded crack over one planet pitch, per depth."""
    run = _default_run()
    states = run["elastic_ring"]["crack_state"] or []
    rows = [[f"{1e3 * s['depth_m']:.3g}", f"{100 * s['open_share']:.0f} %",
             f"{1e3 * s['max_open_length_m']:.2f}", f"{1e6 * s['max_gap_m']:.2f}"]
            for s in states]
    torque = states[0]["torque_N_m"] if states else float("nan")
    return (markdown_table(["depth [mm]", "positions with faces apart",
                            "largest open length [mm]", "largest gap [um]"], rows, "rrrr")
            + f"\n\nThe Raba ring under {torque:g} N m at the sun, closure gap 0, planet 1 "
            "on each ring tooth of one planet pitch in turn (frictionless Signorini contact "
            "on the crack faces of the FE ring)." + provenance("raba118_crack/", f"{run['date']}, hubvib {run['hubvib_version']}"))


def elastic_record_changes() -> str:
    """The default scene's watched coupled modes: the change a record sees (loaded crack)
    against the open crack half a pitch away, with the instantaneous range, per depth."""
    run = _default_run()
    elastic = run["elastic_ring"]
    modes = [elastic["modes"][m - 1] for m in elastic["watched_modes"]]
    rows = []
    for k, depth in enumerate(elastic["depths_mm"]):
        if depth == 0:
            continue
        for m in modes:
            record = m["record"][k] or {}
            low, high = record.get("instantaneous_min_hz"), record.get("instantaneous_max_hz")
            cells = [m["shift_record_hz"][k], m["shift_open_hz"][k]]
            rows.append([f"{depth:.3g}", m["label"]] + [
                "-" if x is None else f"{x:+.1f}" for x in cells] + [
                "-" if low is None else f"{low:.0f} .. {high:.0f}",
                record.get("regime") or "-"])
    return (markdown_table(["depth [mm]", "mode", "record change [Hz]", "open change [Hz]",
                            "instantaneous range [Hz]", "record"], rows, "rlrrrl")
            + "\n\nRecord change: what a record identifies over many planet passes with the "
            "crack under the working load, against the intact ring treated the same way; "
            "open change: the faces held open with planet 1 half a planet pitch away; "
            "instantaneous range: the stuck faces' frequency over the pitch; record: averaged "
            "(swing inside the half-power band), mixture (one peak off the mean) or split."
            + provenance("raba118_crack/", f"{run['date']}, hubvib {run['hubvib_version']}"))


def elastic_load_sensitivity() -> str:
    """The default scene's smallest detectable depth per closure gap and torque."""
    run = _default_run()
    variants = run["load_sensitivity"] or []
    lengths = sorted({t for v in variants for t in v["answer"]}, key=float)
    rows = [[f"{1e6 * v['closure_gap_m']:g}",
             "any" if v["closure_gap_m"] == 0 else f"{100 * v['torque_fraction']:g} %"]
            + [v["answer"][t] for t in lengths] for v in variants]
    return (markdown_table(["closure gap [um]", "torque"] + [f"{t} s records" for t in lengths],
                           rows, "rr" + "l" * len(lengths))
            + "\n\nWhere the nominal reducer's family POD (identification noise only) crosses "
            "0.9 on the default scene's depths (those the sweep added included)."
            + provenance("raba118_crack/", f"{run['date']}, hubvib {run['hubvib_version']}"))


def elastic_identification() -> str:
    """The intact Raba reducer's coupled modes identified from elastic-ring records of
    several seeds: their scatter against the Cramer-Rao bound and Au's law."""
    from hubvib.signal.elastic_scatter import scatter_table

    data = json.loads((DATA / "elastic_identification.json").read_text())
    return scatter_table(data) + provenance("elastic_identification.json")



def record_loop() -> str:
    """The elastic ring's closed loop from records (``hubvib.studies.record_loop``): per
    true depth the verdicts and the intervals that hold it, the coverage and the false
    alarms with their binomial intervals."""
    from hubvib.studies.record_loop import loop_table

    data = json.loads((DATA / "record_loop.json").read_text())
    return loop_table(data) + provenance("record_loop.json")


def elastic_floquet_change() -> str:
    """The crack's change of the coupled modes: the mean-stiffness eigen model the detection
    uses against the Floquet modes over the mesh cycle that a running record shows
    (``hubvib.studies.floquet_change``), with the default scene's watched modes marked; the
    build fails when they are not the modes the default scene's report watches."""
    data = json.loads((DATA / "floquet_change.json").read_text())
    watched = _default_run()["elastic_ring"]["watched_modes"]
    marked = [row["mode"] for row in data["modes"] if row["watched"]]
    if sorted(marked) != sorted(watched):
        raise ValueError(f"floquet_change.json watches modes {marked}, the default scene's "
                         f"report {watched}: rerun its command with --watched "
                         + ",".join(map(str, watched)))
    depths = data["depths_mm"][1:]

    def hz(x, digits=2):
        return "-" if x is None else f"{x:.{digits}f}"

    rows = []
    for row in data["modes"]:
        rows.append([f"{row['mode']}{' *' if row['watched'] else ''}",
                     hz(row["eigen_hz"][0], 1),
                     hz(row["floquet_hz"][0], 1) if row["unique_branch"] else "no branch"]
                    + [f"{hz(e)} / {hz(f) if row['unique_branch'] else '-'}"
                       for e, f in zip(row["eigen_change_hz"][1:], row["floquet_change_hz"][1:])]
                    + [hz(row["sigma_hz"])])
    header = (["mode", "eigen intact [Hz]", "Floquet intact [Hz]"]
              + [f"change at {d:g} mm, eigen / Floquet [Hz]" for d in depths]
              + [f"sigma at {data['record_length_s']:g} s [Hz]"])
    return (markdown_table(header, rows, "l" + "r" * (len(header) - 1))
            + f"\n\nFaces open; planet 1 at carrier position {data['carrier_position']} (the "
            f"diagnosis's); mesh frequency {data['mesh_hz']:.1f} Hz. * a mode the default "
            "scene's report watches; \"no branch\": the mode's Floquet exponent meets another "
            "mode's on the way from the eigen model to the running reducer, so it has no change "
            "of its own."
            + provenance("floquet_change.json"))

# ---------------------------------------------------------------- entry points

#: markers whose text changes from run to run: tables measured while the docs are built
#: (times of the build machine) and a command whose zero shifts print with the sign of
#: their round-off; their committed block is the last run's, never compared
LIVE = frozenset({"stability", "meshing_2d", "convergence_annulus", "convergence_edge_crack",
                  "hubvib run raba118_five_planets --out out"})
#: markers whose generation takes seconds or minutes (a table name, or a ``cli`` marker's
#: command): compared with their committed block in the slow test run only
SLOW = frozenset({"batch", "harmonics_ball49", "closed_loop_records", "closed_loop_diagnosis",
                  "closed_loop_not_identifiable"})

#: a generated-figure marker and, when committed, its block up to ``<!-- /gen -->`` (or
#: ``<!-- /cli -->``); a block holds no other marker
BLOCK = re.compile(r"<!--[ \t]*(gen|cli):[ \t]*([^\n]*?)[ \t]*-->"
                   r"(?:\n((?:(?!<!--[ \t]*(?:gen|cli):).)*?)\n?<!--[ \t]*/\1[ \t]*-->)?",
                   re.S)

TABLES = {name: function for name, function in list(globals().items())
          if callable(function) and not name.startswith("_") and function.__module__ == __name__
          and name not in {"markdown_table", "provenance", "table", "console", "render",
                           "expand", "fill", "blocks", "stale", "write_pages", "data_entries",
                           "command_modules", "data_source_key", "stale_data", "unkeyed_data",
                           "record_source", "data_problems", "stale_or_unkeyed"}}


@lru_cache(maxsize=None)
def table(name: str) -> str:
    """The Markdown of generated table ``name`` (a ``KeyError`` names the known ones)."""
    if name not in TABLES:
        raise KeyError(f"no generated table {name!r}; known: {', '.join(sorted(TABLES))}")
    return TABLES[name]()


def console(argv: list[str], expected: int = 0, prepare=None, folder: Path | None = None,
            stderr: bool = True) -> str:
    """``hubvib ARGS`` run in-process in a scratch folder holding ``docs/data/inputs``; a
    console block with the command and what it printed (stdout, then stderr unless
    ``stderr`` is false: the progress lines with their times).
    ``prepare(folder)``, when given, writes further input files first; ``folder``: run in
    this folder instead, kept for the next command."""
    from hubvib.cli import main

    if not argv or argv[0] != "hubvib":
        raise ValueError(f"a cli marker runs hubvib, not {argv[:1]}")
    out, err = io.StringIO(), io.StringIO()
    keep = folder is not None
    folder = folder or Path(tempfile.mkdtemp(prefix="hubvib-docs-cli-"))
    here, columns = Path.cwd(), os.environ.get("COLUMNS")
    try:
        shutil.copytree(DATA / "inputs", folder, dirs_exist_ok=True)
        if prepare:
            prepare(folder)
        os.chdir(folder)
        os.environ["COLUMNS"] = "100"  # argparse's help wraps to it: the same on every machine
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code = main(argv[1:])
            except SystemExit as stop:  # argparse's --help and usage errors exit
                code = stop.code if isinstance(stop.code, int) else 2
    finally:
        if columns is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = columns
        os.chdir(here)
        if not keep:
            shutil.rmtree(folder, ignore_errors=True)
    if code != expected:
        raise RuntimeError(f"exit {code}, expected {expected}: {err.getvalue().strip()}")
    text = (out.getvalue() + (err.getvalue() if stderr else "")).rstrip()
    return f"```console\n$ {shlex.join(argv)}\n{text}\n```"


def render(kind: str, body: str) -> str:
    """What one marker generates: ``gen`` the table ``body``, ``cli`` the console block of
    the command ``body`` (``hubvib ARGS [; exit=N]``)."""
    if kind == "gen":
        return table(body)
    command, _, expected = body.partition(";")
    expected = int(expected.split("=")[1]) if expected.strip() else 0
    return console(shlex.split(command), expected)


def blocks(markdown: str) -> list[tuple[str, str, str | None]]:
    """Every marker of a page: (kind, body, committed block or None)."""
    return [(m.group(1), m.group(2), m.group(3)) for m in BLOCK.finditer(markdown)]


def expand(markdown: str, generate=render) -> str:
    """The page as the site shows it: each marker and its committed block replaced by what
    ``generate(kind, body)`` gives now."""
    return BLOCK.sub(lambda m: generate(m.group(1), m.group(2)), markdown)


def fill(markdown: str, generate=render) -> str:
    """The page as committed: each marker followed by its generated block and end marker.
    A marker whose data is not committed (the generator raises FileNotFoundError) keeps
    its block, or stays without one."""
    def one(match):
        kind, body = match.group(1), match.group(2)
        try:
            text = generate(kind, body)
        except FileNotFoundError:
            return match.group(0)
        return f"<!-- {kind}: {body} -->\n{text.rstrip()}\n<!-- /{kind} -->"

    return BLOCK.sub(one, markdown)


def stale(markdown: str, generate=render, skip=frozenset()) -> list[str]:
    """The markers of a page whose committed block is not what ``generate`` gives now
    (``kind: body``), leaving out markers without a block and those whose body is in
    ``skip``."""
    return [f"{kind}: {body}" for kind, body, block in blocks(markdown)
            if block is not None and body not in skip
            and block.rstrip() != generate(kind, body).rstrip()]


def write_pages(pages: list[Path]) -> None:
    """Refill the committed blocks of ``pages``."""
    for page in pages:
        text = page.read_text(encoding="utf-8")
        filled = fill(text)
        if filled != text:
            page.write_text(filled, encoding="utf-8")
            print(f"written: {page}")


if __name__ == "__main__":
    if sys.argv[1:2] == ["--stale"]:
        print("\n".join(stale_or_unkeyed()))
    elif sys.argv[1:2] == ["--record-source"]:
        record_source(sys.argv[2:] or data_entries())
    elif sys.argv[1:2] == ["--write"]:
        here = Path(__file__).resolve().parent
        write_pages([Path(p) for p in sys.argv[2:]] or sorted(here.glob("*.md")))
    else:
        for name in sys.argv[1:] or sorted(TABLES):
            print(f"## {name}\n\n{table(name)}\n")
