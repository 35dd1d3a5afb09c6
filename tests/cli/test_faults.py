"""Fault injection: Ctrl-C, killed parents, closed pipes, a full disk, concurrent
runs.  Real processes and signals where it matters; lumped-only scenes keep it fast.

A run either leaves its whole set of files in the output folder or leaves the folder as it
was; ``hubvib`` never shows a traceback, only one line (exit 2, or 130 for an interrupt).
"""
import errno
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from hubvib.cli import main

HUBVIB = [sys.executable, "-m", "hubvib.cli"]
#: N = 32 planets (the most allowed) and 6 shift values: seconds of lumped work, time
#: enough to interrupt it
SLOW_SCENE = """# slow lumped scene for interrupts
[reducer]
preset = "raba118"
[reducer.parameters]
n_planets = 32
[study]
parameter = "c_ru"
values = [8e5, 6e5, 5e5, 3e5, 2e5, 1e5]
[output]
plots = false
"""


def _error_line(err: str) -> str:
    """The one error line of a run's stderr (progress lines aside), no traceback."""
    assert "Traceback" not in err
    errors = [line for line in err.splitlines() if line.startswith("hubvib: error: ")]
    assert len(errors) == 1, err
    return errors[0]


def _visible(folder: Path) -> dict:
    """Every file under ``folder`` (hidden ones too) -> its bytes."""
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()} if folder.exists() else {}


def _snapshot_set(tmp_path, capsys, scene="raba118_five_planets") -> tuple[Path, dict]:
    out = tmp_path / "out"
    assert main(["run", scene, "--out", str(out)]) == 0
    capsys.readouterr()
    return out, _visible(out)


def _descendants_alive(pids) -> list[int]:
    alive = []
    for pid in pids:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if state != "Z":  # a zombie has exited; only its parent's wait is missing
            alive.append(pid)
    return alive


def _children(pid: int) -> list[int]:
    out = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[1]) == pid:
                out.append(int(entry.name))
    return out


# -- Ctrl-C ---------------------------------------------------------------------

def test_interrupt_in_process_is_one_line_and_keeps_the_folder(tmp_path, capsys, monkeypatch):
    """KeyboardInterrupt anywhere in a run: exit 130, exactly one line, and the
    output folder keeps the previous run's set byte for byte (the stage is removed)."""
    import hubvib.studies.sweep

    out, before = _snapshot_set(tmp_path, capsys)

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(hubvib.studies.sweep, "run_study", interrupted)
    assert main(["run", "raba118_c_ru", "--out", str(out)]) == 130
    assert capsys.readouterr().err.splitlines()[-1:] == ["hubvib: interrupted"]
    assert _visible(out) == before


@pytest.mark.slow
def test_sigint_to_a_real_run_exits_130_with_one_line(tmp_path):
    """SIGINT (what Ctrl-C sends) to a running ``hubvib run``: exit 130, stderr is
    the one line, no traceback, nothing left in the output folder."""
    scene = tmp_path / "slow.toml"
    scene.write_text(SLOW_SCENE)
    out = tmp_path / "out"
    run = subprocess.Popen([*HUBVIB, "run", str(scene), "--out", str(out)],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not out.exists() and run.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)  # the folder appears when the run has checked it, before the work
    assert out.exists() and run.poll() is None, "waited for the run's output folder while it ran"
    run.send_signal(signal.SIGINT)
    stdout, stderr = run.communicate(timeout=60)
    assert run.returncode == 130, stderr
    assert stderr == "hubvib: interrupted\n" and stdout == ""
    assert not out.exists() or not [p for p in out.rglob("*") if p.is_file()]


# -- worker processes -------------------------------------------------------------

POOL_PARENT = textwrap.dedent("""
    import sys, time
    from hubvib.runtime.process_pool import worker_pool

    if __name__ == "__main__":
        try:
            with worker_pool(2) as pool:
                short = pool.submit(time.sleep, 0.5)
                busy = pool.submit(time.sleep, 120)
                short.result()  # one worker now waits for work, idle; the other is busy
                print("ready", flush=True)
                busy.result()
        except KeyboardInterrupt:
            print("parent: interrupted", file=sys.stderr)
            sys.exit(130)
""")


