"""The docs build's own modules (``docs/generate.py``, ``docs/hooks.py``), loaded by file as
the MkDocs hook loads them: they are not part of the package."""
import importlib.util
import sys
from pathlib import Path

DOCS = Path(__file__).parents[2] / "docs"


def docs_module(name: str, folder: Path = DOCS):
    """``folder/name.py`` as a fresh module (its folder on ``sys.path`` while it loads, as
    ``generate`` imports its siblings)."""
    sys.path.insert(0, str(folder))
    try:
        spec = importlib.util.spec_from_file_location(f"docs_{name}", folder / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    finally:
        sys.path.remove(str(folder))
