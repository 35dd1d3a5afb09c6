"""How the app runs work: engines (local processes or Dask, ``engines``), the worker pool
(``process_pool``), progress lines (``progress``), the FE case cache and its check
(``fe_cache``, ``cache_check``), the result cache (``result_cache``), interrupts while a
cluster starts (``cluster_signals``) and the lumped parameter input (``params_input``).
dask is imported where it is used; every name below is imported on first use (PEP 562)."""
from typing import TYPE_CHECKING

from hubvib.foundation.lazy import lazy_face

if TYPE_CHECKING:
    from .cache_check import CacheError, check_writable
    from .engines import EngineError, Execution, parse_execution_table, run_cases
    from .fe_cache import read_entry, write_entry
    from .params_input import load_parameters
    from .process_pool import WorkerPool, worker_pool
    from .progress import LineProgress
    from .result_cache import cached_result

__all__ = [
    "Execution", "EngineError", "parse_execution_table", "run_cases", "WorkerPool",
    "worker_pool", "LineProgress", "read_entry", "write_entry", "CacheError",
    "check_writable", "cached_result", "load_parameters",
]
__getattr__, __dir__ = lazy_face(__name__, __file__, __all__)
