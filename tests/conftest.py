import importlib.util
import os
from pathlib import Path

import pytest

#: worker processes of the whole default run (pytest-xdist, the ``test`` extra): the
#: machine the default command must finish on has two cores
DEFAULT_WORKERS = 2


@pytest.hookimpl(tryfirst=True)
def pytest_cmdline_main(config):
    """The whole default run (``python -m pytest``, no file named) goes to two worker
    processes when pytest-xdist is installed, a test file at a time (``--dist loadfile``:
    a module's fixtures are built in one worker only, not in both); naming files, ``-n``,
    ``-p no:xdist`` or a worker process keep the run as asked."""
    if (importlib.util.find_spec("xdist") is None or os.environ.get("PYTEST_XDIST_WORKER")
            or not config.pluginmanager.hasplugin("xdist")
            or config.option.file_or_dir or getattr(config.option, "numprocesses", None)
            or config.option.collectonly):
        return None
    config.option.numprocesses = DEFAULT_WORKERS
    if getattr(config.option, "dist", "no") == "no":
        config.option.dist = "loadfile"
    return None


@pytest.fixture(scope="session")
def fig4_sweep():
    """The shipped lumped sweep scene ``raba118_c_ru`` (the paper's fig. 4: c_ru swept)
    run once per test process: its ``StudyResult``, read by tests, never changed."""
    from hubvib.studies.scene import load_scene
    from hubvib.studies.sweep import run_study

    return run_study(load_scene(str(Path(__file__).parents[1] / "scenes" / "raba118_c_ru.toml")))


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


@pytest.fixture
def edit_source(tmp_path, monkeypatch):
    """``edit(module)``: from now on the source keys of every cache
    (``hubvib.foundation.source_graph``) read module ``module`` (dotted name) from a copy
    with ``line`` appended, as after a developer's edit; the graph of the process is
    restored after the test."""
    from hubvib.foundation import source_graph

    edited = {}

    def locate(name):
        return edited.get(name) or source_graph.find_module(name)

    def edit(module: str, line: str = "# an edit\n") -> Path:
        original = locate(module)
        assert original is not None, f"no source file for {module}"
        copy = tmp_path / "edited" / module / original.name
        copy.parent.mkdir(parents=True, exist_ok=True)
        copy.write_bytes(original.read_bytes() + line.encode())
        edited[module] = copy
        monkeypatch.setattr(source_graph, "PROCESS_GRAPH", source_graph.SourceGraph(locate))
        return copy

    return edit


@pytest.fixture
def installed_copy(tmp_path):
    """A folder holding a copy of ``hubvib/`` laid out as the wheel installs it (every
    package folder of ``pyproject.toml`` at its dotted place, its files copied), to be
    imported from a fresh interpreter with the folder first on ``PYTHONPATH``."""
    import shutil
    import tomllib

    root = Path(__file__).parents[1]
    config = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]
    folders = config["package-dir"]
    out = tmp_path / "installed"
    for package in config["packages"]:
        source = root / folders.get(package, package.replace(".", "/"))
        target = out.joinpath(*package.split("."))
        target.mkdir(parents=True, exist_ok=True)
        for file in source.iterdir():
            if file.is_file() and file.suffix in (".py", ".toml"):
                shutil.copy2(file, target / file.name)
    return out
