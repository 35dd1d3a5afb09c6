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
