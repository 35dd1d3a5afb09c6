"""Ctrl-C and the worker processes of a LocalCluster: only ``hubvib`` sees it.

A terminal sends SIGINT to its whole foreground process group.  The worker processes a
LocalCluster spawns are in that group: one interrupted while it started printed a
KeyboardInterrupt traceback (2-4 of them), and a Ctrl-C inside ``LocalCluster(...)``
left a half-built cluster whose close at exit printed one more, before ``hubvib``'s one
line ``hubvib: interrupted``.

:func:`held_interrupts` blocks SIGINT in the calling (main) thread while the cluster is
built.  The cluster's event-loop thread is created then and inherits the blocked mask, and
so does every worker process it spawns (a blocked signal stays blocked across fork and
exec; Python never unblocks it): the workers never see the terminal's SIGINT.
multiprocessing's resource tracker is started first: starting it later, from a thread of
the cluster, unblocks SIGINT in that thread (``resource_tracker.ensure_running`` blocks
and then *unblocks* it) and the workers it spawned then saw the Ctrl-C again.  The Ctrl-C
is not lost: it stays pending and is raised as KeyboardInterrupt in ``hubvib`` as soon as
the cluster is built and assigned, and ``hubvib`` then closes the cluster, which stops its
workers.
"""
from __future__ import annotations

import signal
import threading
from contextlib import contextmanager
from multiprocessing import resource_tracker


@contextmanager
def held_interrupts():
    """Block SIGINT in this thread (and in the threads and processes started here) for the
    block; a SIGINT that came meanwhile is delivered when the block ends.  Outside the
    main thread, or where signal masks are unavailable, nothing is changed."""
    if (threading.current_thread() is not threading.main_thread()
            or not hasattr(signal, "pthread_sigmask")):
        yield
        return
    resource_tracker.ensure_running()  # now, not from a cluster thread (module docstring)
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)
