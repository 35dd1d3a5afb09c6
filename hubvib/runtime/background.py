"""One task in a worker process while this process goes on with other work.

The main job's FE-ring render needs only the scene (not the FE results, not the
detection study), so it can run beside the lumped and detection stages and the
plots: on two cores that overlaps ~15 s of rendering with them.  The worker is a
``worker_pool`` process (it dies with this one, ignores Ctrl-C) with one BLAS
thread (``engines.SINGLE_THREADED``, as every FE worker), so it does not
oversubscribe the cores the caller's own work uses::

    with background(render, scene, folder) as task:
        ...                       # other work, here
        files = task.result()     # waits; the task's exception is raised here

Leaving the block by an exception stops the worker (its result is not wanted).
With ``inline=True`` the task runs in this process when ``result`` is asked for
(no worker: nothing to overlap, or a caller that wants one process).
"""
from __future__ import annotations

from contextlib import contextmanager

from hubvib.runtime.engines import SINGLE_THREADED, _environment
from hubvib.runtime.process_pool import worker_pool


class _Inline:
    """The task, run here when its result is asked for."""

    def __init__(self, function, args):
        self.function, self.args = function, args

    def result(self):
        return self.function(*self.args)


@contextmanager
def background(function, *args, inline: bool = False):
    """``function(*args)`` in one worker process (``inline``: here, on ``result()``);
    yields an object whose ``result()`` waits for it and returns its value."""
    if inline:
        yield _Inline(function, args)
        return
    with worker_pool(1) as pool:
        with _environment(SINGLE_THREADED):  # the worker is spawned on submit
            future = pool.submit(function, *args)
        yield future