def _start_pool_parent(tmp_path):
    script = tmp_path / "parent.py"
    script.write_text(POOL_PARENT)
    parent = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True, start_new_session=True)
    assert parent.stdout.readline() == "ready\n"
    deadline = time.monotonic() + 30
    while len(_children(parent.pid)) < 3 and time.monotonic() < deadline:
        time.sleep(0.02)  # two workers and multiprocessing's resource tracker
    children = _children(parent.pid)
    assert len(children) >= 2, children
    return parent, children


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM], ids=["kill-9", "SIGTERM"])
def test_pool_workers_exit_when_only_the_parent_is_killed(sig, tmp_path):
    """kill -9 / SIGTERM of the parent alone: every worker and the resource
    tracker exit (a plain ProcessPoolExecutor's workers live on, holding the pipes)."""
    parent, children = _start_pool_parent(tmp_path)
    try:
        os.kill(parent.pid, sig)
        parent.communicate(timeout=30)  # EOF on its pipes: no child holds them any more
        deadline = time.monotonic() + 30
        while _descendants_alive(children) and time.monotonic() < deadline:
            time.sleep(0.05)  # polls for the workers' exit (the event), up to the deadline
        assert _descendants_alive(children) == []
    finally:
        for pid in _descendants_alive(children):
            os.kill(pid, signal.SIGKILL)


def test_ctrl_c_to_the_process_group_stops_the_pool_quietly(tmp_path):
    """SIGINT to the whole group (a terminal's Ctrl-C) reaches the workers too:
    they print nothing (the idle one would print a KeyboardInterrupt traceback), the parent
    stops the pool without waiting for the 120 s task and exits 130."""
    parent, children = _start_pool_parent(tmp_path)
    try:
        os.killpg(parent.pid, signal.SIGINT)
        _, stderr = parent.communicate(timeout=60)
        assert parent.returncode == 130 and stderr == "parent: interrupted\n", stderr
        deadline = time.monotonic() + 30
        while _descendants_alive(children) and time.monotonic() < deadline:
            time.sleep(0.05)  # polls for the workers' exit (the event), up to the deadline
        assert _descendants_alive(children) == []
    finally:
        for pid in _descendants_alive(children):
            os.kill(pid, signal.SIGKILL)


# -- a closed pipe -----------------------------------------------------------------

