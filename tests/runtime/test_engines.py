"""Where a sweep's cases run (hubvib.runtime.engines): the scene's [execution] table and run_cases.

A 2-worker ``LocalCluster`` costs a few seconds, so one test gathers the fault
behaviours (a worker killed mid-task, a case that raises, the
numbers of the local engine) and one slow test runs a real crack sweep on both
engines.  Tasks are functions defined inside the tests, so cloudpickle ships them to
the workers by value.
"""
from __future__ import annotations

import math
import os
import socket
from pathlib import Path

import pytest

from hubvib.runtime.engines import (EngineError, Execution, OneAtATime, parse_execution_table,
                            run_cases)
from hubvib.studies.scene import SceneError, parse_scene

ITEMS = list(range(8))
#: the case that raises, and its message
FAILING, MESSAGE = 5, "synthetic failure of case five"


def expected(item: int) -> float:
    """The value a task returns: float arithmetic whose last digit shows any difference."""
    return math.sin(item + 0.1) * 1.234567890123e10 / 3.0


def collector():
    """``on_result`` that records every call, and the list it records into."""
    delivered = []
    return (lambda item, result: delivered.append((item, result))), delivered


# ---- [execution] table ----------------------------------------------------------------

def test_execution_table_defaults_and_values():
    assert parse_execution_table({}) == Execution("local", None, None, 10.0)
    got = parse_execution_table({"engine": "dask", "scheduler": "tcp://10.0.0.5:8786",
                                 "workers": 64, "timeout_s": 600})
    assert got == Execution("dask", "tcp://10.0.0.5:8786", 64, 600.0)
    assert parse_execution_table({"engine": "dask", "workers": 1, "timeout_s": 1}).workers == 1


BAD_TABLES = [
    ({"engine": "spark"}, "engine"),
    ({"engine": 1}, "engine"),
    ({"scheduler": "tcp://10.0.0.5:8786"}, "scheduler"),  # engine local
    ({"engine": "local", "scheduler": "tcp://10.0.0.5:8786"}, "scheduler"),
    ({"engine": "dask", "scheduler": "10.0.0.5:8786"}, "scheduler"),
    ({"engine": "dask", "scheduler": "http://10.0.0.5:8786"}, "scheduler"),
    ({"engine": "dask", "scheduler": 8786}, "scheduler"),
    ({"engine": "dask", "scheduler": ""}, "scheduler"),
    ({"engine": "dask", "scheduler": "inproc://nothing"}, "scheduler"),
    ({"engine": "dask", "scheduler": "inproc://10.0.0.5/4242/1"}, "scheduler"),
    ({"engine": "dask", "scheduler": "tls://10.0.0.5:8786"}, "scheduler"),
    ({"engine": "dask", "scheduler": "tcp://10.0.0.5"}, "scheduler"),  # no port
    ({"engine": "dask", "scheduler": "tcp://:8786"}, "scheduler"),  # no host
    ({"engine": "dask", "scheduler": "tcp://"}, "scheduler"),
    ({"engine": "dask", "scheduler": "tcp://10.0.0.5:0"}, "scheduler"),
    ({"engine": "dask", "scheduler": "tcp://10.0.0.5:65536"}, "scheduler"),
    ({"engine": "dask", "scheduler": "tcp://10.0.0.5:port"}, "scheduler"),
    ({"engine": "dask", "scheduler": "tcp://10.0.0.5:8786/path"}, "scheduler"),
    ({"workers": 0}, "workers"),
    ({"workers": 65}, "workers"),
    ({"workers": True}, "workers"),
    ({"workers": 2.0}, "workers"),
    ({"workers": "2"}, "workers"),
    ({"workers": -1}, "workers"),
    ({"engine": "dask", "timeout_s": 0}, "timeout_s"),
    ({"engine": "dask", "timeout_s": 0.5}, "timeout_s"),
    ({"engine": "dask", "timeout_s": 601}, "timeout_s"),
    ({"engine": "dask", "timeout_s": math.nan}, "timeout_s"),
    ({"engine": "dask", "timeout_s": math.inf}, "timeout_s"),
    ({"engine": "dask", "timeout_s": True}, "timeout_s"),
    ({"engine": "dask", "timeout_s": "10"}, "timeout_s"),
    ({"engine": "dask", "threads": 2}, "threads"),
]


