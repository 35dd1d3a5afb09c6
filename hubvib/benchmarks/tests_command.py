"""Figure: the README's test command (``python -m pytest``) timed in the source checkout."""
from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

def readme_test_command(progress=None) -> dict:
    """The README's test command (``python -m pytest``) in the source checkout [s]."""
    say = progress or (lambda line: None)
    root = Path(__file__).resolve().parents[2]
    if not (root / "tests").is_dir() or not (root / "pyproject.toml").is_file():
        return {"tests_seconds": None, "tests_skipped": "no source checkout (tests/)"}
    started = time.perf_counter()
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"],
                         cwd=root, capture_output=True, text=True)
    seconds = time.perf_counter() - started
    last = (run.stdout.strip().splitlines() or ["no output"])[-1]
    if run.returncode != 0:
        return {"tests_seconds": None, "tests_skipped": f"the tests failed: {last}"}
    say(f"tests: {last}")
    return {"tests_seconds": seconds, "tests_summary": last}
