"""Every file input through one guarded reader, physical ranges
checked before computing, errors that name the file, line or key, and contradictions
refused."""
from __future__ import annotations

import json
import os
import threading
import warnings
from pathlib import Path

import pytest

from hubvib.cli import main
from hubvib.foundation.errors import InputError
from hubvib.foundation.files import read_bytes, read_text
from hubvib.runtime.fe_cache import CacheEntryError, read_entry

#: the entry module the stand-in FE cache entries below are keyed on
MODULES = ("hubvib.runtime.fe_cache",)


def _fails(capsys, argv, *pieces):
    """``main(argv)`` exits 2 with one line on stderr holding every piece; nothing else
    on stderr (no warning text)."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hubvib: error: "), err
    for piece in pieces:
        assert piece in lines[0], f"{piece!r} not in {lines[0]!r}"
    return lines[0]


def _bounded(call, fifo: Path | None = None):
    """Run ``call()`` in a thread; if it is still blocked after 20 s (the bug: a FIFO is
    opened for reading and waits for a writer forever), unblock it by opening the FIFO for
    writing, and fail."""
    done = threading.Event()
    result = {}

    def target():
        try:
            result["value"] = call()
        except BaseException as exc:  # noqa: BLE001 - handed to the test thread
            result["error"] = exc
        finally:
            done.set()

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    if not done.wait(20):
        if fifo is not None:
            os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        pytest.fail("the reader blocked on a FIFO")
    if "error" in result:
        raise result["error"]
    return result["value"]


@pytest.fixture
def fifo(tmp_path):
    path = tmp_path / "input.fifo"
    os.mkfifo(path)
    return path


INPUTS = {  # the flag and the words that name it in the error line
    "design": (["spectrum", "--design"], "design file"),
    "measured": (["diagnose", "--scene", "raba118_crack", "--measured"], "--measured"),
    "periods": (["harmonics", "--pulses-per-rev", "4", "--z2", "10", "--periods"], "--periods"),
    "params": (["spectrum", "--params"], "parameters file"),
}


@pytest.mark.parametrize("source", ["fifo", "dev-zero", "symlink to dev-zero"])
@pytest.mark.parametrize("name", INPUTS)
def test_every_file_input_refuses_devices_and_pipes(name, source, fifo, tmp_path, capsys):
    """--design, --measured, --periods (and --params) refuse a FIFO at once (it
    blocked forever) and /dev/zero (MemoryError) with one line naming the flag and file."""
    argv, words = INPUTS[name]
    path = {"fifo": fifo, "dev-zero": Path("/dev/zero")}.get(source)
    if path is None:
        path = tmp_path / "zero.csv"
        path.symlink_to("/dev/zero")
    code = _bounded(lambda: main([*argv, str(path)]), fifo)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    assert f"{words} {str(path)!r} is not a regular file" in err[0], err[0]


def test_scene_design_file_key_refuses_a_fifo(fifo, tmp_path, capsys):
    """``[design] file =`` in a scene goes through the same reader."""
    scene = tmp_path / "s.toml"
    scene.write_text(f'[design]\nfile = "{fifo}"\n', encoding="utf-8")
    code = _bounded(lambda: main(["run", str(scene), "--out", str(tmp_path / "out")]), fifo)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and "is not a regular file" in err[-1], err


@pytest.mark.parametrize("source", ["fifo", "symlink to dev-zero"])
def test_cache_entry_that_is_a_device_is_recomputed_not_read(source, fifo, tmp_path):
    """An FE cache entry that is a FIFO or a symlink to /dev/zero is 'unreadable'
    (recomputed), not a hang or a MemoryError."""
    path = fifo if source == "fifo" else tmp_path / "entry.json"
    if source != "fifo":
        path.symlink_to("/dev/zero")
    with pytest.raises(CacheEntryError, match="unreadable .*not a regular file"):
        _bounded(lambda: read_entry(path, {"a": 1}, modules=MODULES), fifo)


def test_render_cache_file_symlinked_to_a_device_is_rendered_again(tmp_path, capsys):
    """A render-cache file replaced by a symlink to /dev/zero fails its check (one
    notice, rendered again) instead of reading forever."""
    from hubvib.render.cache import _verified

    entry = tmp_path / "entry"
    entry.mkdir()
    (entry / "a.png").symlink_to("/dev/zero")
    (entry / "manifest.json").write_text(json.dumps(
        {"files": {"a.png": "0" * 64}, "returned": ["a.png"]}), encoding="utf-8")
    assert _bounded(lambda: _verified(entry, notice=True)) is None
    assert "not a regular file" in capsys.readouterr().err


def test_reader_limits_and_messages(tmp_path):
    """The one reader bounds the size and names file and line of bad bytes."""
    big = tmp_path / "big.csv"
    big.write_bytes(b"1\n" * 600)
    with pytest.raises(InputError, match=r"--periods .*big.csv' is larger than 1000 bytes"):
        read_text(big, "--periods", kind="CSV", max_bytes=1000)
    assert len(read_bytes(big, "x", max_bytes=1200)) == 1200
    latin = tmp_path / "latin.csv"
    latin.write_bytes(b"period_s\n0.1\n0.\xe9\n")
    with pytest.raises(InputError, match=r"latin.csv' is not UTF-8 text \(line 3, byte 15"):
        read_text(latin, "--periods", kind="CSV")
    assert read_text(big, "x", kind="CSV").count("\n") == 600


# -- physical ranges checked before computing; no warning text -------------------

def _periods(tmp_path, value, count=16):
    path = tmp_path / "periods.csv"
    path.write_text("period_s\n" + f"{value}\n" * count, encoding="utf-8")
    return str(path)


def test_mode_number_too_large_for_numpy_is_one_line(tmp_path, capsys):
    """Mode = 99999999999999999999999 in --measured ended in OverflowError."""
    path = tmp_path / "m.csv"
    path.write_text("frequency_hz,mode\n50,99999999999999999999999\n", encoding="utf-8")
    _fails(capsys, ["diagnose", "--scene", "raba118_crack", "--measured", str(path)],
           "line 2: mode = '99999999999999999999999'", "1..10000")


@pytest.mark.parametrize("flags, message", [
    (["--stages", "1000"], "--stages = 1000; allowed: an integer 1..20"),
    (["--stages", "20", "--z2", "10000"], "allowed: a total ratio <= 1e+12"),
])
def test_harmonics_stage_count_bounded_before_computing(flags, message, tmp_path, capsys):
    """--stages 1000 overflowed (OverflowError) in the engagement orders."""
    _fails(capsys, ["harmonics", "--periods", _periods(tmp_path, 0.01), "--pulses-per-rev",
                    "4", "--z2", "6", *flags], message)


@pytest.mark.parametrize("value", ["1e308", "1e-320"])
def test_periods_outside_physical_range_refused_without_warnings(value, tmp_path, capsys):
    """Periods of 1e308 s printed numpy RuntimeWarnings before an error naming
    nothing (``y must contain only finite values``)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any numpy warning fails the test
        _fails(capsys, ["harmonics", "--periods", _periods(tmp_path, value),
                        "--pulses-per-rev", "4", "--z2", "6"],
               "--periods: period 1", "allowed: 1e-09..86400 s")


