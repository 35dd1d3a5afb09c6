"""Every bad input is one line naming the flag, key or file, exit 2, nothing written.

The fault-injection tests (signals, a full
disk, killed parents, concurrent runs) are in ``test_faults.py``.
"""
import codecs
import json
import math
import os
import random
import subprocess
import sys
from pathlib import Path

import pytest

from hubvib import lumped
from hubvib.reducer import lumped_preset
from hubvib.cli import main
from hubvib.lumped.parameters import ANGLE_TOLERANCE, MAX_PLANETS


def _strict_json(text: str):
    """Parse as RFC 8259 JSON: NaN and Infinity are not numbers there."""
    def refuse(name):
        raise AssertionError(f"non-standard JSON constant {name}")
    return json.loads(text, parse_constant=refuse)


def _fails(capsys, argv, *pieces):
    """``main(argv)`` exits 2 with one line on stderr holding every piece."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hubvib: error: "), err
    for piece in pieces:
        assert piece in lines[0], f"{piece!r} not in {lines[0]!r}"
    return lines[0]


# -- the --params file ---------------------------------------------------------

def _params_files(tmp_path):
    files = {}
    files["missing"] = (tmp_path / "missing.toml", "No such file")
    folder = tmp_path / "folder.toml"
    folder.mkdir()
    files["directory"] = (folder, "is a directory")
    files["device"] = ("/dev/zero", "not a regular file")
    huge = tmp_path / "huge.toml"
    huge.write_bytes(b"#" * (2 << 20))
    files["huge"] = (huge, "larger than")
    bad = tmp_path / "bad.toml"
    bad.write_text("c_ru = \n")
    files["malformed"] = (bad, "not valid TOML")
    utf16 = tmp_path / "utf16.toml"
    utf16.write_bytes("c_ru = 1e5\n".encode("utf-16"))
    files["utf-16"] = (utf16, "UTF-16")
    binary = tmp_path / "binary.toml"
    binary.write_bytes(b"\x7fELF\x02\x01\x01\x00\x00\x00")
    files["binary"] = (binary, "binary")
    latin = tmp_path / "latin1.toml"
    latin.write_bytes('c_ru = "\xe9"\n'.encode("latin-1"))
    files["latin-1"] = (latin, "not UTF-8")
    preset = tmp_path / "preset.toml"
    preset.write_text("preset = [1]\n")
    files["preset"] = (preset, "preset = [1]")
    return files


@pytest.mark.parametrize("case", ["missing", "directory", "device", "huge", "malformed",
                                  "utf-16", "binary", "latin-1", "preset"])
def test_params_file_refused_naming_the_file(case, tmp_path, capsys):
    """Each bad --params file is one line naming the file; /dev/zero is not read."""
    path, why = _params_files(tmp_path)[case]
    _fails(capsys, ["spectrum", "--params", str(path)], f"parameters file {str(path)!r}", why)


def test_params_file_with_utf8_bom_reads_as_without(tmp_path, capsys):
    """A UTF-8 byte-order mark (Windows editors) is skipped, not an error."""
    plain, marked = tmp_path / "plain.toml", tmp_path / "bom.toml"
    plain.write_text("c_ru = 1e5\n", encoding="utf-8")
    marked.write_bytes(codecs.BOM_UTF8 + b"c_ru = 1e5\n")
    outputs = []
    for path in (plain, marked):
        assert main(["spectrum", "--params", str(path), "--json"]) == 0
        outputs.append(_strict_json(capsys.readouterr().out))
    assert outputs[0] == outputs[1]
    # c_ru = 1e5 lowers mode 1 by 43.64 % (README worked example, frequency_shift)
    assert outputs[0]["modes"][0]["omega_rad_s"] == pytest.approx(336.454 * (1 - 0.4364), rel=1e-3)


def test_params_file_bad_key_names_the_file(tmp_path, capsys):
    """A bad value inside the file says which file it came from."""
    path = tmp_path / "p.toml"
    path.write_text("c_ru = -1\n")
    _fails(capsys, ["spectrum", "--params", str(path)], str(path), "c_ru = -1")


# -- shift --to ------------------------------------------------------------------

@pytest.mark.parametrize("key, value, message", [
    ("foo", "1e5", "--to 'foo' is not a parameter; allowed: m_s"),
    ("theta_deg", "10", "--to 'theta_deg' holds one value per planet"),
    ("theta", "1", "--to 'theta' holds one value per planet"),
    ("c_rp_factors", "0.5", "--to 'c_rp_factors' holds one value per planet"),
    ("alpha_w_deg", "22", "sets alpha_s and alpha_r together"),
    ("n_planets", "4", "--to 'n_planets'"),
    ("", "1", "--to '' is not a parameter"),
    ("c_ru", "abc", "--to c_ru = 'abc', but it must be a number"),
    ("c_ru", "nan", "c_ru = nan, but it must be finite"),
])
def test_shift_to_names_the_flag(key, value, message, capsys):
    """No AttributeError/TypeError; the error names --to, not --set."""
    line = _fails(capsys, ["shift", "--to", key, value], message)
    assert "--set" not in line


def test_shift_to_a_pressure_angle_still_works(capsys):
    """The one-number fields stay shiftable: the modified frequencies of
    ``shift --to alpha_s 0.5`` (tracked along a path) are those ``spectrum --set
    alpha_s=0.5`` computes directly (1e-9)."""
    assert main(["shift", "--to", "alpha_s", "0.5", "--json"]) == 0
    shifted = _strict_json(capsys.readouterr().out)["modes"]
    assert main(["spectrum", "--set", "alpha_s=0.5", "--json"]) == 0
    direct = _strict_json(capsys.readouterr().out)["modes"]
    assert sorted(m["omega_modified_rad_s"] for m in shifted) == pytest.approx(
        [m["omega_rad_s"] for m in direct], rel=1e-9)


# -- output folders of mesh, validate, convergence ---------------------------------

def _bad_folders(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    return {"file": blocker, "under a file": blocker / "out", "proc": "/proc/hubvib-out",
            "long name": tmp_path / ("x" * 300)}


@pytest.mark.parametrize("command", ["mesh", "validate", "convergence"])
@pytest.mark.parametrize("where", ["file", "under a file", "proc", "long name"])
def test_output_folder_checked_before_any_work(command, where, tmp_path, capsys, monkeypatch):
    """The folder is refused in one line before meshing/validating/computing."""
    import hubvib.studies.part_mesh
    import hubvib.validation.convergence
    import hubvib.validation.raba118

    def no_work(*args, **kwargs):
        raise AssertionError("work started before the output folder was checked")

    monkeypatch.setattr(hubvib.studies.part_mesh, "mesh_part", no_work)
    monkeypatch.setattr(hubvib.validation.raba118, "validate", no_work)
    monkeypatch.setattr(hubvib.validation.convergence, "run_study", no_work)
    folder = str(_bad_folders(tmp_path)[where])
    argv = {"mesh": ["mesh", "planet"], "validate": ["validate", "raba118"],
            "convergence": ["convergence", "annulus"]}[command] + ["--out", folder]
    _fails(capsys, argv, f"cannot write the output folder {folder!r}")


# -- the FE cache -----------------------------------------------------------------

CRACK_SCENE = """# tiny crack scene
[crack]
depths = [0.0, 0.004]
accuracy = "fast"
workers = 1
[output]
plots = false
"""


@pytest.mark.parametrize("cache", ["file", "proc"])
def test_unwritable_cache_refused_before_fe_work(cache, tmp_path, capsys, monkeypatch):
    """HUBVIB_CACHE that is a file or cannot be created: one line naming it, exit 2,
    before any FE case (the FE entry point would fail the test) and with nothing written."""
    pytest.importorskip("gmsh")
    import hubvib.studies.crack_study

    def no_work(*args, **kwargs):
        raise AssertionError("FE work started before the cache was checked")

    monkeypatch.setattr(hubvib.studies.crack_study, "run_crack_study", no_work)
    blocker = tmp_path / "cache-file"
    blocker.write_text("x")
    root = str(blocker) if cache == "file" else "/proc/hubvib-cache"
    monkeypatch.setenv("HUBVIB_CACHE", root)
    scene = tmp_path / "crack.toml"
    scene.write_text(CRACK_SCENE)
    out = tmp_path / "out"
    _fails(capsys, ["run", str(scene), "--out", str(out)], f"HUBVIB_CACHE = {root!r}",
           "writable folder")
    assert not out.exists()


# -- bounds ------------------------------------------------------------------------

BOUNDS = [
    (["spectrum", "--set", "n_planets=1000"],
     f"n_planets = 1000, but it must be an integer 1..{MAX_PLANETS}"),
    (["spectrum", "--set", "n_planets=1e6"], "n_planets = 1000000"),
    (["spectrum", "--set", "theta=" + ",".join(str(0.001 * i) for i in range(1000))],
     f"theta has 1000 planet angles, but at most N = {MAX_PLANETS}"),
    (["mesh", "ring", "--size", "1e-5"], "--size = 1e-05 m would give ~5.0e+08 elements"),
    (["mesh", "ring", "--dim", "3", "--size", "1e-3"], "allowed >= 3.4e-03 m"),
    (["mesh", "ring", "--size", "nan"], "--size = nan m"),
    (["stability", "--repeats", "1000000000"], "--repeats = 1000000000, but it must be 1..1000"),
]
#: each command line through ``hubvib.cli.main`` in one fresh process, stderr caught per
#: line; a command that does not return (the old hangs) trips the process's time limit
BOUNDS_RUNNER = """
import contextlib, io, json, sys
from hubvib.cli import main