@pytest.mark.parametrize("table, key", BAD_TABLES, ids=[repr(t) for t, _ in BAD_TABLES])
def test_bad_execution_table_names_the_key(table, key):
    with pytest.raises(SceneError, match=key) as info:
        parse_execution_table(table)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("address", ["tcp://10.0.0.5:8786", "tcp://scheduler.example:1",
                                     "tcp://[::1]:65535", "tcp://127.0.0.1:8786/"])
def test_scheduler_accepts_tcp_host_and_port(address):
    assert parse_execution_table({"engine": "dask", "scheduler": address}).scheduler == address


def test_scheduler_refusal_names_the_key_the_value_and_the_allowed_forms():
    with pytest.raises(SceneError) as info:
        parse_execution_table({"engine": "dask", "scheduler": "inproc://nothing",
                               "timeout_s": 2})
    assert str(info.value) == (
        "[execution] scheduler = 'inproc://nothing'; allowed with engine = \"dask\": a running "
        "scheduler's \"tcp://HOST:PORT\", or no scheduler key for a LocalCluster on this "
        "machine")


def test_run_refuses_an_inproc_scheduler_before_writing(tmp_path, capsys, monkeypatch):
    """A crack scene naming an ``inproc://`` scheduler: refused when the scene is read, in
    one line naming the key (dask's own parsing of it raised an unpacking error naming
    nothing), exit 2, no output folder and no cache entry."""
    from hubvib.cli import main

    scene = tmp_path / "scene.toml"
    scene.write_text('[reducer]\npreset = "raba118"\n[crack]\ndepths = [0.0, 0.003]\n'
                     '[execution]\nengine = "dask"\nscheduler = "inproc://nothing"\n'
                     'timeout_s = 2\n')
    cache = tmp_path / "cache"
    monkeypatch.setenv("HUBVIB_CACHE", str(cache))
    out = tmp_path / "out"
    code = main(["run", str(scene), "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2
    assert err.splitlines() == [
        "hubvib: error: [execution] scheduler = 'inproc://nothing'; allowed with engine = "
        "\"dask\": a running scheduler's \"tcp://HOST:PORT\", or no scheduler key for a "
        "LocalCluster on this machine"]
    assert not out.exists() and not cache.exists()


SCENE = """
[reducer]
preset = "raba118"
[study]
parameter = "c_ru"
values = [1e6]
"""


def test_scene_execution_table_is_parsed_and_checked():
    """The [execution] table reaches ``Scene.tables``; a bad one fails the scene load."""
    scene = parse_scene(SCENE + '[execution]\nengine = "dask"\nworkers = 3\n', "t")
    assert scene.tables["execution"] == Execution("dask", None, 3, 10.0)
    assert "execution" not in parse_scene(SCENE, "t").tables
    with pytest.raises(SceneError, match="workers"):
        parse_scene(SCENE + "[execution]\nworkers = 65\n", "t")
    with pytest.raises(SceneError, match="execution"):
        parse_scene(SCENE + "execution = 3\n", "t")


# ---- run_cases, local engine -----------------------------------------------------------

def test_local_in_process_delivers_each_result_once():
    on_result, delivered = collector()
    run_cases(expected, ITEMS, on_result, Execution(), workers=1)
    assert delivered == [(i, expected(i)) for i in ITEMS]
    on_result, delivered = collector()
    run_cases(expected, [], on_result, Execution(), workers=1)
    assert delivered == []


def test_local_in_process_failure_names_the_case_and_keeps_the_others():
    def task(item):
        if item == FAILING:
            raise ValueError(MESSAGE)
        return expected(item)

    on_result, delivered = collector()
    with pytest.raises(EngineError, match=f"case {FAILING} failed: ValueError: {MESSAGE}"):
        run_cases(task, ITEMS, on_result, Execution(), workers=1)
    assert delivered == [(i, expected(i)) for i in ITEMS if i != FAILING]


def test_local_pool_failure_names_the_case_and_keeps_the_others():
    """Two spawned workers; ``math.sqrt`` (picklable, light to import) fails on -1."""
    pytest.importorskip("hubvib.runtime.process_pool")
    items = [4.0, 9.0, -1.0, 16.0, 25.0]
    on_result, delivered = collector()
    with pytest.raises(EngineError, match="case -1.0 failed: ValueError: math domain error"):
        run_cases(math.sqrt, items, on_result, Execution(workers=2), workers=1)
    assert sorted(delivered) == [(4.0, 2.0), (9.0, 3.0), (16.0, 4.0), (25.0, 5.0)]


def test_local_pool_worker_that_dies_is_reported_once_per_message():
    """Both workers exit (``os._exit``): one EngineError line naming both cases and the
    broken pool once; no hang, nothing delivered."""
    pytest.importorskip("hubvib.runtime.process_pool")
    on_result, delivered = collector()
    with pytest.raises(EngineError) as info:
        run_cases(os._exit, [3, 4], on_result, Execution(workers=2), workers=1)
    text = str(info.value)
    assert text.startswith("cases 3, 4 failed: BrokenProcessPool") and text.count("failed") == 1
    assert delivered == []


def test_local_pool_workers_run_one_blas_thread(monkeypatch):
    """As Dask's nanny does, so both engines round alike; the parent's environment is
    left as it was."""
    pytest.importorskip("hubvib.runtime.process_pool")
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "7")
    monkeypatch.delenv("OMP_NUM_THREADS", raising=False)
    names = ["OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"]
    on_result, delivered = collector()
    run_cases(os.getenv, names, on_result, Execution(workers=2), workers=1)
    assert sorted(delivered) == sorted((name, "1") for name in names)
    assert os.environ["OPENBLAS_NUM_THREADS"] == "7" and "OMP_NUM_THREADS" not in os.environ


def test_one_at_a_time_serialises_threads_of_one_process():
    """A Dask worker started with several threads runs one FE case at a time (gmsh has
    one current model per process).  Events, not sleeps: a wrapped case waits inside until
    every thread has called in (the others then queue on the lock); the control, unwrapped,
    waits at a barrier that only opens with all four inside at once."""
    import threading

    running, most, called = [0], [0], [0]
    guard = threading.Condition()
    inside = threading.Barrier(4, timeout=30)

    def enter():
        with guard:
            running[0] += 1
            most[0] = max(most[0], running[0])

    def leave(item):
        with guard:
            running[0] -= 1
        return item

    def queued_case(item):
        enter()
        with guard:  # every thread has asked to run a case: the others wait on the lock
            assert guard.wait_for(lambda: called[0] == 4, timeout=30), "a thread never called"
        return leave(item)

    def call(item):
        with guard:
            called[0] += 1
            guard.notify_all()
        wrapped(item)

    def barrier_case(item):
        enter()
        inside.wait()  # BrokenBarrierError after 30 s if the four never overlap
        return leave(item)

    wrapped = OneAtATime(queued_case)
    threads = [threading.Thread(target=call, args=(i,)) for i in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert most[0] == 1 and called[0] == 4
    most[0] = 0
    threads = [threading.Thread(target=barrier_case, args=(i,)) for i in range(4)]  # control
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert most[0] == 4, "without the lock the four threads run at once (else the check " \
        "above is void)"


# ---- run_cases, dask engine ------------------------------------------------------------

def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def test_dask_scheduler_that_does_not_answer_fails_within_the_timeout():
    """A clear EngineError naming the address and the timeout."""
    address = f"tcp://127.0.0.1:{free_port()}"
    execution = parse_execution_table({"engine": "dask", "scheduler": address, "timeout_s": 1})
    on_result, delivered = collector()
    with pytest.raises(EngineError, match="did not answer within 1 s") as info:
        run_cases(expected, ITEMS, on_result, execution, workers=2)
    assert address in str(info.value) and "\n" not in str(info.value)
    assert delivered == []


@pytest.mark.filterwarnings("ignore:Port .* is already in use")  # a `dask scheduler` running
def test_dask_scheduler_without_workers_fails_within_the_timeout():
    """A scheduler that answers but has no worker: the cases would wait for ever."""
    from distributed import LocalCluster

    with LocalCluster(n_workers=0, processes=False, protocol="tcp", host="127.0.0.1",
                      dashboard_address=None) as empty:
        execution = parse_execution_table({"engine": "dask", "scheduler": empty.scheduler_address,
                                           "timeout_s": 1})
        on_result, delivered = collector()
        with pytest.raises(EngineError, match="has no worker .*within 1 s"):
            run_cases(expected, ITEMS, on_result, execution, workers=2)
    assert delivered == []


@pytest.mark.slow
def test_dask_local_cluster_killed_worker_and_failing_case(tmp_path):
    """Faults on a 2-worker LocalCluster, in one cluster start:

    - case 3 kills its worker (``os._exit``) the first time it runs: the nanny replaces
      the worker and the case is recomputed;
    - case 5 raises: EngineError names it and its message, every other result delivered;
    - ``on_result`` is called exactly once per delivered case, with the same values as
      the local engine, to the last digit.
    """
    marker, failing, message = str(tmp_path / "killed-once"), FAILING, MESSAGE

    def task(item):  # self-contained: the workers need not import this test module
        import math
        import os
        import time
        from pathlib import Path

        if item == 3 and not Path(marker).exists():
            Path(marker).write_text(str(os.getpid()))
            os._exit(1)
        if item == failing:
            raise ValueError(message)
        time.sleep(0.05)  # a case that takes time (what is simulated here): the kill lands
        # while the other worker still holds cases
        return math.sin(item + 0.1) * 1.234567890123e10 / 3.0  # = expected(item)

    on_result, delivered = collector()
    with pytest.raises(EngineError) as info:
        run_cases(task, ITEMS, on_result, Execution("dask", workers=2), workers=1)
    assert str(info.value) == f"case {FAILING} failed: ValueError: {MESSAGE}"
    assert Path(marker).exists(), "the task killed its worker once"
    assert sorted(i for i, _ in delivered) == [i for i in ITEMS if i != FAILING], \
        "each case delivered exactly once, the killed one recomputed"

    on_local, local = collector()
    with pytest.raises(EngineError):  # marker present: no kill in this process
        run_cases(task, ITEMS, on_local, Execution(), workers=1)
    assert sorted(delivered) == sorted(local) == [(i, expected(i)) for i in ITEMS if i != FAILING]


# ---- end to end: a real crack sweep on both engines ------------------------------------

HUB4_FAST = """
[design]
preset = "hub4"
[crack]
depths = [0.0, 0.002]
through_rim = false
accuracy = "fast"
workers = 2
"""


@pytest.mark.slow
def test_crack_sweep_dask_equals_local_to_the_last_digit(tmp_path, monkeypatch):
    """The same FE rows with engine "dask" as with "local" (fresh
    caches each), timings excluded; a rerun on the dask run's cache computes nothing."""
    from hubvib.cases.runner import run_fe_cases

    sweep = parse_scene(HUB4_FAST, "hub4-fast").crack
    assert sweep.depths == (0.0, 0.002)
    rows = {}
    for engine in ("local", "dask"):
        monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / engine))
        results, computed = run_fe_cases(sweep, progress=False,
                                         execution=Execution(engine, workers=2))
        assert computed == 2
        rows[engine] = [{k: v for k, v in r.items() if not k.startswith("seconds_")}
                        for r in results]
    assert rows["dask"] == rows["local"], "dask vs local engine, exact equality"
    assert [r["depth_m"] for r in rows["dask"]] == [0.0, 0.002]
    cracked = rows["dask"][1]
    assert 1 - cracked["c_rp_engaged_ratio"] > 10 * cracked["c_rp_engaged_ratio_error"], \
        "a 2 mm root crack softens the cracked tooth's mesh by far more than its FE error"
    _, computed = run_fe_cases(sweep, progress=False, execution=Execution("dask", workers=2))
    assert computed == 0, "the client wrote the cache; a rerun resumes from it"