@pytest.mark.parametrize("argv", [["spectrum"], ["shift", "--to", "c_ru", "1e5", "--json"]])
def test_closed_stdout_is_quiet(argv):
    """``hubvib ... | head -0``: the reader is gone before the first line; exit 141
    (128 + SIGPIPE, as a shell reports ``yes | head``), nothing on stderr."""
    run = subprocess.Popen([*HUBVIB, *argv], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    run.stdout.close()
    stderr = run.stderr.read().decode()
    assert run.wait(timeout=60) == 141 and stderr == ""


def _buffered_env() -> dict:
    """The environment with Python's default block-buffered stdout (a pipe's output then
    leaves at the flush, as for a user; PYTHONUNBUFFERED would write every print at once)."""
    return {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}


def test_help_into_a_closed_pipe_is_quiet():
    """``hubvib diagnose --help | head -0``: as for a command's own output, exit 141 and
    nothing on stderr; the help waits in the buffer, so the pipe shows at its flush, which
    must not be the interpreter's last one ("Exception ignored ... BrokenPipeError", exit
    120)."""
    run = subprocess.Popen([*HUBVIB, "diagnose", "--help"], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, env=_buffered_env())
    run.stdout.close()
    stderr = run.stderr.read().decode()
    assert (run.wait(timeout=60), stderr) == (141, "")


@pytest.mark.slow
def test_json_error_into_a_closed_pipe_is_exit_2_and_one_line(tmp_path):
    """Bad input with --json and stdout closed: the error's JSON object cannot be written;
    the answer stays exit 2 with its one line on stderr, and the unwritten object is not
    left for the interpreter's last flush ("Exception ignored ...", exit 120)."""
    measured = tmp_path / "measured.csv"
    measured.write_text("frequency_hz\n53.5\n")
    run = subprocess.Popen([*HUBVIB, "diagnose", "--scene", "raba118_c_ru", "--measured",
                            str(measured), "--json"], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, env=_buffered_env())
    run.stdout.close()
    stderr = run.stderr.read().decode()
    assert run.wait(timeout=60) == 2
    assert stderr.splitlines() == ["hubvib: error: --scene 'raba118_c_ru' has no [crack] "
                                   "study: diagnosis needs the crack sweep it compares the "
                                   "measurement with"]


@pytest.mark.parametrize("argv, code", [(["spectrum"], 141), (["diagnose", "--help"], 0)],
                         ids=["output", "help"])
def test_stdout_closed_from_the_start_is_quiet(argv, code):
    """``hubvib spectrum >&-``: no standard output at all (Python's ``sys.stdout`` is None,
    every print dropped): exit 141 and nothing on stderr, as for a closed pipe, no
    traceback; ``--help`` goes to stderr then (argparse) and exits 0."""
    run = subprocess.run([*HUBVIB, *argv], stderr=subprocess.PIPE, timeout=60,
                         preexec_fn=lambda: os.close(1))
    stderr = run.stderr.decode()
    assert run.returncode == code and "Traceback" not in stderr, stderr
    assert (stderr == "") if code == 141 else stderr.startswith("usage: hubvib diagnose")


# -- a full disk --------------------------------------------------------------------

@pytest.mark.slow
def test_full_disk_leaves_the_previous_set(tmp_path, capsys, monkeypatch):
    """ENOSPC while the third file is put in place: one line naming the file and
    what was discarded, exit 2, and the folder still holds the previous set byte for byte
    (no file of the failed run, no stage, no temporary file)."""
    out, before = _snapshot_set(tmp_path, capsys)
    real_replace = os.replace
    calls = []

    def full_disk(src, dst, *args, **kwargs):
        if str(out) in str(dst):
            calls.append(dst)
            if len(calls) == 3:
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return real_replace(src, dst, *args, **kwargs)

    monkeypatch.setattr(os, "replace", full_disk)
    assert main(["run", "raba118_c_ru", "--out", str(out)]) == 2
    line = _error_line(capsys.readouterr().err)
    assert "No space left on device" in line and str(out) in line
    assert f"nothing of this run was written to {str(out)!r}" in line
    assert _visible(out) == before


def test_full_tmpfs(tmp_path, capsys):
    """On a real full disk: a 32 kB tmpfs cannot take the five-planet set
    (results.json alone is ~32 kB): one line, exit 2, and the disk is left empty."""
    disk = tmp_path / "disk"
    disk.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=32k", "tmpfs", str(disk)],
                             capture_output=True)
    if mounted.returncode != 0:
        pytest.skip("cannot mount a tmpfs here (needs root)")
    try:
        out = disk / "out"
        assert main(["run", "raba118_five_planets", "--out", str(out)]) == 2
        assert "No space left on device" in _error_line(capsys.readouterr().err)
        assert list(disk.rglob("*")) == []
    finally:
        subprocess.run(["umount", str(disk)], check=True)


# -- concurrent runs ----------------------------------------------------------------

def test_busy_output_folder_is_refused(tmp_path, capsys):
    """A folder another run holds is refused at once in one line naming the folder
    and the holder's pid; the folder keeps its set."""
    from hubvib.foundation.output import folder_lock

    out, before = _snapshot_set(tmp_path, capsys)
    with folder_lock(out):
        assert main(["run", "raba118_c_ru", "--out", str(out)]) == 2
        lines = capsys.readouterr().err.strip().splitlines()
    assert lines == [f"hubvib: error: cannot write the output folder {str(out)!r}: another "
                     f"hubvib run (pid {os.getpid()}) is writing into it; wait for it to "
                     "finish or choose another output folder"]
    assert _visible(out) == before


@pytest.mark.slow
def test_two_scenes_at_once_never_mix(tmp_path):
    """Two runs of different scenes started together into one folder: each either
    writes its whole set or is refused; the folder then holds one scene's set only (the
    results.json scene and the baseline CSV's 9 + 3N modes agree, nothing else is there)."""
    out = tmp_path / "out"
    scenes = {"raba118_c_ru": 3, "raba118_five_planets": 5}
    runs = [subprocess.Popen([*HUBVIB, "run", name, "--out", str(out)], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True) for name in scenes]
    results = [(r.wait(timeout=300), r.communicate()[1]) for r in runs]
    assert all(code in (0, 2) for code, _ in results) and any(c == 0 for c, _ in results)
    for code, err in results:
        assert "Traceback" not in err
        if code == 2:
            assert "another hubvib run" in err
    import json

    data = json.loads((out / "results.json").read_text())
    n_planets = scenes[data["scene"]]
    rows = (out / "baseline_spectrum.csv").read_text().strip().splitlines()
    assert len(rows) - 1 == 9 + 3 * n_planets
    listed = set(json.loads((out / ".hubvib-files.json").read_text())["files"])
    assert listed == {p.name for p in out.iterdir() if not p.name.startswith(".")}
