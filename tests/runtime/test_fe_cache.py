"""The FE cache (hubvib.runtime.fe_cache) as used by a crack sweep: faults are detected, never trusted.

The FE stage is replaced by a synthetic ``fe_case`` (monkeypatched; the sweep runs with
``workers = 1``, in this process), so each test takes well under a second.  Every
fault is injected into one entry of a three-depth sweep; the run
must recompute exactly that case, say so in one line on stderr, and return the
recomputed value, never the stored one.
"""
from __future__ import annotations

import json
import math
import multiprocessing
import os
import subprocess
import sys
import time
from dataclasses import asdict, replace
from pathlib import Path

import pytest

import hubvib.cases.runner as crack_sweep
import hubvib.runtime.fe_cache as fe_cache
from hubvib.cases.runner import POSITIVE_KEYS, case_inputs, run_fe_cases
from hubvib.cases.sweep import CrackSweep
from hubvib.design.presets import hub4, raba118
from hubvib.foundation.source_graph import source_key
from hubvib.runtime.fe_cache import CacheEntryError, CacheFolderError, entry_key
from hubvib.meshing.crack import Crack

DEPTHS = (0.0, 0.002, 0.004)
#: synthetic intact stiffnesses [N/m], of the order of the FE values (c_ru 1.1e10 rim part,
#: 1.7e10 root land: docs/data/raba118_crack)
C_RU0, C_R0 = 1.66e10, 3.1e10


def synthetic(depth: float) -> dict:
    """A plausible FE result for ``depth`` [m]: every key of ``fe_case``'s result, SI.

    The stiffness falls linearly with the depth (10 % per mm), so a result taken from
    the wrong depth's entry shows up as a wrong number.
    """
    factor = 1.0 - 100.0 * depth
    ratio = 1.0 - 50.0 * depth  # exactly 1 when intact, as fe_case gives it
    return {"c_ru_N_m": C_RU0 * factor, "c_ru_error_N_m": 1e-3 * C_RU0,
            "c_ru_min_N_m": 0.99 * C_RU0 * factor, "c_ru_max_N_m": 1.01 * C_RU0 * factor,
            "c_r_N_m": C_R0 * factor, "c_r_error_N_m": 1e-3 * C_R0, "dofs": 12345,
            "solver": "synthetic", "seconds_mesh": 0.01, "seconds_fe": 0.02,
            "seconds_total": 0.03, "depth_m": float(depth), "c_rp_engaged_ratio": ratio,
            "c_rp_engaged_ratio_error": 1e-4, "c_rp_engaged_min_ratio": 1.0 - 80.0 * depth,
            "c_rp_engaged_intact_N_m": 1.48e9, "c_rp_engaged_intact_min_N_m": 1.2e9,
            "c_rp_engaged_intact_window_N_m": 1.55e9, "c_ru_root_land_N_m": 1.5 * C_RU0 * factor,
            "c_r_root_land_N_m": 1.01 * C_R0 * factor, "c_ru_root_land_error_N_m": 2e-3 * C_RU0,
            "c_r_root_land_error_N_m": 1e-3 * C_R0}


@pytest.fixture
def fake(tmp_path, monkeypatch):
    """The cache in ``tmp_path``, ``fe_case`` synthetic; yields the list of computed depths."""
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    computed = []

    def fe_case(sweep, depth):
        computed.append(depth)
        return synthetic(depth)

    monkeypatch.setattr(crack_sweep, "fe_case", fe_case)
    return computed


def make_sweep(**changes) -> CrackSweep:
    return replace(CrackSweep(DEPTHS, accuracy="fast", workers=1, design=hub4()), **changes)


def entry_path(sweep: CrackSweep, depth: float) -> Path:
    key = entry_key(case_inputs(sweep, depth), modules=crack_sweep.SOURCE)
    return crack_sweep.cache_folder() / f"{key}.json"


def notices(stderr: str) -> list[str]:
    return [line for line in stderr.splitlines() if line.startswith("hubvib: cache entry")]


