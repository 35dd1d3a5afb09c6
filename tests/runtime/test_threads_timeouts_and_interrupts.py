"""Engines and interrupts (a scheduler that never answers, Ctrl-C,
the same digits after a killed run)."""
from __future__ import annotations

import numpy  # noqa: F401 - loads the OpenBLAS whose threads are compared
import pytest

from hubvib.foundation.blas import blas_thread_counts
from hubvib.runtime.engines import Execution, run_cases


def _threads(item):
    """The BLAS thread counts where the case runs (a pool worker or this process)."""
    return item, blas_thread_counts()


def _collect(items, workers):
    seen = {}
    run_cases(_threads, items, lambda item, value: seen.update({item: value}),
              Execution("local", None, None, 10.0), workers)
    return seen


@pytest.mark.slow
def test_a_case_run_in_process_has_the_pool_workers_blas_threads():
    """After kill -9 the one case left ran in this process with the default
    (multi-threaded) BLAS, the others in single-threaded pool workers: the rerun differed
    in the last digits (7e-16 relative).  Same threads now, so the same digits."""
    if not blas_thread_counts():
        pytest.skip("no OpenBLAS/MKL found in this process (no thread count to compare)")
    pool = _collect(["a", "b"], workers=2)
    here = _collect(["c"], workers=2)  # one case left: run in this process
    assert {tuple(v[1]) for v in pool.values()} == {(1,) * len(pool["a"][1])}, pool
    assert here["c"][1] == [1] * len(here["c"][1]), \
        f"in-process case ran with BLAS threads {here['c'][1]}, pool workers with 1"


def test_in_process_cases_restore_the_threads_after():
    """The limit holds only while the case runs (the lumped batch and the report
    keep the process's own threads)."""
    from hubvib.runtime.engines import _load_mkl

    _load_mkl()  # as in-process cases do first: MKL's threads are among those compared
    before = blas_thread_counts()
    here = _collect(["c"], workers=1)
    assert set(here["c"][1]) <= {1}
    assert blas_thread_counts() == before


@pytest.fixture
def silent_server():
    """A loopback address that accepts TCP connections and never answers (another
    service, a stopped process): ``Client()`` hung on it for ever."""
    import socket
    import threading

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    accepted, stop = [], threading.Event()

    def serve():
        while not stop.is_set():
            try:
                accepted.append(server.accept()[0])
            except OSError:
                return

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield f"tcp://127.0.0.1:{server.getsockname()[1]}", accepted
    stop.set()
    server.close()
    for conn in accepted:
        conn.close()


@pytest.mark.slow  # two 1 s timeouts and the import of dask.distributed: ~3 s
def test_scheduler_that_accepts_but_never_answers_fails_within_the_timeout(silent_server):
    """The connection is accepted, the handshake never answered: before, ``timeout_s``
    bounded only the connect and the run hung (measured: > 60 s at timeout_s = 2); now one
    EngineError naming the address and the timeout."""
    pytest.importorskip("distributed")
    from hubvib.runtime.engines import EngineError, check_reachable, parse_execution_table

    address, accepted = silent_server
    execution = parse_execution_table({"engine": "dask", "scheduler": address, "timeout_s": 1})
    with pytest.raises(EngineError, match="accepts the connection but did not answer within "
                                          "1 s"):
        check_reachable(execution)
    delivered = []
    with pytest.raises(EngineError, match=address):
        run_cases(abs, [1, 2], lambda item, value: delivered.append(item), execution, 2)
    assert accepted and delivered == []