def test_torus_screw_speed_bounded(capsys):
    """--input-speed-rpm 1e300 overflowed Phi4 (OverflowError)."""
    _fails(capsys, ["torus-screw", "--input-speed-rpm", "1e300"], "--input-speed-rpm",
           "0..1e+06")


@pytest.mark.parametrize("ratio", ["1e300", "1001"])
def test_efficiency_ratio_bounded(ratio, capsys):
    """--ratio 1e300 exited 0 printing R = -inf."""
    _fails(capsys, ["efficiency", "--ratio", ratio], "--ratio", "2..1000")


def test_efficiency_largest_ratio_still_finite(capsys):
    """The bound is not too tight: i = 1000 gives finite R, A and eta; R grows
    like i (eq. 12: R ~ i d_c / (2 pi) x ..., 12.39 m for 15 mm balls, computed here)."""
    assert main(["efficiency", "--ratio", "1000", "--json"]) == 0
    text = capsys.readouterr().out
    assert "Infinity" not in text and "NaN" not in text, "non-finite value at i = 1000"


# -- negative contact forces ----------------------------------------------------

def test_torus_screw_negative_contact_force_refused(capsys):
    """Alpha1 = 89.999, alpha3 = 0.001 deg printed N3 = -40.6 N without a word."""
    _fails(capsys, ["torus-screw", "--alpha1-deg", "89.999", "--alpha3-deg", "0.001"],
           "outside the force model's validity", "N3 = -40.61 N < 0", "--alpha1-deg")


