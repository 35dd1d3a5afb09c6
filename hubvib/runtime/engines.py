"""Where the FE cases of a sweep run: a local process pool or a Dask distributed cluster.

Workers compute and return results; the calling process alone writes them
(``on_result``), so no shared filesystem is needed.  The scene's optional
``[execution]`` table chooses (SI, seconds)::

    [execution]
    engine = "local"              # or "dask"
    scheduler = "tcp://host:8786" # dask: a running scheduler (tcp://HOST:PORT only);
                                  # absent: a LocalCluster
    workers = 2                   # local pool / LocalCluster workers, 1..64
    timeout_s = 10                # dask: how long to wait for the scheduler and for a
                                  # worker to join it [s], 1..600
"""
from __future__ import annotations

import asyncio
import importlib.util
import logging
import os
import socket
import threading
import warnings
from concurrent.futures import as_completed
from contextlib import contextmanager
from dataclasses import dataclass
from urllib.parse import urlsplit

from hubvib.foundation.blas import blas_threads
from hubvib.foundation.errors import InputError
from hubvib.foundation.schema import Field, Schema
from hubvib.runtime.cluster_signals import held_interrupts
from hubvib.runtime.process_pool import worker_pool

ENGINES = ("local", "dask")
#: the oldest dask.distributed with every API used here (Client.map, as_completed,
#: LocalCluster(dashboard_address=None))
MIN_DISTRIBUTED = (2022, 1)


class EngineError(InputError):
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


def is_scheduler_address(value) -> bool:
    """Whether ``value`` is an address this engine can reach a running scheduler at:
    ``tcp://HOST:PORT`` (port 1..65535).  ``inproc://`` reaches only a scheduler inside
    this very process, which a scene's run never has, and ``tls://`` needs certificates
    the engine does not pass: dask refuses both, and addresses without a host or port,
    with messages that name no key (an ``inproc://`` address without its ``host/pid/n``
    parts raises "not enough values to unpack")."""
    if not isinstance(value, str) or not value.startswith("tcp://"):
        return False
    try:
        address = urlsplit(value)
        port = address.port
    except ValueError:  # a port that is no number or lies outside 0..65535
        return False
    return (bool(address.hostname) and port is not None and 1 <= port
            and address.path in ("", "/") and not address.query and not address.fragment
            and address.username is None and address.password is None)


#: the ``[execution]`` keys; a new key = one entry here
SCHEMA = Schema("execution", (
    Field("engine", "choice", choices=ENGINES, default="local",
          doc="local process pool or Dask distributed"),
    Field("scheduler", "string", default=None, check=is_scheduler_address,
          doc='dask: a running scheduler, e.g. "tcp://host:8786"; absent: a LocalCluster',
          allowed='with engine = "dask": a running scheduler\'s "tcp://HOST:PORT", '
                  'or no scheduler key for a LocalCluster on this machine',
          message="{label} = {value}; allowed {allowed}"),
    Field("workers", "integer", 1, 64, default=None, unit="-",
          doc="local pool / LocalCluster workers (absent: the study's own)",
          message="{label} = {value}; allowed integers 1..64"),
    Field("timeout_s", "number", 1, 600, default=10.0, unit="s", attr="timeout",
          doc="dask: how long to wait for the scheduler and for a worker to join it",
          message="{label} = {value}; allowed 1..600 [s]"),
), unknown="unknown key(s) {keys} in [{table}]; allowed: {allowed}")


def parse_execution_table(table: dict) -> Execution:
    """The scene's ``[execution]`` table, checked (``SCHEMA``)."""
    values = SCHEMA.parse(table, defaults=True)
    if values["scheduler"] is not None and values["engine"] != "dask":
        raise SCHEMA.refuse(SCHEMA.by_key["scheduler"], values["scheduler"])
    return Execution(**values)


