"""Progress of long work on stderr: a tqdm bar on a terminal, plain lines otherwise.

Output that is not a terminal (a log file, CI, ``2> run.log``) gets one line
per update, so a long run is never silent for minutes::

    with progress(5, "FE crack cases", "case", initial=2) as bar:
        for ...:
            bar.update(note="depth 4 mm")
    # FE crack cases: 3/5 cases (depth 4 mm), 41 s, about 82 s left

    stage("lumped spectra", started)   # hubvib: lumped spectra done (0.3 s)

``stage`` lines appear only when stderr is not a terminal (on a terminal the
command's own output and the bars say enough).
"""
from __future__ import annotations

import sys
import time


def interactive(stream=None) -> bool:
    """True when ``stream`` (default stderr) is a terminal."""
    stream = sys.stderr if stream is None else stream
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


class LineProgress:
    """One line per update: done/total, elapsed and estimated remaining time [s]."""

    def __init__(self, total: int, what: str, unit: str = "", initial: int = 0, stream=None):
        self.total, self.what, self.unit = total, what, unit
        self.initial = self.done = initial
        self.stream = stream
        self.started = time.perf_counter()

    def update(self, n: int = 1, note: str = "") -> None:
        self.done += n
        elapsed = time.perf_counter() - self.started
        ran = self.done - self.initial
        left = elapsed / ran * (self.total - self.done) if ran > 0 else float("nan")
        unit = f" {self.unit}{'s' if self.total != 1 else ''}" if self.unit else ""
        estimate = f", about {left:.0f} s left" if self.done < self.total and ran > 0 else ""
        _say(f"{self.what}: {self.done}/{self.total}{unit}{f' ({note})' if note else ''}, "
             f"{elapsed:.0f} s{estimate}", self.stream)

    def close(self) -> None:
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


class BarProgress:
    """A tqdm bar; ``note`` becomes its postfix."""

    def __init__(self, total: int, what: str, unit: str = "", initial: int = 0, stream=None):
        from tqdm import tqdm

        self.bar = tqdm(total=total, initial=initial, desc=what, unit=unit or "it",
                        file=stream or sys.stderr)

    def update(self, n: int = 1, note: str = "") -> None:
        if note:
            self.bar.set_postfix_str(note, refresh=False)
        self.bar.update(n)

    def close(self) -> None:
        self.bar.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def progress(total: int, what: str, unit: str = "", initial: int = 0, stream=None):
    """A bar on a terminal (if tqdm is installed), else one line per update; see the module."""
    if interactive(stream):
        try:
            return BarProgress(total, what, unit, initial, stream)
        except ImportError:
            pass
    return LineProgress(total, what, unit, initial, stream)


def stage(what: str, started: float | None = None, stream=None) -> None:
    """``hubvib: <what> done (<seconds> s)`` when stderr is not a terminal.

    ``started`` is a ``time.perf_counter()`` value.
    """
    if interactive(stream):
        return
    took = "" if started is None else f" ({time.perf_counter() - started:.1f} s)"
    _say(f"hubvib: {what} done{took}", stream)


def _say(line: str, stream) -> None:
    try:
        print(line, file=stream or sys.stderr, flush=True)
    except (OSError, ValueError):
        pass  # a closed log must not stop the work it reports on
