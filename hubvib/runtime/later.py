"""A value given by ``result()``, as a future's, but computed in this process when asked.

It lets work queued elsewhere (a process pool's futures) and work done here share one
way of being waited for::

    pending = Later(lambda: assemble([f.result() for f in futures]))
    ...                       # this process does something else meanwhile
    value = pending.result()  # waits for the futures, then assembles
"""
from __future__ import annotations


class Later:
    """``result()`` returns ``compute()``, computed on the first call and kept."""

    _UNSET = object()

    def __init__(self, compute):
        self.compute = compute
        self.value = self._UNSET

    def result(self):
        if self.value is self._UNSET:
            self.value = self.compute()
        return self.value