def test_torus_screw_paper_point_still_solves(capsys):
    """The paper's operating point keeps positive contact forces (paper: N1 =
    160.61 N, N3 = 844.47 N cylindrical; this model 162.1, 844.2 as its doctest says)."""
    assert main(["torus-screw", "--fingers", "cylindrical", "--json"]) == 0
    forces = json.loads(capsys.readouterr().out)["results"][0]
    assert forces["N1_n"] == pytest.approx(160.61, rel=0.01), "N1 vs seed 002 table, 1 %"
    assert forces["N3_n"] == pytest.approx(844.47, rel=0.01), "N3 vs seed 002 table, 1 %"


# -- --set after --design contradicting the design ------------------------------

@pytest.mark.parametrize("setting, message", [
    ("n_planets=3", "--set: 3 planets, but the design 'hub4' has n_planets = 4"),
    ("d_r=0.5", "--set: d_r = 0.5, but the design 'hub4' gives d_r = 0.187938524"),
    ("theta_deg=0,90,180,271", "--set: planet 4 at 271 deg, but the design 'hub4' puts it "
                               "at 270 deg"),
])
def test_spectrum_design_refuses_a_contradicting_set(setting, message, capsys):
    """Accepted without a word, while a scene refused the same contradiction
    (d_r = 0.187938524 m is the base diameter the hub4 design derives, as the scene's
    check reports it)."""
    _fails(capsys, ["spectrum", "--design", "hub4", "--set", setting], message)


def test_spectrum_design_accepts_a_set_the_design_leaves_open(capsys):
    """A mounting stiffness the geometry does not give still overrides; c_ru
    lowered by 10^4 lowers the first (rotational) frequency."""
    assert main(["spectrum", "--design", "hub4", "--json"]) == 0
    base = json.loads(capsys.readouterr().out)["modes"][0]["omega_rad_s"]
    assert main(["spectrum", "--design", "hub4", "--set", "c_ru=1e4", "--json"]) == 0
    soft = json.loads(capsys.readouterr().out)["modes"][0]["omega_rad_s"]
    assert soft < base, f"c_ru = 1e4 N/m should lower mode 1: {soft} vs {base} rad/s"


# -- [signal] revolutions, the documented minimum --------------------------------

def test_signal_revolutions_minimum_is_checked_before_the_work():
    """Revolutions = 1 (then the documented minimum) failed after the FE and the
    time integration with "allowed: >= 1"; it is now refused when the scene is parsed,
    and the minimum stated is one that works."""
    from hubvib.foundation.errors import SceneError
    from hubvib.signal.options import parse_signal_table

    with pytest.raises(SceneError, match=r"\[signal\] revolutions = 1; allowed: a finite "
                                         r"number in \[2, 10000\]"):
        parse_signal_table({"revolutions": 1})
    assert parse_signal_table({"revolutions": 2}).revolutions == 2.0


@pytest.mark.parametrize("revolutions, whole", [(1.0, 0), (2.0, 1), (10.0, 9)])
def test_signal_record_holds_one_whole_revolution_less_than_asked(revolutions, whole):
    """Why the minimum is 2: ``sampled`` gives 0 <= t < duration, so the
    angle-domain record of R revolutions holds R - 1 whole ones (computed here with the
    pipeline's own functions on a pure order-3 signal)."""
    import math

    import numpy as np

    from hubvib.signal.accelerometer import sampled
    from hubvib.signal.spectral import angle_domain

    revolution = np.sin(3 * 2 * math.pi * np.arange(64) / 64)
    t, values = sampled(revolution, 5.0, 2000.0, revolutions / 5.0)
    if whole == 0:
        with pytest.raises(ValueError, match="allowed: >= 1"):
            angle_domain(2 * math.pi * 5.0 * t, values, 64)
    else:
        assert angle_domain(2 * math.pi * 5.0 * t, values, 64).revolutions == whole