def test_synthetic_result_passes_the_plausibility_check():
    """The fake must itself be a valid result, or every fault test below is vacuous."""
    for depth in DEPTHS:
        crack_sweep.check_case(depth)(synthetic(depth))
    assert set(POSITIVE_KEYS) <= set(synthetic(0.0))


def test_good_entries_are_reused_and_store_their_inputs(fake, capsys):
    sweep = make_sweep()
    first, computed = run_fe_cases(sweep, progress=False)
    assert computed == 3 and sorted(fake) == list(DEPTHS)
    assert first == [synthetic(d) for d in DEPTHS]
    again, computed = run_fe_cases(sweep, progress=False)
    assert computed == 0 and len(fake) == 3, "a good entry is reused, 0 computed"
    assert again == first
    assert notices(capsys.readouterr().err) == []

    data = json.loads(entry_path(sweep, 0.002).read_text())
    inputs = data["inputs"]
    assert inputs["design"] == json.loads(json.dumps(hub4().fingerprint()))
    assert inputs["crack"] == asdict(Crack(tooth=0, depth=0.002, angle=0.0, start="root"))
    assert inputs["scale"] == crack_sweep.ACCURACY["fast"] == 2.0
    assert data["result"] == synthetic(0.002)
    assert data["source"] == source_key(*crack_sweep.SOURCE)
    assert len(data["checksum"]) == 64


def _resign(data: dict) -> None:
    """Give an edited entry a valid checksum (a buggy writer, not a damaged file)."""
    data["checksum"] = fe_cache._checksum(data["inputs"], data["result"], data["source"])


def _edit_result(change, resign: bool):
    def fault(path: Path) -> None:
        data = json.loads(path.read_text())
        change(data["result"])
        if resign:
            _resign(data)
        path.write_text(json.dumps(data, allow_nan=True))
    return fault


def _halve_c_ru(result):
    result["c_ru_N_m"] /= 2


def _set(key, value):
    def change(result):
        result[key] = value
    return change


def _drop(key):
    def change(result):
        del result[key]
    return change


def _write(text: str):
    def fault(path: Path) -> None:
        path.write_text(text)
    return fault