def run_cases(function, items: list, on_result, execution: Execution, workers: int,
              pool=None, after_submit=None) -> None:
    """``on_result(item, function(item))`` for every item, in completion order.

    A case that raises does not stop the others; afterwards one ``EngineError``
    names every failed case and its message.  Pool and Dask workers run one BLAS
    thread each (``SINGLE_THREADED``), so both engines give the same numbers to the
    last digit; with one worker (or one case left, as after a killed run) the local
    engine runs the cases in this process, with its BLAS limited to one thread as
    well: same threads, same digits.  ``pool`` (a ``worker_pool``, local engine): run
    them there instead of in a pool of their own, and leave it open (the caller goes on
    using its warm workers, see ``submit``); ``after_submit()`` is then called once every
    case is queued, so that what it submits runs on the first worker the cases leave idle.
    """
    if not items:
        return
    workers = execution.workers or workers
    if execution.engine == "dask":
        failures = _run_dask(function, items, on_result, execution, workers)
    elif workers == 1 or len(items) == 1:
        failures = _run_here(function, items, on_result)
    else:
        failures = _run_pool(function, items, on_result, workers, pool, after_submit)
    if failures:
        raise EngineError(_failure_text(failures))


def check_reachable(execution: Execution) -> None:
    """``EngineError`` unless the scheduler (if any) answers within the timeout: checked
    before anything is written.

    The whole handshake is bounded, not only the TCP connection: an address that
    accepts the connection but never answers (another service, a stopped process)
    hung ``Client()`` for ever: the scheduler is asked for its identity (dask.distributed's
    ``identity`` message).  Other addresses (an ``Execution`` built in Python with an
    in-process cluster's ``inproc://`` address; scenes allow ``tcp://`` only) are left to
    dask.
    """
    if execution.engine != "dask" or execution.scheduler is None or not \
            execution.scheduler.startswith("tcp://"):
        return
    address = urlsplit(execution.scheduler)
    try:
        with socket.create_connection((address.hostname, address.port or 8786),
                                      timeout=execution.timeout):
            pass
    except (OSError, ValueError) as exc:
        raise EngineError(f"[execution] scheduler = {execution.scheduler!r} did not answer "
                          f"within {execution.timeout:g} s ({exc})") from None
    if distributed_version_ok()[0]:
        _check_identity(execution)


def _check_identity(execution: Execution) -> None:
    """The scheduler answers dask's ``identity`` message within ``execution.timeout``."""
    from distributed.comm import connect

    async def identity():
        comm = await connect(execution.scheduler, timeout=execution.timeout)
        try:
            await comm.write({"op": "identity", "reply": True})
            return await comm.read()
        finally:
            comm.abort()

    try:
        reply = asyncio.run(asyncio.wait_for(identity(), execution.timeout))
    except (OSError, TimeoutError, asyncio.TimeoutError, ValueError, TypeError) as exc:
        why = "no answer to the handshake" if isinstance(exc, (TimeoutError,
                                                               asyncio.TimeoutError)) else exc
        raise EngineError(f"[execution] scheduler = {execution.scheduler!r} accepts the "
                          f"connection but did not answer within {execution.timeout:g} s "
                          f"({why}): is it a Dask scheduler?") from None
    if not (isinstance(reply, dict) and reply.get("type") == "Scheduler"):
        raise EngineError(f"[execution] scheduler = {execution.scheduler!r} answered, but not "
                          f"as a Dask scheduler (identity {str(reply)[:80]!r})")


def _failure_text(failures: list) -> str:
    """One line: each message once, with the cases it ended (a broken pool ends them all)."""
    cases = {}
    for item, message in failures:
        cases.setdefault(message, []).append(item)
    return "; ".join(f"case {items[0]!r} failed: {message}" if len(items) == 1 else
                     f"cases {', '.join(repr(i) for i in items)} failed: {message}"
                     for message, items in cases.items())


def _run_here(function, items, on_result) -> list:
    """In this process, one item after the other; a failure does not stop the others."""
    _load_mkl()
    failures = []
    for item in items:
        try:
            with blas_threads(1):  # as in a pool worker (SINGLE_THREADED): the same digits
                result = function(item)
        except Exception as exc:  # noqa: BLE001 - reported per case, as with a pool
            failures.append((item, f"{type(exc).__name__}: {exc}"))
            continue
        on_result(item, result)
    return failures