# -- console and text ------------------------------------------------------------

@pytest.fixture(scope="module")
def sweep_run(tmp_path_factory):
    """``hubvib run raba118_c_ru`` (the lumped sweep scene, plots included): its output
    folder and what it printed."""
    import contextlib
    import io

    out, printed = tmp_path_factory.mktemp("sweep") / "o", io.StringIO()
    with contextlib.redirect_stdout(printed):
        assert main(["run", "raba118_c_ru", "--out", str(out)]) == 0
    return out, printed.getvalue()


def test_sweep_console_shows_hz_beside_rad_s(sweep_run):
    """Sweep scenes print Hz beside rad/s, as crack scenes do; mode 1 of the Raba preset is
    336.454 rad/s (README worked example) = 53.548 Hz (omega / 2 pi)."""
    lines = sweep_run[1].splitlines()
    assert "base [Hz]" in lines[1] and "base [rad/s]" in lines[1], lines[1]
    assert lines[2].split()[2:4] == ["53.548", "336.454"], lines[2]


def test_scene_descriptions_are_whole_sentences(capsys):
    """``hubvib scenes`` cut descriptions after the first line, mid-sentence."""
    assert main(["scenes", "--json"]) == 0
    scenes = json.loads(capsys.readouterr().out)["scenes"]
    assert scenes["raba118_c_ru"].endswith("Lumped only: no FE stage."), scenes["raba118_c_ru"]
    assert scenes["raba118_five_planets"].endswith("when the ring softens."), scenes
    for name, what in scenes.items():
        assert what.endswith((".", ")")), f"{name}: {what!r} ends mid-sentence"


def test_tip_interference_names_the_design_keys(tmp_path, capsys):
    """Zero profile shifts said "GearPair.first: the path of contact runs below
    the form circle"; now the gear and the keys that fix it (shifts 0.2/0.2/0.6 of the
    same teeth assemble, checked here)."""
    text = ("[design]\nn_planets = 3\nmodule = 2.5e-3\nface_width = 0.03\n"
            "sun = {{ teeth = 20, shift = {} }}\nplanet = {{ teeth = 31, shift = {} }}\n"
            "ring = {{ teeth = 82, shift = {}, rim_thickness = 0.012 }}\n")
    zero, shifted = tmp_path / "zero.toml", tmp_path / "shifted.toml"
    zero.write_text(text.format(0, 0, 0), encoding="utf-8")
    shifted.write_text(text.format(0.2, 0.2, 0.6), encoding="utf-8")
    line = _fails(capsys, ["design", "check", str(zero)], "ring-planet mesh",
                  "below the planet's form circle (r = 36.8950 mm)", "design.planet.shift")
    assert "GearPair" not in line
    assert main(["design", "check", str(shifted)]) == 0


def test_missing_bearing_suggests_keys_that_exist():
    """The message suggested planet_bearing / carrier_bearing, which are not
    design-file keys; the keys are [design.bearings] planet / carrier."""
    from hubvib.reducer import lumped_parameters
    from hubvib.design import DesignError, read_design

    with pytest.raises(DesignError) as info:
        lumped_parameters(read_design(_design_without_bearings()))
    assert "[design.bearings] planet" in str(info.value)
    assert "planet_bearing" not in str(info.value)


def _design_without_bearings() -> Path:
    import tempfile

    folder = Path(tempfile.mkdtemp())
    path = folder / "nobearing.toml"
    path.write_text("[design]\nn_planets = 3\nmodule = 2.5e-3\nface_width = 0.03\n"
                    "sun = { teeth = 20, shift = 0.2 }\nplanet = { teeth = 31, shift = 0.2 }\n"
                    "ring = { teeth = 82, shift = 0.6, rim_thickness = 0.012 }\n"
                    "[design.lumped]\nc_ru = 1e6\nc_r = 1e8\nc_su = 1e6\nc_cu = 1e6\n",
                    encoding="utf-8")
    return path