def _truncate(path: Path) -> None:
    text = path.read_bytes()
    path.write_bytes(text[: len(text) // 2])


def _binary(path: Path) -> None:
    path.write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff\xfe" + bytes(range(256)))


def _set_top(key, value):
    def fault(path: Path) -> None:
        data = json.loads(path.read_text())
        data[key] = value
        path.write_text(json.dumps(data))
    return fault


def _drop_top(key):
    def fault(path: Path) -> None:
        data = json.loads(path.read_text())
        del data[key]
        path.write_text(json.dumps(data))
    return fault


def _schema_1_entry(path: Path) -> None:
    """An entry as schema 1 wrote it: no absolute intact c_rp, validly
    signed, ``schema`` 1."""
    data = json.loads(path.read_text())
    for key in ("c_rp_engaged_intact_N_m", "c_rp_engaged_intact_min_N_m"):
        del data["result"][key]
    data["schema"] = 1
    _resign(data)
    path.write_text(json.dumps(data))


#: fault name -> (edit of the entry file, words the one-line notice must contain)
FAULTS = {
    # Entries of the schema before the intact c_rp are recomputed
    "schema 1 entry (no intact c_rp)": (_schema_1_entry, "another version"),
    "result missing the intact c_rp": (
        _edit_result(_drop("c_rp_engaged_intact_N_m"), resign=True), "c_rp_engaged_intact_N_m"),
    "c_ru halved": (_edit_result(_halve_c_ru, resign=False), "checksum"),
    # still inside c_ru's own min..max: only the checksum can tell
    "c_ru edited by 0.1 %": (_edit_result(lambda r: r.update(c_ru_N_m=0.999 * r["c_ru_N_m"]),
                                          resign=False), "checksum"),
    "truncated": (_truncate, "JSON"),
    "empty": (_write(""), "JSON"),
    "JSON list": (_write("[1, 2, 3]"), "not a hubvib FE cache entry"),
    "JSON null": (_write("null"), "not a hubvib FE cache entry"),
    "JSON string": (_write('"c_ru_N_m"'), "not a hubvib FE cache entry"),
    "foreign JSON object": (_write('{"c_ru_N_m": 1.66e10}'), "not a hubvib FE cache entry"),
    "foreign binary file": (_binary, "unreadable"),
    "no checksum": (_drop_top("checksum"), "checksum"),
    "no inputs": (_drop_top("inputs"), "inputs"),
    "result missing a key": (_edit_result(_drop("c_r_N_m"), resign=True), "c_r_N_m"),
    "result emptied": (_edit_result(lambda r: r.clear(), resign=True), "c_ru_N_m"),
    "result a string": (_set_top("result", "1.66e10"), "not a table"),
    "c_ru = 0": (_edit_result(_set("c_ru_N_m", 0.0), resign=True), "c_ru_N_m"),
    "c_ru NaN": (_edit_result(_set("c_ru_N_m", math.nan), resign=False), "non-finite"),
    "c_ru negative": (_edit_result(_set("c_ru_N_m", -C_RU0), resign=True), "c_ru_N_m"),
    "c_ru a string": (_edit_result(_set("c_ru_N_m", "1.66e10"), resign=True), "c_ru_N_m"),
    "c_ru true": (_edit_result(_set("c_ru_N_m", True), resign=True), "c_ru_N_m"),
    "c_ru above its max": (_edit_result(_set("c_ru_N_m", 2 * C_RU0), resign=True), "min..max"),
    "c_rp_engaged_ratio 1e6": (_edit_result(_set("c_rp_engaged_ratio", 1e6), resign=True),
                               "c_rp_engaged_ratio"),
    "depth_m of another case": (_edit_result(_set("depth_m", 0.004), resign=True), "depth_m"),
}


@pytest.mark.parametrize("name", FAULTS)
def test_damaged_entry_is_recomputed_with_one_notice(fake, capsys, name):
    """Each fault -> that case recomputed, a one-line notice, no traceback."""
    fault, words = FAULTS[name]
    sweep = make_sweep()
    run_fe_cases(sweep, progress=False)
    path = entry_path(sweep, 0.002)
    fault(path)
    capsys.readouterr()
    fake.clear()

    results, computed = run_fe_cases(sweep, progress=False)

    assert (computed, fake) == (1, [0.002]), f"{name}: only the damaged case is recomputed"
    assert results == [synthetic(d) for d in DEPTHS], f"{name}: the recomputed value is returned"
    lines = notices(capsys.readouterr().err)
    assert len(lines) == 1, f"{name}: one notice line, got {lines}"
    assert path.name in lines[0] and "recomputing" in lines[0] and words in lines[0], lines[0]
    assert "\n" not in lines[0]
    _, computed = run_fe_cases(sweep, progress=False)
    assert computed == 0, f"{name}: the recomputed entry replaced the damaged one"


def test_swapped_entries_are_both_recomputed(fake, capsys):
    """Two depths' files exchanged: each holds the other case's inputs (the
    depth column read 0, 12, 8, 4 mm)."""
    sweep = make_sweep()
    run_fe_cases(sweep, progress=False)
    a, b = entry_path(sweep, 0.002), entry_path(sweep, 0.004)
    text_a, text_b = a.read_text(), b.read_text()
    a.write_text(text_b)
    b.write_text(text_a)
    fake.clear()
    capsys.readouterr()
    results, computed = run_fe_cases(sweep, progress=False)
    assert computed == 2 and sorted(fake) == [0.002, 0.004]
    assert [r["depth_m"] for r in results] == list(DEPTHS)
    assert results == [synthetic(d) for d in DEPTHS]
    lines = notices(capsys.readouterr().err)
    assert len(lines) == 2 and all("inputs are not those of this case" in l for l in lines), lines


def test_entry_of_another_source_is_not_trusted(fake, capsys, edit_source):
    """A source change invalidates every entry, whether it is looked up under its new key
    or found under the current one."""
    sweep = make_sweep()
    run_fe_cases(sweep, progress=False)
    old_text = entry_path(sweep, 0.002).read_text()
    edit_source("hubvib.fem.ring_stiffness")
    fake.clear()
    _, computed = run_fe_cases(sweep, progress=False)
    assert computed == 3, "new source: new keys, every case computed"

    entry_path(sweep, 0.002).write_text(old_text)  # the old entry under the current key
    fake.clear()
    capsys.readouterr()
    _, computed = run_fe_cases(sweep, progress=False)
    assert (computed, fake) == (1, [0.002])
    assert "another version of the source" in notices(capsys.readouterr().err)[0]


def test_a_worker_of_another_source_refuses_the_case(fake, edit_source):
    """A worker (a Dask worker on another machine) whose source key is not the client's
    computes nothing: its result would be stored under the client's key."""
    sweep = make_sweep()
    case = crack_sweep._Case(sweep, source_key(*crack_sweep.SOURCE))
    assert case(0.002) == synthetic(0.002)
    edit_source("hubvib.reducer.stages")
    with pytest.raises(RuntimeError, match="install the same hubvib on every worker"):
        case(0.002)
    assert fake == [0.002]


#: modules an FE case imports, in each stage it runs through (the ring, gear bodies and
#: material are built by ``hubvib.reducer.stages``)
IMPORTED = ["hubvib.reducer.stages", "hubvib.reducer", "hubvib.fem.ring_stiffness",
            "hubvib.meshing.ring_mesh", "hubvib.design.model", "hubvib.cases.runner"]
#: modules an FE case does not import
UNRELATED = ["hubvib.render.modes", "hubvib.render.fe", "hubvib.detection.pod",
             "hubvib.signal.mesh_curves", "hubvib.commands.run"]


@pytest.mark.parametrize("module", IMPORTED)
def test_an_edit_to_a_module_the_case_imports_recomputes_it(fake, capsys, edit_source, module):
    """An edited module of the case's import graph (the build layer's included): every case
    is computed again, and the entries of the old source are left alone."""
    sweep = make_sweep()
    first, _ = run_fe_cases(sweep, progress=False)
    assert run_fe_cases(sweep, progress=False)[1] == 0
    edit_source(module)
    fake.clear()
    again, computed = run_fe_cases(sweep, progress=False)
    assert computed == 3 and sorted(fake) == list(DEPTHS), f"{module} edited: a cache miss"
    assert again == first
    assert len(list(crack_sweep.cache_folder().glob("*.json"))) == 6
    assert run_fe_cases(sweep, progress=False)[1] == 0, "the new entries are reused"
    assert notices(capsys.readouterr().err) == []


@pytest.mark.parametrize("module", UNRELATED)
def test_an_edit_outside_the_cases_import_graph_keeps_its_entries(fake, edit_source, module):
    sweep = make_sweep()
    run_fe_cases(sweep, progress=False)
    edit_source(module)
    fake.clear()
    _, computed = run_fe_cases(sweep, progress=False)
    assert computed == 0 and fake == [], f"{module} is not imported by an FE case"


#: a sweep of the synthetic cases (JSON in argv) in a fresh interpreter; prints how many ran
_SWEEP = """
import json, sys
import hubvib.cases.runner as crack_sweep
from hubvib.design.presets import hub4
results = {float(depth): result for depth, result in json.loads(sys.argv[1]).items()}
crack_sweep.fe_case = lambda sweep, depth: results[depth]
sweep = crack_sweep.CrackSweep(tuple(sorted(results)), accuracy="fast", workers=1,
                               design=hub4())
print(crack_sweep.run_fe_cases(sweep, progress=False)[1])
"""


@pytest.mark.slow
def test_an_edited_build_module_of_an_installed_copy_recomputes_the_case(installed_copy,
                                                                         tmp_path):
    """The installed layout, each run a new process, the file itself edited: a comment
    appended to ``hubvib/reducer/stages.py`` (which builds the ring, the gear bodies and the
    material of every case) is a cache miss; one appended to a render module is not."""
    results = json.dumps({str(d): synthetic(d) for d in DEPTHS})
    env = dict(os.environ, PYTHONPATH=str(installed_copy), HUBVIB_CACHE=str(tmp_path / "c"))

    def computed() -> int:
        run = subprocess.run([sys.executable, "-c", _SWEEP, results], capture_output=True,
                             text=True, cwd=installed_copy, env=env, timeout=300)
        assert run.returncode == 0, run.stderr
        return int(run.stdout.split()[-1])

    def append(path: str) -> None:
        with open(installed_copy / path, "a", encoding="utf-8") as file:
            file.write("# an edit\n")

    assert computed() == 3
    assert computed() == 0
    append("hubvib/render/modes.py")
    assert computed() == 0, "a render module is not imported by an FE case"
    append("hubvib/reducer/stages.py")
    assert computed() == 3, "an edit to the build layer must not leave stale c_ru and c_rp"


def test_design_and_accuracy_decide_the_entry(fake):
    """hub4 vs raba118, or "fast" vs "default": different entries, each computed."""
    base = make_sweep(depths=(0.0,))
    others = [make_sweep(depths=(0.0,), design=raba118()),
              make_sweep(depths=(0.0,), accuracy="default")]
    keys = {entry_key(case_inputs(s, 0.0), modules=crack_sweep.SOURCE)
            for s in [base, *others]}
    assert len(keys) == 3
    for n, sweep in enumerate([base, *others], start=1):
        _, computed = run_fe_cases(sweep, progress=False)
        assert computed == 1 and len(fake) == n
    assert len(list(crack_sweep.cache_folder().glob("*.json"))) == 3
    assert json.loads(entry_path(others[0], 0.0).read_text())["inputs"]["design"]["name"] == \
        raba118().name


def test_design_with_explicit_planet_angles_is_reused(fake):
    """Inputs holding tuples (explicit, equally spaced planet angles) still match after
    the JSON round trip (a tuple reads back as a list)."""
    design = replace(hub4(), planet_angles=tuple(i * math.pi / 2 for i in range(4)))
    sweep = make_sweep(depths=(0.0,), design=design)
    assert run_fe_cases(sweep, progress=False)[1] == 1
    assert run_fe_cases(sweep, progress=False)[1] == 0


def test_entry_that_is_a_folder_is_refused_before_any_case(fake):
    """A folder where the entry should be cannot be replaced: a one-line error naming it,
    before any FE work (which would be lost)."""
    sweep = make_sweep()
    path = entry_path(sweep, 0.002)
    path.mkdir(parents=True)
    with pytest.raises(CacheFolderError, match=path.name):
        run_fe_cases(sweep, progress=False)
    assert fake == []


def test_cache_that_is_a_file_is_refused_before_any_case(fake, tmp_path, monkeypatch):
    """HUBVIB_CACHE pointing at a file is found before the FE work."""
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("x")
    monkeypatch.setenv("HUBVIB_CACHE", str(blocker))
    with pytest.raises(CacheFolderError, match="HUBVIB_CACHE"):
        run_fe_cases(make_sweep(), progress=False)
    assert fake == []


def test_non_finite_fe_result_is_not_stored(fake, monkeypatch):
    """An FE result holding NaN is refused with a message naming the key; nothing stored."""
    monkeypatch.setattr(crack_sweep, "fe_case", lambda s, d: synthetic(d) | {"c_r_N_m": math.nan})
    with pytest.raises(ValueError, match="non-finite c_r_N_m"):
        run_fe_cases(make_sweep(depths=(0.0,)), progress=False)
    assert list(crack_sweep.cache_folder().glob("*.json")) == []


def _killed_run(cache: str) -> None:
    """A run killed (``os._exit``, no clean-up) while it computes the third case."""
    os.environ["HUBVIB_CACHE"] = cache

    def fe_case(sweep, depth):
        if depth == DEPTHS[2]:
            os._exit(9)
        return synthetic(depth)

    crack_sweep.fe_case = fe_case
    run_fe_cases(make_sweep(), progress=False)


def test_killed_run_resumes_from_its_finished_cases(fake, tmp_path):
    """The calling process stores each case as it finishes (whatever the engine), so a
    run killed mid-sweep loses only the case in progress."""
    run = multiprocessing.get_context("fork").Process(
        target=_killed_run, args=(os.environ["HUBVIB_CACHE"],))
    run.start()
    run.join(30)
    assert run.exitcode == 9
    results, computed = run_fe_cases(make_sweep(), progress=False)
    assert (computed, fake) == (1, [DEPTHS[2]])
    assert results == [synthetic(d) for d in DEPTHS]


#: a slow FE case, simulated: the sleep IS what the concurrency test needs (two runs
#: overlap on a case in progress), not a wait for an event
SLOW_CASE_S = 0.4


def _concurrent_run(cache: str, counter: str, out: str) -> None:
    """One run of the sweep in a forked process; ``fe_case`` logs each case it computes."""
    os.environ["HUBVIB_CACHE"] = cache

    def fe_case(sweep, depth):
        with open(counter, "a") as handle:
            handle.write(f"{os.getpid()} {depth!r}\n")
        time.sleep(SLOW_CASE_S)
        return synthetic(depth)

    crack_sweep.fe_case = fe_case
    results, computed = run_fe_cases(make_sweep(), progress=False)
    Path(out).write_text(json.dumps({"results": results, "computed": computed}))


def test_concurrent_runs_compute_each_case_once(tmp_path):
    """Two runs of one sweep on one cache share the entries."""
    context = multiprocessing.get_context("fork")
    counter = tmp_path / "computed.txt"
    outs = [tmp_path / f"run{i}.json" for i in range(2)]
    runs = [context.Process(target=_concurrent_run, args=(str(tmp_path / "cache"), str(counter),
                                                         str(out)))
            for out in outs]
    for run in runs:
        run.start()
    for run in runs:
        run.join(30)
    assert [r.exitcode for r in runs] == [0, 0]
    lines = counter.read_text().split()
    depths = sorted(float(d) for d in lines[1::2])
    assert depths == list(DEPTHS), f"each case computed once in total, got {lines}"
    reports = [json.loads(o.read_text()) for o in outs]
    assert sum(r["computed"] for r in reports) == len(DEPTHS)
    assert reports[0]["results"] == reports[1]["results"] == [synthetic(d) for d in DEPTHS]


def test_typed_case_round_trips_and_names_what_is_missing():
    """A cached case reads back as a typed, frozen result whose to_dict is
    the entry's dict again (same keys, same values); a missing key or a wrong type is
    named, and the entry records the schema version of that dict form."""
    from hubvib.fem.estimate import SCHEMA_VERSION, CrackCaseEstimate
    from hubvib.cases.results import PlaneCase

    row = synthetic(0.004)
    case = PlaneCase.from_dict(row)
    assert isinstance(case.estimate, CrackCaseEstimate) and case.depth == 0.004
    assert case.to_dict() == row
    with pytest.raises(ValueError, match="lacks c_r_N_m"):
        PlaneCase.from_dict({k: v for k, v in row.items() if k != "c_r_N_m"})
    with pytest.raises(ValueError, match="dofs = '12345'; allowed: int"):
        PlaneCase.from_dict(dict(row, dofs="12345"))
    with pytest.raises(CacheEntryError, match="lacks solver"):
        crack_sweep.check_case(0.004)({k: v for k, v in row.items() if k != "solver"})
    assert SCHEMA_VERSION >= 1


def test_the_test_run_keeps_out_of_the_users_cache(shared_cache_folder):
    """conftest's ``run_cache``: with no test-level override every stage caches below the
    run's own folder, not in ``~/.cache/hubvib`` (a run that found entries there from an
    earlier one would not start as cold as CI's)."""
    from hubvib.meshing.cache import root_folder

    assert root_folder() == shared_cache_folder
