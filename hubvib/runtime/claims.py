"""Work that this process and a worker pool may both take: each piece is done once, by
whoever claims it first.

A task queued on a ``ProcessPoolExecutor`` cannot be cancelled once the executor has moved
it to its call queue (up to ``workers + 1`` tasks ahead of the workers), though no worker
may start it for a long time (behind a render).  So the pool is given a wrapper that first
claims the task (an exclusive create of a file named for it, ``O_CREAT | O_EXCL``: atomic
between processes), and this process claims the same way before it computes a task
itself.  The loser of a claim does nothing: a worker's wrapper returns ``NOT_CLAIMED``.
After :meth:`Claims.close` every unstarted wrapper finds no folder and returns
``NOT_CLAIMED`` too, so work queued ahead and then not needed costs nothing.  Should the
folder vanish while the claims are open (a temporary-folder cleaner), this process claims
every key and the workers none: each piece is still done once, here.

    with Claims() as claims:
        future = claims.submit(pool, "3 mm", case_at, 0.003)
        ...
        if claims.claim("3 mm"):      # no worker has begun it: compute it here
            case = case_at(0.003)
        else:
            case = future.result()
"""
from __future__ import annotations

import enum
import errno
import os
import shutil
import tempfile

__all__ = ["Claims", "NOT_CLAIMED"]


class _Outcome(enum.Enum):
    NOT_CLAIMED = "another process claimed the work first"


#: what a pool task returns when another process claimed its work first (an enum member:
#: the same object after pickling, never a task's own result)
NOT_CLAIMED = _Outcome.NOT_CLAIMED


class Claims:
    """A folder of claim files, one per task key (a short string); see the module doc."""

    def __init__(self):
        self.folder = tempfile.mkdtemp(prefix=f"hubvib-claims-{os.getpid()}-")

    def claim(self, key: str) -> bool:
        """True when this process now holds ``key`` (also when the folder has vanished: the
        workers then claim nothing), False when a worker claimed it first."""
        return _claim(self.folder, key, vanished=True)

    def submit(self, pool, key: str, function, *args):
        """``function(*args)`` on ``pool`` (``runtime.engines.submit``) if a worker claims
        ``key`` first; the future's result is ``NOT_CLAIMED`` otherwise."""
        from .engines import submit

        return submit(pool, claimed_call, self.folder, key, function, *args)

    def close(self) -> None:
        """Remove the folder: every task not yet claimed stays unclaimed.  It is renamed
        first (atomic), so no claim lands while its files are removed."""
        closed = f"{self.folder}.closed"
        try:
            os.rename(self.folder, closed)
        except OSError:
            closed = self.folder
        shutil.rmtree(closed, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def _claim(folder: str, key: str, vanished: bool = False) -> bool:
    """Claim ``key`` in ``folder``; ``vanished``: the answer when the folder is gone (a
    worker: closed, every task not claimed by now is unneeded)."""
    try:
        fd = os.open(os.path.join(folder, key), os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600)
    except FileExistsError:
        return False
    except OSError as exc:
        if exc.errno == errno.ENOENT:
            return vanished
        raise
    os.close(fd)
    return True


def claimed_call(folder: str, key: str, function, *args):
    """On a worker: ``function(*args)`` if this worker claims ``key`` first, else
    ``NOT_CLAIMED``."""
    if not _claim(folder, key):
        return NOT_CLAIMED
    return function(*args)