@pytest.mark.parametrize("argv", [["spectrum", "--set", "c_ru=-1", "--json"],
                                  ["efficiency", "--ratio", "1e300", "--json"]])
def test_json_errors_are_a_json_object_on_stdout(argv, capsys):
    """With --json an error left stdout empty; now one JSON object with the same
    message, and the one line on stderr (exit 2)."""
    assert main(argv) == 2
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert data["exit_code"] == 2
    assert captured.err.strip() == f"hubvib: error: {data['error']}"


# -- part-width cracks in the signal study ---------------------------------------------

def test_signal_refuses_the_solid_scenes_part_width_cracks(tmp_path, capsys):
    """``hubvib signal raba118_crack_3d`` exited 0, simulating the semi-elliptic
    cracks as through-width ones; now refused before any FE work, naming the key."""
    out = tmp_path / "out"
    _fails(capsys, ["signal", "raba118_crack_3d", "--out", str(out)],
           "[crack] model = 'solid' gives semi-elliptic part-width cracks",
           "allowed for a signal study: [crack] model = \"plane\"")
    assert not out.exists()


# -- errors that name the file and line ----------------------------------------------

@pytest.mark.parametrize("content, words", [
    (b"scale,value\n1.0,\xe9\n", "is not UTF-8 text (line 2, byte 16 is 0xe9)"),
    (b"scale,value\nabc,1\n", "line 2: {'scale': 'abc', 'value': '1'} is not a level"),
    (b"scale,value\n1,2,3\n", "line 2:"),
])
def test_damaged_convergence_levels_file_is_named(content, words, tmp_path, capsys):
    """A damaged levels file of a resumed convergence study said only "'utf-8'
    codec can't decode byte 0xe9 in position 16" (or "could not convert string to
    float: 'abc'"); now the file, the line and what to do, before any level is computed."""
    out = tmp_path / "cv"
    out.mkdir()
    levels = out / "convergence_c_ru.levels.csv"
    levels.write_bytes(content)
    _fails(capsys, ["convergence", "c_ru", "--out", str(out)],
           f"convergence levels file {str(levels)!r}", words)


# "not enough values to unpack": every input that takes a pair or a list, given too
# few values, an empty string, a list for a table or a row of one column, is refused naming
# its key, flag or file (the origin of the reported message was not found again: this keeps
# each of these inputs from producing one).
_DESIGN = """[design]
n_planets = 3
module = 2.5e-3
face_width = 0.030
sun = {{ teeth = 20, shift = 0.2 }}
planet = {{ teeth = 31, shift = 0.2 }}
ring = {{ teeth = 82, shift = 0.6, rim_thickness = 0.012 }}
{extra}
"""


@pytest.mark.parametrize("argv, files, pieces", [
    (["spectrum", "--set", "theta=1,"], {}, ["theta = ''"]),
    (["spectrum", "--set", "="], {}, ["--set '='", "KEY=VALUE"]),
    (["spectrum", "--set", "c_rp_factors=1"], {}, ["c_rp_factors", "one factor per planet"]),
    (["spectrum", "--set", "n_planets=2,3"], {}, ["n_planets", "integer 1..32"]),
    (["shift", "--to", "theta", "1,2"], {}, ["--to 'theta'", "one value per planet"]),
    (["shift", "--to", "c_ru", ""], {}, ["--to c_ru = ''"]),
    (["harmonics", "--periods", "{p}", "--pulses-per-rev", "4", "--z2", "6"],
     {"p": ",\n,\n"}, ["--periods", "0 periods"]),
    (["torus-screw", "--lift-table", "{p}"], {"p": "a,b\n1\n"},
     ["--lift-table", "phi2_deg, alpha1_deg, alpha3_deg"]),
    (["spectrum", "--design", "{p}"], {"p": _DESIGN.format(extra="").replace(
        "sun = { teeth = 20, shift = 0.2 }", "sun = [20]")}, ["design.sun = [20]", "a table"]),
    (["spectrum", "--design", "{p}"], {"p": _DESIGN.format(extra="planet_angles_deg = [0]")},
     ["design.planet_angles_deg = [0]", "a list of 3"]),
    (["spectrum", "--design", "{p}"], {"p": _DESIGN.format(
        extra="[design.bearings]\nplanet = [16]")}, ["design.bearings.planet = [16]"]),
    (["run", "{p}"], {"p": '[reducer]\npreset = "raba118"\n[crack]\ndepths = [[0.0, 1]]\n'},
     ["[crack] depths = [[0.0, 1]]"]),
    (["run", "{p}"], {"p": '[reducer]\npreset = "raba118"\n[reducer.parameters]\ntheta = []\n'
                      '[crack]\ndepths = [0.0, 0.003]\n'}, ["theta has 0 planet angles"]),
])
def test_short_pairs_and_lists_name_their_key(argv, files, pieces, tmp_path, capsys):
    paths = {}
    for name, text in files.items():
        paths[name] = tmp_path / f"{name}.{'toml' if '[' in text else 'csv'}"
        paths[name].write_text(text, encoding="utf-8")
    line = _fails(capsys, [a.format(**paths) for a in argv], *pieces)
    assert "unpack" not in line and "values to" not in line, line


