"""Wall seconds per named part of one run: where the main job's time goes.

Library code wraps its parts in ``timed("fe")`` etc.; the seconds add up per
name for the whole process (a part may sit inside another: the crack study's
``write`` holds its ``plots`` and ``render``).  ``hubvib benchmark`` reads them
from the main job's subprocess: when the environment variable ``ENV`` names a
file, ``hubvib run`` writes them there as JSON (``write_requested``) after the
run (SI: seconds)::

    with timed("detection"):
        study = detection_study(...)
    stage_seconds()   # {"detection": 8.2}
"""
from __future__ import annotations

import json
import os
import time
from contextlib import contextmanager
from pathlib import Path

#: the environment variable naming the JSON file of the parts' seconds (``hubvib run``)
ENV = "HUBVIB_STAGE_SECONDS"

_SECONDS: dict[str, float] = {}


@contextmanager
def timed(part: str):
    """Add the block's wall time [s] to ``part`` (however the block ends)."""
    started = time.perf_counter()
    try:
        yield
    finally:
        _SECONDS[part] = _SECONDS.get(part, 0.0) + time.perf_counter() - started


def stage_seconds() -> dict[str, float]:
    """Every part timed so far in this process: name -> wall seconds [s]."""
    return dict(_SECONDS)


def write_requested() -> None:
    """Write ``stage_seconds()`` as JSON to the file ``ENV`` names (if it names one)."""
    path = os.environ.get(ENV)
    if path:
        Path(path).write_text(json.dumps(stage_seconds(), sort_keys=True), encoding="utf-8")