results = []
for argv in json.loads(sys.argv[1]):
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            code = main(argv)
        except SystemExit as stop:
            code = stop.code
    results.append([code, err.getvalue()])
print(json.dumps(results))
"""


@pytest.fixture(scope="module")
def bounds_runs(tmp_path_factory):
    """``{index in BOUNDS: (exit code, stderr, out folder)}``, all from one subprocess with
    a time limit (one interpreter start instead of one per line: the same ``main``)."""
    folder = tmp_path_factory.mktemp("bounds")
    lines, outs = [], []
    for i, (argv, _) in enumerate(BOUNDS):
        outs.append(folder / f"out{i}")
        lines.append(argv + ["--out", str(outs[-1])] if argv[0] == "mesh" else argv)
    run = subprocess.run([sys.executable, "-c", BOUNDS_RUNNER, json.dumps(lines)],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0 and run.stderr == "", run.stderr
    return {i: (code, err, out) for i, ((code, err), out)
            in enumerate(zip(json.loads(run.stdout), outs))}


@pytest.mark.parametrize("index", range(len(BOUNDS)),
                         ids=[message for _, message in BOUNDS])
def test_documented_bounds(index, bounds_runs):
    """Each bound is one line at once (in a subprocess with a time limit: the old
    code hung in an N^2 angle check, meshed for minutes or ran the benchmark forever),
    exit 2, nothing written."""
    argv, message = BOUNDS[index]
    if argv[0] == "mesh":
        pytest.importorskip("gmsh")
    code, stderr, out = bounds_runs[index]
    assert code == 2 and stderr.count("\n") == 1, stderr
    assert message in stderr
    assert not out.exists()


def test_huge_planet_count_in_a_params_file(tmp_path):
    """N_planets = 1e9 in a file (the old code tried to build 1e9 angles)."""
    path = tmp_path / "p.toml"
    path.write_text("n_planets = 1e9\n")
    run = subprocess.run([sys.executable, "-m", "hubvib.cli", "spectrum", "--params", str(path)],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 2
    assert run.stderr.strip() == (f"hubvib: error: parameters file {str(path)!r}: n_planets = "
                                  f"1000000000, but it must be an integer 1..{MAX_PLANETS}")


def test_planet_angle_check_agrees_with_every_pair():
    """The N log N neighbour check refuses exactly the angle sets that the plain
    check of all N^2 pairs refuses (random sets with near-duplicates and wrap-around)."""
    def brute_force(theta):
        wrap = lambda a: (a + math.pi) % (2 * math.pi) - math.pi  # noqa: E731
        return any(abs(wrap(theta[i] - theta[j])) <= ANGLE_TOLERANCE
                   for i in range(len(theta)) for j in range(i))

    rng = random.Random(17)
    refused = accepted = 0
    for _ in range(400):
        n = rng.randint(2, MAX_PLANETS)
        theta = [rng.uniform(-2 * math.pi, 2 * math.pi) for _ in range(n)]
        if rng.random() < 0.5:  # a near-duplicate, possibly one turn away
            i, j = rng.randrange(n), rng.randrange(n)
            turn = rng.choice([-2 * math.pi, 0.0, 2 * math.pi])
            near = theta[i] + turn + rng.choice([0.0, 0.5, 2.0]) * ANGLE_TOLERANCE
            if i != j and abs(near) <= 2 * math.pi:
                theta[j] = near
        expected = brute_force(theta)
        try:
            lumped_preset("raba118").replace(theta=tuple(theta))
            refused_now = False
        except lumped.ParameterError as exc:
            assert "same place" in str(exc)
            refused_now = True
        assert refused_now == expected, theta
        refused += refused_now
        accepted += not refused_now
    assert refused > 50 and accepted > 50  # both branches were exercised


def test_most_planets_allowed_still_solve():
    """N = MAX_PLANETS is inside the bound and keeps Lin & Parker's structure
    (equally spaced planets): 6 rotational modes, 6 translational pairs and 3 groups of
    N - 3 planet modes, 9 + 3N in all."""
    params = lumped_preset("raba118").replace(theta=lumped.equally_spaced_angles(MAX_PLANETS))
    spectrum = lumped.natural_modes(params)
    kinds = spectrum.kind
    assert len(kinds) == 9 + 3 * MAX_PLANETS
    assert kinds.count("rotational") == 6 and kinds.count("translational") == 12
    assert kinds.count("planet") == 3 * (MAX_PLANETS - 3)


# -- overflow and standard JSON ---------------------------------------------------

MASSES = ("m_s", "m_c", "m_r", "m_p", "mu_s", "mu_c", "mu_r", "mu_p")


def test_overflowing_spectrum_is_refused(capsys):
    """Every mass x 1e-300 puts omega^2 beyond the double range (3e8 / 1e-300):
    refused in one line, not 9 modes of 'inf' labelled 'mixed'."""
    argv = ["spectrum", "--json"] + [a for m in MASSES for a in ("--set", f"{m}=1e-300")]
    _fails(capsys, argv, "overflow double precision", "c_sp = 3e+08 N/m over m_s = 1e-300 kg")


def test_light_but_representable_masses_still_solve():
    """Only non-finite results are refused.  Every mass x 1e-290 kg is fine, and
    scales every frequency by exactly 1e145 (omega ~ sqrt(k / m): homogeneity), 1e-9."""
    base = lumped_preset("raba118")
    scaled = base.replace(**{m: getattr(base, m) * 1e-290 for m in MASSES})
    ratio = lumped.natural_modes(scaled).omega / lumped.natural_modes(base).omega
    assert ratio == pytest.approx(1e145, rel=1e-9)


@pytest.mark.parametrize("argv", [["spectrum", "--json"],
                                  ["shift", "--to", "c_ru", "1e5", "--json"],
                                  ["stability", "--repeats", "1", "--json"]])
@pytest.mark.slow
def test_json_output_is_standard(argv, capsys):
    """--json is RFC 8259 JSON (the stability table had NaN for the printed matrix:
    it is null now)."""
    main(argv)
    _strict_json(capsys.readouterr().out)


def test_json_text_names_a_non_finite_value():
    """A NaN on its way to a JSON file is an error naming where it is."""
    from hubvib.foundation.output import json_text

    with pytest.raises(ValueError, match=r"modes\[1\]\.omega = inf is not a finite number"):
        json_text({"modes": [{"omega": 1.0}, {"omega": math.inf}]})


def test_written_tables_leave_a_nan_cell_empty(tmp_path):
    """A NaN (a value that has none) is an empty CSV field, never ``nan``; every other value,
    an infinite one too, is written as before (``str`` of the float)."""
    import csv

    from hubvib.foundation.output import write_csv

    numpy = pytest.importorskip("numpy")
    path = write_csv(tmp_path / "t.csv", [
        {"a": 1.0 / 3.0, "b": math.nan, "c": 7, "d": None},
        {"a": numpy.float64("nan"), "b": numpy.float32(0.5), "c": math.inf, "d": "text"}])
    text = path.read_text()
    assert "nan" not in text.lower(), text
    assert text.splitlines() == ["a,b,c,d", f"{1.0 / 3.0!r},,7,", ",0.5,inf,text"]
    assert list(csv.DictReader(path.open(newline="")))[0]["b"] == ""


# -- silent acceptance -------------------------------------------------------------

@pytest.mark.parametrize("sets, message", [
    (["n_planets=4", "theta_deg=0,90"], "n_planets = 4, but theta_deg gives 2 planet angle(s)"),
    (["n_planets=3", "theta=0,1"], "n_planets = 3, but theta gives 2 planet angle(s)"),
    (["theta=0,2", "theta_deg=0,90"], "theta and theta_deg are both given"),
    (["alpha_w_deg=22", "alpha_s=0.4"], "alpha_w_deg and alpha_s are both given"),
    (["theta=1e300"], "theta[0] = 1e+300 rad, but planet angles must lie in [-2 pi, 2 pi]"),
    (["theta_deg=0,1e300"], "theta_deg[1] = 1e+300, but planet angles must lie in [-360, 360]"),
    (["alpha_w_deg=90"], "alpha_w_deg = 90.0, but it must lie in (0, 90) deg"),
    (["alpha_w_deg=0"], "alpha_w_deg = 0.0"),
])
def test_contradictions_and_ranges_name_the_key(sets, message, capsys):
    """No silent choice between contradicting keys; the key the user typed is the
    one named (alpha_w_deg, not alpha_s)."""
    argv = ["spectrum"] + [a for s in sets for a in ("--set", s)]
    _fails(capsys, argv, message)


def test_planet_count_and_matching_angles_agree(capsys):
    """N_planets with angles of the same count is not a contradiction; unequal
    spacing breaks the cyclic symmetry, so no 'planet' multiplicity-2 modes remain."""
    assert main(["spectrum", "--set", "n_planets=3", "--set", "theta_deg=0,100,200",
                 "--json"]) == 0
    modes = _strict_json(capsys.readouterr().out)["modes"]
    assert len(modes) == 18 and all(m["multiplicity"] == 1 for m in modes)


# -- progress lines -----------------------------------------------------------------

def test_run_prints_one_line_per_stage_when_not_a_terminal(tmp_path, capsys):
    """Stderr that is not a terminal gets one line per finished stage."""
    assert main(["run", "raba118_five_planets", "--out", str(tmp_path / "out")]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("hubvib: lumped spectra and shifts of 3 values done (")
    assert err[1].startswith("hubvib: tables and report done (") and len(err) == 2


def test_line_progress_counts_and_estimates():
    """The plain progress line: done/total, the note, elapsed and time left."""
    import io

    from hubvib.runtime.progress import progress

    stream = io.StringIO()
    with progress(4, "FE crack cases", "case", initial=1, stream=stream) as bar:
        bar.update(note="depth 4 mm")
        bar.update()
        bar.update(note="depth 12 mm")
    lines = stream.getvalue().splitlines()
    assert lines[0].startswith("FE crack cases: 2/4 cases (depth 4 mm), ")
    assert "s left" in lines[0] and "s left" not in lines[2]
    assert lines[2].startswith("FE crack cases: 4/4 cases (depth 12 mm), ") and len(lines) == 3


# -- the output set ------------------------------------------------------------

@pytest.mark.slow
def test_output_files_are_0644_under_umask_022(tmp_path, capsys):
    """CSV, JSON, report and plots get the umask's mode, 0644 under 022, as the
    renders always did (mkstemp alone creates 0600)."""
    previous = os.umask(0o022)
    try:
        assert main(["run", "raba118_c_ru", "--out", str(tmp_path / "out")]) == 0
    finally:
        os.umask(previous)
    files = [p for p in (tmp_path / "out").iterdir() if p.is_file()]
    assert len(files) >= 7
    assert {p.name: oct(p.stat().st_mode & 0o777) for p in files} == {
        p.name: "0o644" for p in files}


def test_a_new_set_replaces_the_previous_one_whole(tmp_path):
    """The second set into a folder removes the first set's files it does not
    have (no plot of scene A beside the tables of scene B), leaves files hubvib did not
    write, and follows no manifest entry out of the folder."""
    from hubvib.foundation.output import MANIFEST_NAME, output_set, write_text

    out = tmp_path / "out"
    with output_set(out) as stage:
        write_text(stage / "a.csv", "a")
        write_text(stage / "plots" / "a.png", "png")
    (out / "mine.txt").write_text("the user's")
    outside = tmp_path / "outside.txt"
    outside.write_text("keep")
    manifest = json.loads((out / MANIFEST_NAME).read_text())
    manifest["files"] += ["../outside.txt", str(outside)]
    (out / MANIFEST_NAME).write_text(json.dumps(manifest))
    with output_set(out) as stage:
        write_text(stage / "b.csv", "b")
    assert sorted(p.relative_to(out).as_posix() for p in out.rglob("*")) == [
        MANIFEST_NAME, "b.csv", "mine.txt"]
    assert outside.read_text() == "keep"


def test_failed_set_changes_nothing_and_says_what_was_discarded(tmp_path):
    """An error while writing the set leaves the folder as it was."""
    from hubvib.foundation.output import OutputError, output_set, write_text

    out = tmp_path / "out"
    with output_set(out) as stage:
        write_text(stage / "a.csv", "first")
    before = sorted(out.iterdir())
    with pytest.raises(OutputError, match=r"1 finished file\(s\) discarded: a.csv"):
        with output_set(out) as stage:
            write_text(stage / "a.csv", "second")
            raise OSError(28, "No space left on device")
    assert sorted(out.iterdir()) == before and (out / "a.csv").read_text() == "first"


def test_atomic_path_is_the_only_file_replacer():
    """One atomic-write helper, hubvib.foundation.output.atomic_path.  A module that
    renames a temporary file into place itself is listed below until it uses the helper
    (the list may only shrink)."""
    root = Path(__file__).parents[2]
    patterns = ("os.replace(", "mkstemp(", "tmp.replace(")
    writers = {p.relative_to(root).as_posix()
               for folder in ("hubvib",)
               for p in (root / folder).rglob("*.py")
               if any(s in p.read_text(encoding="utf-8") for s in patterns)}
    assert writers - {"hubvib/foundation/output.py"} <= KNOWN_OTHER_WRITERS, writers


#: writers in files this change does not own, to be switched to hubvib.foundation.output.atomic_path
KNOWN_OTHER_WRITERS = set()


def test_leftovers_of_a_killed_run_are_cleared(tmp_path):
    """Kill -9 leaves the hidden stage and lock file behind (no handler runs);
    the next run into the folder removes the stage and takes the lock (the kernel released
    the dead run's flock)."""
    from hubvib.foundation.output import LOCK_NAME, STAGE_PREFIX, output_set, write_text

    out = tmp_path / "out"
    stale = out / f"{STAGE_PREFIX}killed"
    stale.mkdir(parents=True)
    (stale / "results.json").write_text("{")
    (out / LOCK_NAME).write_text("12345\n")
    with output_set(out) as stage:
        write_text(stage / "a.csv", "a")
    assert sorted(p.name for p in out.iterdir()) == [".hubvib-files.json", "a.csv"]