# -- what the cache checksum guards against ------------------------------------------

def test_cache_checksum_has_no_key(tmp_path):
    """An entry edited and re-summed is trusted: the checksum guards against
    damage, not tampering.  docs/reliability.md says so; this test keeps that true."""
    import hashlib

    from hubvib.runtime import fe_cache

    inputs, path = {"case": 1}, tmp_path / "entry.json"
    fe_cache.write_entry(path, inputs, {"c_ru_N_m": 1.0e10}, modules=MODULES)
    data = json.loads(path.read_text(encoding="utf-8"))
    data["result"]["c_ru_N_m"] = 2.0e10  # edited ...
    with pytest.raises(CacheEntryError, match="checksum mismatch"):
        path.write_text(json.dumps(data), encoding="utf-8")
        read_entry(path, inputs, modules=MODULES)  # ... is caught while the sum is stale
    data["checksum"] = hashlib.sha256(fe_cache.canonical(  # ... and re-summed: no key needed
        [fe_cache.FORMAT, fe_cache.FORMAT_VERSION, data["source"], inputs,
         data["result"]]).encode()).hexdigest()
    path.write_text(json.dumps(data), encoding="utf-8")
    assert read_entry(path, inputs, modules=MODULES) == {"c_ru_N_m": 2.0e10}
    page = (Path(__file__).parents[2] / "docs" / "reliability.md").read_text(encoding="utf-8")
    assert "guards against damage, not tampering" in page.replace("\n", " ")


# -- every figure in a report has a caption ------------------------------------------

def _uncaptioned(report: str) -> list[str]:
    lines = report.splitlines()
    return [line for i, line in enumerate(lines) if line.startswith("![")
            and not (i + 2 < len(lines) and lines[i + 2].startswith("*")
                     and lines[i + 2].endswith("*"))]


def test_every_figure_of_a_report_has_a_caption(sweep_run):
    """Each figure has a caption line under it saying what it shows (the lumped sweep's
    report)."""
    report = (sweep_run[0] / "report.md").read_text(encoding="utf-8")
    assert report.count("![") == 2 and _uncaptioned(report) == [], report


def test_captions_cover_every_figure_name_and_state_the_drawn_scale():
    """A figure without a caption is an error (found when its report is built);
    the stated magnifications are those the renders use."""
    from hubvib.render import captions
    from hubvib.render.fe import MAGNIFIED
    from hubvib.render.modes import AMPLITUDE

    with pytest.raises(KeyError, match="no caption"):
        captions.caption("new_figure.png")
    assert captions.FE_MAGNIFIED == MAGNIFIED
    assert f"{100 * AMPLITUDE:g} % of the ring radius" in captions.caption("renders/mode_01.gif")
    assert "3 % of the outer radius" in captions.caption("renders/fe_ring_mode_02.png")
    for name in ("pod.png", "carrier_position.png", "fe_crack_tip.png", "tsa.png"):
        assert captions.figure_lines(name)[2] == f"*{captions.CAPTIONS[name]}*"
