"""Worker processes that never outlive the process that started them.

:func:`worker_pool` is a ``concurrent.futures.ProcessPoolExecutor`` (spawn start
method) whose workers

* exit when their parent dies, however it dies (``kill -9`` included): on Linux
  the kernel sends them SIGTERM (``prctl(PR_SET_PDEATHSIG)``); everywhere a
  watchdog thread sees the parent change (``os.getppid()``) within
  ``WATCH_SECONDS``.  With the workers gone, multiprocessing's resource tracker
  sees its pipe close and exits too;
* ignore SIGINT: Ctrl-C reaches the whole process group, and the parent alone
  turns it into one line and stops the pool (no traceback from each worker).

Leaving the ``with`` block by an exception (an error, Ctrl-C) cancels the
queued tasks and terminates the running ones instead of waiting for them::

    with worker_pool(2) as pool:
        futures = [pool.submit(task, case) for case in cases]

The parent-death signal follows the *thread* that started a worker: submit
from the thread that lives as long as the pool (the main thread).
"""
from __future__ import annotations

import os
import signal
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor
from contextlib import contextmanager
from multiprocessing import get_context

#: how often a worker's watchdog looks at its parent [s]
WATCH_SECONDS = 1.0
_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


class WorkerPool(ProcessPoolExecutor):
    """A process pool that stops at once when its block ends by an exception."""

    def submit(self, fn, /, *args, **kwargs):
        # a worker is spawned here; it starts with SIGINT blocked (the mask is inherited)
        # until its set-up ignores SIGINT, so Ctrl-C while it imports prints nothing
        with _sigint_blocked():
            return super().submit(fn, *args, **kwargs)

    def __exit__(self, exc_type, exc, tb):
        if exc_type is None:
            return super().__exit__(exc_type, exc, tb)
        self.terminate()
        return False

    def terminate(self) -> None:
        """Cancel the queued tasks and kill the running ones (their results are lost)."""
        processes = list((getattr(self, "_processes", None) or {}).values())
        self.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            if process.is_alive():
                process.terminate()
        for process in processes:
            process.join(timeout=5)


def worker_pool(workers: int, initializer=None, initargs: tuple = ()) -> WorkerPool:
    """A pool of ``workers`` spawned processes that die with this one (see the module doc).

    ``initializer(*initargs)`` runs in each worker after its own set-up.
    """
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers = {workers!r}, but it must be an integer >= 1")
    return WorkerPool(workers, mp_context=get_context("spawn"), initializer=_start_worker,
                      initargs=(os.getpid(), initializer, initargs))


def _start_worker(parent_pid: int, initializer, initargs) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    die_with_parent(parent_pid)
    if initializer is not None:
        initializer(*initargs)


@contextmanager
def _sigint_blocked():
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def die_with_parent(parent_pid: int) -> None:
    """Make this process exit when ``parent_pid`` (its parent) dies."""
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)
        except (OSError, AttributeError):
            pass  # the watchdog below still works
    if os.getppid() != parent_pid:  # the parent died before prctl took effect
        os._exit(1)
    threading.Thread(target=_watch, args=(parent_pid,), name="parent-watchdog",
                     daemon=True).start()


def _watch(parent_pid: int) -> None:
    while os.getppid() == parent_pid:
        time.sleep(WATCH_SECONDS)
    os._exit(1)
