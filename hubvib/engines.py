"""Where the FE cases of a sweep run: a local process pool or a Dask distributed cluster.

Workers compute and return results; the calling process alone writes them
(``on_result``), so no shared filesystem is needed.  The scene's optional
``[execution]`` table chooses (SI, seconds)::

    [execution]
    engine = "local"              # or "dask"
    scheduler = "tcp://host:8786" # dask: a running scheduler; absent: a LocalCluster
    workers = 2                   # local pool / LocalCluster workers, 1..64
    timeout_s = 10                # dask: how long to wait for the scheduler, 1..600
"""
from __future__ import annotations

import math
from dataclasses import dataclass

ENGINES = ("local", "dask")
#: the oldest dask.distributed with every API used here (Client.map, as_completed,
#: LocalCluster(dashboard_address=None))
MIN_DISTRIBUTED = (2022, 1)


class EngineError(ValueError):
    """The engine cannot run the cases; the message names the setting or the case."""


@dataclass(frozen=True)
class Execution:
    """How to run a sweep's cases: ``engine`` ("local" or "dask"), ``scheduler``
    address (dask; ``None`` = a LocalCluster), ``workers`` (``None`` = the sweep's
    own), ``timeout`` [s] to reach the scheduler."""

    engine: str = "local"
    scheduler: str | None = None
    workers: int | None = None
    timeout: float = 10.0


def parse_execution_table(table: dict) -> Execution:
    """The scene's ``[execution]`` table, checked."""
    from .scene import SceneError

    allowed = {"engine", "scheduler", "workers", "timeout_s"}
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise SceneError(f"unknown key(s) {unknown} in [execution]; allowed: {sorted(allowed)}")
    engine = table.get("engine", "local")
    if engine not in ENGINES:
        raise SceneError(f"[execution] engine = {engine!r}; allowed: {', '.join(ENGINES)}")
    scheduler = table.get("scheduler")
    if scheduler is not None and (engine != "dask" or not isinstance(scheduler, str)
                                  or not scheduler.startswith(("tcp://", "tls://", "inproc://"))):
        raise SceneError(f"[execution] scheduler = {scheduler!r}; allowed with engine = \"dask\": "
                         "an address like \"tcp://host:8786\"")
    workers = table.get("workers")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or not 1 <= workers <= 64):
        raise SceneError(f"[execution] workers = {workers!r}; allowed integers 1..64")
    timeout = table.get("timeout_s", 10.0)
    if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not (
            math.isfinite(timeout) and 1 <= timeout <= 600):
        raise SceneError(f"[execution] timeout_s = {timeout!r}; allowed 1..600 [s]")
    return Execution(engine, scheduler, workers, float(timeout))


def run_cases(function, items: list, on_result, execution: Execution, workers: int) -> None:
    """``on_result(item, function(item))`` for every item, in completion order.

    A case that raises does not stop the others; afterwards one ``EngineError``
    names every failed case and its message.
    """
    if not items:
        return
    workers = execution.workers or workers
    if execution.engine == "dask":
        failures = _run_dask(function, items, on_result, execution, workers)
    elif workers == 1 or len(items) == 1:
        failures = []
        for item in items:
            on_result(item, function(item))
    else:
        failures = _run_pool(function, items, on_result, workers)
    if failures:
        raise EngineError("; ".join(f"case {item!r} failed: {message}"
                                    for item, message in failures))


def _run_pool(function, items, on_result, workers) -> list:
    from concurrent.futures import as_completed

    from .process_pool import worker_pool

    failures = []
    with worker_pool(min(workers, len(items))) as pool:
        futures = {pool.submit(function, item): item for item in items}
        for future in as_completed(futures):
            try:
                result = future.result()
            except Exception as exc:  # noqa: BLE001 - reported per case below
                failures.append((futures[future], f"{type(exc).__name__}: {exc}"))
                continue
            on_result(futures[future], result)
    return failures


def distributed_version_ok() -> tuple[bool, str]:
    """Whether dask.distributed is installed and recent enough, and its version."""
    try:
        import distributed
    except ImportError:
        return False, "not installed"
    parts = distributed.__version__.split(".")
    try:
        version = (int(parts[0]), int(parts[1]))
    except (ValueError, IndexError):
        return True, distributed.__version__
    return version >= MIN_DISTRIBUTED, distributed.__version__


def _run_dask(function, items, on_result, execution: Execution, workers: int) -> list:
    ok, version = distributed_version_ok()
    if not ok:
        raise EngineError(f"[execution] engine = \"dask\" needs dask.distributed >= "
                          f"{MIN_DISTRIBUTED[0]}.{MIN_DISTRIBUTED[1]} (found: {version}): "
                          "pip install 'hubvib[dask]'")
    from distributed import Client, LocalCluster, as_completed

    cluster = None
    try:
        if execution.scheduler is None:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
        else:
            try:
                client = Client(execution.scheduler, timeout=execution.timeout)
            except (OSError, TimeoutError) as exc:
                raise EngineError(f"[execution] scheduler = {execution.scheduler!r} did not "
                                  f"answer within {execution.timeout:g} s ({exc})") from None
        failures = []
        with client:
            futures = client.map(function, items, pure=False)
            item_of = {f.key: item for f, item in zip(futures, items)}
            for future in as_completed(futures):
                item = item_of[future.key]
                try:
                    result = future.result()
                except Exception as exc:  # noqa: BLE001 - reported per case
                    failures.append((item, f"{type(exc).__name__}: {exc}"))
                    continue
                on_result(item, result)
        return failures
    finally:
        if cluster is not None:
            cluster.close()
