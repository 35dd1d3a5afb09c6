"""Preload of the worker processes of ``hubvib``'s LocalCluster: leave Ctrl-C to ``hubvib``.

A terminal sends SIGINT to its whole foreground process group, and the worker processes a
LocalCluster spawns are in it: each raised KeyboardInterrupt and printed its traceback
(2-4 of them) before ``hubvib``'s one line ``hubvib: interrupted``.  Imported in each
worker process as it starts (``LocalCluster(preload=[__name__])``), this module makes the
worker ignore SIGINT; ``hubvib`` itself still gets the Ctrl-C and closes the cluster,
which stops the workers.  A worker also exits when ``hubvib`` dies
(distributed's worker processes watch their parent).
"""
from __future__ import annotations

import signal
import threading

if threading.current_thread() is threading.main_thread():  # signals: main thread only
    signal.signal(signal.SIGINT, signal.SIG_IGN)
