"""Shared leaves below every layer: atomic output (``output``), BLAS thread limits
(``blas``), the base of input errors (``errors``), size-checked file reads (``files``),
the declarative TOML table schema (``schema``), the lazy package faces (``lazy``) and the
source key every cache is keyed on (``source_graph``).
Standard library and numpy only; it imports nothing else of hubvib.  Every name below is
imported on first use (PEP 562)."""
from typing import TYPE_CHECKING

from .lazy import lazy_face

if TYPE_CHECKING:
    from .blas import blas_threads
    from .errors import InputError, SceneError
    from .files import read_bytes, read_text
    from .output import (OutputError, OutputFolderError, atomic_folder, atomic_path,
                         write_csv, write_json, write_text)
    from .schema import Field, Schema

__all__ = [
    "InputError", "SceneError", "OutputError", "OutputFolderError", "atomic_path",
    "atomic_folder", "write_text", "write_json", "write_csv", "read_text", "read_bytes",
    "blas_threads", "Field", "Schema",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