def test_ctrl_c_while_the_output_lock_is_taken_leaves_no_lock_file(tmp_path, monkeypatch):
    """A Ctrl-C between creating ``.hubvib.lock`` and the block that removes it
    left an empty lock file.  The SIGINT is sent (to this process, as a terminal does)
    from inside the lock's own write, deterministically in that window."""
    import os
    import signal

    from hubvib.foundation import output

    real_write = os.write

    def write_then_interrupt(fd, data):
        os.kill(os.getpid(), signal.SIGINT)
        return real_write(fd, data)

    reached = []
    with pytest.raises(KeyboardInterrupt):
        monkeypatch.setattr(os, "write", write_then_interrupt)
        try:
            with output.folder_lock(tmp_path):
                reached.append("inside")
        finally:
            monkeypatch.undo()
    assert not (tmp_path / output.LOCK_NAME).exists(), "the lock file was left behind"
    assert reached == [], "the interrupt is raised before the locked block runs"
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_a_late_ctrl_c_cannot_escape_main_as_a_program(monkeypatch):
    """Called as the program (argv None), a SIGINT that arrives as main returns
    is ignored instead of escaping (the process then died by the signal, not exit 130,
    1 run in 25).  Here it is sent from the command itself, as it returns."""
    import signal
    import sys

    from hubvib import cli

    monkeypatch.setattr(sys, "argv", ["hubvib", "spectrum", "--json"])
    real = cli._main

    def returns_while_interrupted(argv):
        code = real(argv)
        signal.raise_signal(signal.SIGINT)  # the handler runs at the next check
        return code

    monkeypatch.setattr(cli, "_main", returns_while_interrupted)
    previous = signal.getsignal(signal.SIGINT)
    try:
        assert cli.main() in (0, 130)  # never KeyboardInterrupt out of main
        assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
    finally:
        signal.signal(signal.SIGINT, previous)


class _Lines:
    """A stream that is not a terminal and records whole lines; ``arrived`` is set at the
    first one (the test waits on it, not on a sleep)."""

    def __init__(self):
        import threading

        self.lines, self.arrived = [], threading.Event()

    def write(self, text):
        self.lines += [line for line in text.splitlines() if line]
        if self.lines:
            self.arrived.set()

    def flush(self):
        pass

    def isatty(self):
        return False


def test_work_without_a_count_says_it_is_working_off_a_terminal():
    """Off a terminal plots and renders ran 32 s without a line; ``working``
    prints one at least every HEARTBEAT_S (5 s) until the work ends, and none after."""
    from hubvib.runtime.progress import HEARTBEAT_S, working

    assert HEARTBEAT_S <= 5.0, "the documented bound: a line at least every 5 s of work"
    stream = _Lines()
    with working("plots", every=0.01, stream=stream):
        assert stream.arrived.wait(30), "no heartbeat line within 30 s"
    count = len(stream.lines)
    assert stream.lines[0].startswith("hubvib: plots: working, ")
    with working("quiet", every=3600, stream=stream):
        pass  # ends at once: no line, and the thread is joined
    assert len(stream.lines) == count


def test_working_is_silent_on_a_terminal():
    """On a terminal the bars and the command's own output say enough."""
    from hubvib.runtime.progress import working

    stream = _Lines()
    stream.isatty = lambda: True
    with working("plots", every=0.001, stream=stream):
        pass
    assert stream.lines == []


PROGRAM = """
import ctypes, sys
from hubvib import cli

def interrupted_import(argv):
    # a Ctrl-C inside code an extension runs with PyRun_String while being imported,
    # caught as main catches it
    run = ctypes.pythonapi.PyRun_String
    run.restype, run.argtypes = ctypes.py_object, [ctypes.c_char_p, ctypes.c_int,
                                                   ctypes.py_object, ctypes.py_object]
    try:
        run(b"raise KeyboardInterrupt", 257, {}, {})  # 257: Py_file_input
    except KeyboardInterrupt:
        cli._say("hubvib: interrupted")
        return cli.EXIT_INTERRUPTED
    return 0

cli._main = interrupted_import
sys.exit(cli.main())
"""


def test_python_m_exits_130_after_a_ctrl_c_during_the_imports(tmp_path):
    """``python -m hubvib.cli`` interrupted while importing printed the one line
    and chose exit 130, then CPython killed it by SIGINT (a flag left by the interrupted
    PyRun_* call; 13 of 40 storm runs).  The same path, made deterministic."""
    import subprocess
    import sys

    (tmp_path / "interrupted_program.py").write_text(PROGRAM, encoding="utf-8")
    run = subprocess.run([sys.executable, "-m", "interrupted_program"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 130 and run.stderr == "hubvib: interrupted\n", \
        (run.returncode, run.stderr)