def _load_mkl() -> None:
    """Load MKL (PARDISO's library) before ``blas_threads(1)`` looks for the loaded BLAS
    libraries: loaded inside the block, by the first case, it kept its default threads
    there, and that case's last digits differed from a pool worker's."""
    if importlib.util.find_spec("pypardiso") is None:
        return
    from hubvib.fem.pardiso import mkl_library

    try:
        mkl_library()
    except Exception:  # noqa: BLE001 - no usable MKL: the case reports it if it needs it
        pass


#: set in every worker, as Dask's nanny does (``distributed.nanny.pre-spawn-environ``):
#: one BLAS thread per worker process, so the local pool and a Dask cluster round alike
#: (a multi-threaded BLAS changes the last digits of the FE values, and with the core count)
SINGLE_THREADED = {"OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}


@contextmanager
def _environment(values: dict):
    """``os.environ`` updated with ``values`` inside the block (spawned children inherit it)."""
    saved = {key: os.environ.get(key) for key in values}
    os.environ.update(values)
    try:
        yield
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


def submit(pool, function, *args):
    """``pool.submit(function, *args)`` with the environment of ``SINGLE_THREADED`` (a
    worker spawned by this submit gets one BLAS thread, as every case worker)."""
    with _environment(SINGLE_THREADED):  # the workers are spawned on submit
        return pool.submit(function, *args)


def _run_pool(function, items, on_result, workers, pool=None, after_submit=None) -> list:
    if pool is None:
        with worker_pool(min(workers, len(items))) as own:
            return _run_pool(function, items, on_result, workers, own)
    failures = []
    futures = {submit(pool, function, item): item for item in items}
    if after_submit is not None:
        after_submit()
    for future in as_completed(futures):
        try:
            result = future.result()
        except Exception as exc:  # noqa: BLE001 - reported per case below
            failures.append((futures[future], f"{type(exc).__name__}: {exc}"))
            continue
        on_result(futures[future], result)
    return failures


_ONE_AT_A_TIME = threading.Lock()


@dataclass(frozen=True)
class OneAtATime:
    """``function`` under a per-process lock: a Dask worker started with several threads
    still runs one case at a time (gmsh has one current model per process, so two
    meshes built in two threads of one process would mix)."""

    function: object

    def __call__(self, item):
        with _ONE_AT_A_TIME:
            return self.function(item)


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


def _wait_for_a_worker(client, execution: Execution) -> None:
    """``EngineError`` unless a worker is (or joins) the scheduler within the timeout:
    without one the cases would wait for ever."""
    try:
        client.wait_for_workers(1, timeout=execution.timeout)
    except (OSError, TimeoutError):
        raise EngineError(f"[execution] scheduler = {execution.scheduler!r} answers but has no "
                          f"worker (none joined within {execution.timeout:g} s): start "
                          f"`dask worker {execution.scheduler}` on the machines that compute"
                          ) from None


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
            # quiet: a failed case is reported once, by EngineError, without a traceback;
            # the scheduler's HTTP port moves on if 8787 is taken (a running `dask scheduler`)
            # SIGINT held while it is built: its workers never see a Ctrl-C (.cluster_signals)
            with warnings.catch_warnings(), held_interrupts():
                warnings.filterwarnings("ignore", message="Port .* is already in use")
                cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=logging.CRITICAL)
            client = Client(cluster)
        else:
            check_reachable(execution)  # the whole handshake bounded, not only the connect
            try:
                client = Client(execution.scheduler, timeout=execution.timeout)
            except (OSError, TimeoutError) as exc:
                raise EngineError(f"[execution] scheduler = {execution.scheduler!r} did not "
                                  f"answer within {execution.timeout:g} s ({exc})") from None
        failures = []
        with client:
            if execution.scheduler is not None:
                _wait_for_a_worker(client, execution)
            futures = client.map(OneAtATime(function), items, pure=False)
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
