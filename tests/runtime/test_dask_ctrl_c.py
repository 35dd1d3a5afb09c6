"""Ctrl-C during a run on a LocalCluster printed 2-4 worker
tracebacks (KeyboardInterrupt) before the one line ``hubvib: interrupted``.  The terminal's
SIGINT reaches the whole foreground process group, the worker processes included; they now
ignore it (``hubvib.runtime.dask_worker``, their preload) and ``hubvib`` closes the cluster.

The test sends SIGINT to the whole process group of a real ``hubvib run`` (as a terminal
does) at a known point: once the progress line of the first finished FE case says the
cluster is up and the other cases are running on its workers (it waits on that line, not on
a sleep)."""
from __future__ import annotations

import importlib.util
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

#: only the slow test below needs dask.distributed: found, not imported, so collecting this
#: module in the default run costs no second of dask imports
pytestmark = pytest.mark.skipif(importlib.util.find_spec("distributed") is None,
                                reason="distributed not installed")

SCENE = """
[reducer]
preset = "raba118"

[crack]
depths = [0.0, 0.004, 0.008, 0.012, 0.016]
apply = "series"
accuracy = "fast"
workers = 2

[execution]
engine = "dask"
workers = 2

[output]
folder = "{out}"
plots = false
renders = false
"""

#: progress lines ``hubvib`` writes off a terminal (hubvib.runtime.progress)
PROGRESS = re.compile(r"^(hubvib: .*(: working, \d+ s| done \(.*\))|FE crack cases: .*)$")


def _children(pid: int) -> set[int]:
    """Process ids whose parent is ``pid`` (from /proc)."""
    found = set()
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                found.add(int(entry.name))
    return found


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


def _gone(pids: set[int], within: float = 30.0) -> list[int]:
    """The processes of ``pids`` still alive after waiting up to ``within`` [s] for them to
    end (a condition polled, not a fixed sleep: the resource tracker ends on its own once
    its pipe closes)."""
    deadline = time.monotonic() + within
    while True:
        alive = [pid for pid in pids if _alive(pid)]
        if not alive or time.monotonic() > deadline:
            return alive
        time.sleep(0.05)


def _worker_importing(pid: int) -> bool:
    """A LocalCluster worker process of ``pid`` runs Python: its SIGINT handler is installed
    (``SigCgt`` in /proc), so it is importing dask and distributed, the seconds in which
    a Ctrl-C gave its traceback.  (Earlier, before Python's handler, a SIGINT only ends
    the process silently.)"""
    for child in _children(pid):
        try:
            line = Path(f"/proc/{child}/cmdline").read_bytes()
            status = Path(f"/proc/{child}/status").read_text()
        except OSError:
            continue
        caught = int(next(x for x in status.splitlines() if x.startswith("SigCgt:")).split()[1],
                     16)
        if (b"multiprocessing" in line and b"resource_tracker" not in line
                and caught & (1 << (signal.SIGINT - 1))):
            return True
    return False


@pytest.mark.slow  # a LocalCluster and a few FE cases: ~10-25 s on 2 cores
@pytest.mark.parametrize("when", ["a worker is starting", "cases are running"])
def test_ctrl_c_during_a_dask_run_prints_one_line_and_leaves_no_worker(when, tmp_path):
    """The SIGINT goes to the whole process group, as a terminal's Ctrl-C does: while the
    first worker process is still starting (it used to die in its imports with a
    traceback, and the half-built cluster printed one more at exit), or once the first
    FE case has finished on the cluster and the others are running."""
    out = tmp_path / "out"
    scene = tmp_path / "dask.toml"
    scene.write_text(SCENE.format(out=out), encoding="utf-8")
    env = dict(os.environ, HUBVIB_CACHE=str(tmp_path / "cache"))
    run = subprocess.Popen([sys.executable, "-m", "hubvib.cli", "run", str(scene)],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                           start_new_session=True)  # its own process group, as a shell job
    lines, children = [], set()
    try:
        if when == "a worker is starting":
            deadline = time.monotonic() + 120
            while not _worker_importing(run.pid):
                assert run.poll() is None and time.monotonic() < deadline, \
                    "no LocalCluster worker process appeared"
                time.sleep(0.01)
        else:
            for line in run.stderr:  # a finished case: the cluster is up, cases run
                lines.append(line.rstrip("\n"))
                if line.startswith("FE crack cases: "):
                    break
            else:
                pytest.fail(f"no FE case finished: {lines}")
        children = _children(run.pid)
        os.killpg(run.pid, signal.SIGINT)  # a terminal's Ctrl-C: the whole group
        _, rest = run.communicate(timeout=120)
    finally:
        if run.poll() is None:
            os.killpg(run.pid, signal.SIGKILL)
            run.wait()
    after = [line for line in rest.splitlines() if not PROGRESS.match(line)]
    assert run.returncode == 130, (run.returncode, lines, rest)
    assert after == ["hubvib: interrupted"], f"stderr after the Ctrl-C: {after}"
    assert "Traceback" not in rest and "KeyboardInterrupt" not in rest, rest
    assert children, "the LocalCluster had started processes"
    assert not _gone(children), "a worker process outlived hubvib"
    assert not (out / ".hubvib.lock").exists(), "the output folder's lock was left behind"
