"""SIGTERM and SIGINT at any moment of ``hubvib run``: one line, the documented exit code,
no warning or traceback, nothing left in the output folder (hubvib.cli's module docstring).

A signal is sent once, or twice in a row to the whole process group (what ``timeout`` does:
the command, then its group), at stage boundaries (each progress line on stderr) and, in
the slow sweep, at fixed delays into the FE crack study of ``hub4_crack``, whose worker pool
starts, computes and is stopped there."""
from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from hubvib.foundation.output import LOCK_NAME, MANIFEST_NAME, STAGE_PREFIX

#: a traceback frame of hubvib.cli's main
MAIN_FRAME = re.compile(r'cli\.py", line \d+, in main\b')
EXPECTED = {signal.SIGTERM: (143, "hubvib: terminated"),
            signal.SIGINT: (130, "hubvib: interrupted")}

#: a lumped sweep of two values without plots: each stage over in well under a second
SMALL_SCENE = """
[reducer]
preset = "raba118"
[study]
parameter = "c_ru"
values = [5e5, 1e5]
[output]
folder = "out"
plots = false
"""


def _start(folder: Path, argv: list[str]) -> subprocess.Popen:
    env = dict(os.environ, HUBVIB_CACHE=str(folder / "cache"))
    return subprocess.Popen([sys.executable, "-m", "hubvib.cli", *argv], cwd=folder, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)


def _send(process: subprocess.Popen, signum: int, twice: bool) -> None:
    try:
        process.send_signal(signum)
        if twice:  # as `timeout` does: then to the whole group (the workers too)
            time.sleep(0.01)
            os.killpg(process.pid, signum)
    except ProcessLookupError:  # it ended meanwhile
        pass


def _check(process: subprocess.Popen, folder: Path, signum: int, when: str,
           stderr_before: str = "") -> None:
    try:
        _, err = process.communicate(timeout=90)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
    err = stderr_before + err
    code, line = EXPECTED[signum]
    what = f"{signal.Signals(signum).name} {when}: exit {process.returncode}, stderr {err!r}"
    out = folder / "out"
    left = sorted(p.name for p in out.iterdir()) if out.is_dir() else []
    if process.returncode != 0 and not MAIN_FRAME.search(err) and "hubvib:" not in err and \
            not left:
        return  # before hubvib.cli's main ran (interpreter start-up, the import of hubvib.cli):
        # the signal's default action (for SIGINT a KeyboardInterrupt in site, runpy or the
        # import, or exit 1 "Failed to import the site module"); nothing was started
    assert "leaked" not in err and "Traceback" not in err and "Warning" not in err, what
    assert LOCK_NAME not in left and not any(n.startswith(STAGE_PREFIX) for n in left), (
        f"{what}; left in the output folder: {left}")
    if process.returncode == 0:  # it had finished before the signal came
        assert line not in err and MANIFEST_NAME in left, what
        return
    assert process.returncode == code, f"{what}; expected exit {code} (hubvib.cli docstring)"
    assert err.count(line) == 1 and err.rstrip().endswith(line), what
    assert left in ([], [MANIFEST_NAME]) or MANIFEST_NAME in left, what


@pytest.mark.parametrize("signum,twice", [
    pytest.param(signal.SIGTERM, True, marks=pytest.mark.slow),
    pytest.param(signal.SIGTERM, False, marks=pytest.mark.slow),
    pytest.param(signal.SIGINT, False, marks=pytest.mark.slow),
    pytest.param(signal.SIGINT, True, marks=pytest.mark.slow)],
    ids=["SIGTERM-twice", "SIGTERM", "SIGINT", "SIGINT-twice"])
def test_a_stop_at_each_stage_boundary_is_one_line_and_leaves_nothing(tmp_path, signum, twice):
    """The signal at the start and right after each progress line of a small lumped run."""
    (tmp_path / "small.toml").write_text(SMALL_SCENE)
    boundaries, k = 0, 0
    while True:
        folder = tmp_path / f"try{k}"
        folder.mkdir()
        (folder / "small.toml").write_text(SMALL_SCENE)
        process = _start(folder, ["run", "small.toml"])
        seen = ""
        if k == 0:
            time.sleep(0.3)  # while the interpreter imports hubvib
        for _ in range(k):  # wait for the k-th progress line, then send
            line = process.stderr.readline()
            if not line:
                break
            seen += line
        finished = k > 0 and seen.count("\n") < k
        _send(process, signum, twice)
        _check(process, folder, signum, f"after {k} progress line(s)", seen)
        if finished or process.returncode == 0:
            break
        boundaries, k = boundaries + 1, k + 1
        assert k < 10, "the small run prints a few progress lines"
    assert boundaries >= 2, "stopped at the start and after at least one stage"


@pytest.mark.slow
@pytest.mark.parametrize("signum,twice", [(signal.SIGTERM, False), (signal.SIGTERM, True),
                                          (signal.SIGINT, True)],
                         ids=["SIGTERM", "SIGTERM-twice", "SIGINT-group"])
def test_a_stop_at_any_moment_of_a_crack_study_with_a_worker_pool(tmp_path, signum, twice):
    """``hub4_crack`` from a cold cache (its pool starts, spawns, computes): a sweep of
    delays across imports, pool start-up and the FE cases."""
    for delay in (0.2, 0.6, 1.0, 1.5, 2.0, 3.0, 4.5, 6.0):
        folder = tmp_path / f"at{delay}"
        folder.mkdir()
        process = _start(folder, ["run", "hub4_crack", "--out", "out"])
        time.sleep(delay)
        _send(process, signum, twice)
        _check(process, folder, signum, f"{delay} s into hub4_crack")


@pytest.mark.parametrize("signum", [signal.SIGTERM,
                                    pytest.param(signal.SIGINT, marks=pytest.mark.slow)])
def test_a_stop_while_the_imports_run_is_one_line(tmp_path, signum):
    """Early, while numpy and the rest are imported: an extension module's import turns the
    exception raised inside it into an ImportError that no longer names it (numpy: 'could
    not import module "datetime"', a traceback and exit 1); it is still the stop's line."""
    for delay in (0.05, 0.1, 0.15, 0.2, 0.3):
        folder = tmp_path / f"at{delay}"
        folder.mkdir()
        (folder / "small.toml").write_text(SMALL_SCENE)
        process = _start(folder, ["run", "small.toml"])
        time.sleep(delay)
        _send(process, signum, twice=False)
        _check(process, folder, signum, f"{delay} s in, while importing")
