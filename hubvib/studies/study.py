"""What a study kind is: how it runs into an output folder, and what ``hubvib run`` says of
its result (the ``--json`` object and the printed lines).  ``hubvib.studies.kinds`` is the
registry; a scene's ``kind`` names its study."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable


@dataclass(frozen=True)
class Study:
    """One study kind.

    ``run(scene, staged)`` computes and writes every file into the staged folder and
    returns the result (its ``files`` are the paths written); ``summary(scene, result,
    folder, files)`` is the ``hubvib run --json`` object; ``lines(scene, result, folder)``
    are the printed lines.  Library code: nothing here prints.
    """

    kind: str
    run: Callable[[Any, Path], Any]
    summary: Callable[[Any, Any, Path, list], dict]
    lines: Callable[[Any, Any, Path], list]
