import importlib.util
import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

#: worker processes of the whole default run (pytest-xdist, the ``test`` extra): the
#: machine the default command must finish on has two cores
DEFAULT_WORKERS = 2


@pytest.hookimpl(tryfirst=True)
def pytest_cmdline_main(config):
    """The whole default run (``python -m pytest``, no file named) goes to two worker
    processes when pytest-xdist is installed; naming files, ``-n``, ``-p no:xdist`` or a
    worker process keep the run as asked."""
    if (importlib.util.find_spec("xdist") is None or os.environ.get("PYTEST_XDIST_WORKER")
            or not config.pluginmanager.hasplugin("xdist")
            or config.option.file_or_dir or getattr(config.option, "numprocesses", None)
            or config.option.collectonly):
        return None
    config.option.numprocesses = DEFAULT_WORKERS
    if getattr(config.option, "dist", "no") == "no":
        config.option.dist = "load"
    return None


@pytest.fixture(scope="session")
def shared_cache_folder(tmp_path_factory):
    """One FE cache folder for the whole test run, shared by its xdist workers (below the
    run's base temporary folder), for tests that need the same expensive cached entries
    (the Raba predicted crack path: some 23 FE solutions; the signal scenes' FE cases).
    Sound because an entry is keyed on its inputs and the FE stage's source, written
    atomically and checked on reading (``hubvib.runtime.fe_cache``); tests of the cache
    itself keep their own."""
    base = tmp_path_factory.getbasetemp()
    folder = (base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base) / "shared-cache"
    folder.mkdir(exist_ok=True)
    return folder


@pytest.fixture(scope="session", autouse=True)
def run_cache(shared_cache_folder):
    """Every test's default ``$HUBVIB_CACHE`` is the run's ``shared_cache_folder``, whatever
    the shell set, never the user's ``~/.cache/hubvib``: a run neither leaves entries there
    nor finds them from an earlier run, so every run starts as cold as CI's on a fresh
    machine; tests that need an empty or broken cache set their own."""
    previous = os.environ.get("HUBVIB_CACHE")
    os.environ["HUBVIB_CACHE"] = str(shared_cache_folder)
    yield shared_cache_folder
    if previous is None:
        os.environ.pop("HUBVIB_CACHE", None)
    else:
        os.environ["HUBVIB_CACHE"] = previous


@pytest.fixture
def shared_cache(shared_cache_folder, monkeypatch):
    """``$HUBVIB_CACHE`` set to ``shared_cache_folder`` for one test: what ``run_cache``
    sets already, named by the tests that rely on entries other tests computed."""
    monkeypatch.setenv("HUBVIB_CACHE", str(shared_cache_folder))
    return shared_cache_folder
