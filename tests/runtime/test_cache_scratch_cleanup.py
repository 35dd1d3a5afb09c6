"""Scratch in the cache does not outlive its run: SIGTERM unwinds the run (exit 143, one
line) and removes what it was writing; what ``kill -9`` leaves (``.fe-ring-*``,
``.modes-*``, ``.<entry>.json.*``) the next run removes once its owner has exited, and any
scratch a day old whoever wrote it."""
import os
import signal
import subprocess
import sys
import textwrap
import time

#: a hubvib process that renders into the cache until it is stopped
RENDERING = textwrap.dedent("""
    import argparse, sys, time
    from pathlib import Path
    import hubvib.cli as cli
    from hubvib.render.cache import cached_render

    def render(target):
        (target / "picture.png").write_bytes(b"png")
        print("ready", flush=True)
        time.sleep(120)
        return [target / "picture.png"]

    def handler(args):
        cached_render("fe-ring", {"case": 1}, Path(sys.argv[1]), render,
                      modules=("hubvib.render.cache",))
        return 0

    cli._parse = lambda argv: argparse.Namespace(handler=handler, json=False)
    sys.exit(cli.main())
""")

#: a process killed (SIGKILL) while it writes a render folder and an FE-cache entry
KILLED = textwrap.dedent("""
    import os, signal, sys
    from pathlib import Path
    from hubvib.foundation.output import atomic_folder, atomic_path

    root = Path(sys.argv[1])
    with atomic_folder(root / "renders" / "modes-0123") as scratch:
        (scratch / "mode_01.png").write_bytes(b"png")
        with atomic_path(root / "stiffness" / "tooth-curves" / "abc.json") as tmp:
            tmp.write_text("{")
            os.kill(os.getpid(), signal.SIGKILL)
""")


def _hidden(root):
    return sorted(p.relative_to(root).as_posix() for p in root.rglob(".*"))


def test_sigterm_ends_the_run_in_one_line_and_removes_its_scratch(tmp_path):
    cache, out = tmp_path / "cache", tmp_path / "out"
    script = tmp_path / "rendering.py"
    script.write_text(RENDERING)
    run = subprocess.Popen([sys.executable, str(script), str(out)], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True,
                           env={**os.environ, "HUBVIB_CACHE": str(cache)})
    try:
        assert run.stdout.readline() == "ready\n"
        assert [p.name.startswith(".fe-ring-") for p in (cache / "renders").iterdir()] == [True]
        run.send_signal(signal.SIGTERM)
        _, stderr = run.communicate(timeout=60)
    finally:
        run.kill()
    assert run.returncode == 143 and stderr == "hubvib: terminated\n", (run.returncode, stderr)
    assert list((cache / "renders").iterdir()) == [], "no scratch and no half entry left"
    assert not out.exists()


def test_next_run_removes_the_scratch_of_a_killed_run(tmp_path, monkeypatch):
    from hubvib.foundation.output import atomic_folder
    from hubvib.runtime.cache_check import check_writable

    cache = tmp_path / "cache"
    script = tmp_path / "killed.py"
    script.write_text(KILLED)
    killed = subprocess.run([sys.executable, str(script), str(cache)], capture_output=True)
    assert killed.returncode == -signal.SIGKILL
    left = _hidden(cache)
    assert [p.split("/")[-1].split(".")[1] for p in left] == ["modes-0123", "abc"], left
    fresh = cache / "results" / ".detection-1.pickle.abcdefgh.pickle"  # no owner, new
    old = cache / "results" / ".detection-2.pickle.ijklmnop.pickle"  # no owner, a day old
    for path in (fresh, old):
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(b"")
    os.utime(old, (time.time() - 2 * 86400,) * 2)
    monkeypatch.setenv("HUBVIB_CACHE", str(cache))
    with atomic_folder(cache / "renders" / "modes-mine") as mine:  # this live process's
        assert check_writable("stiffness") == cache  # what a run does before its FE work
        assert _hidden(cache) == sorted(p.relative_to(cache).as_posix() for p in (mine, fresh))


def test_scratch_of_another_host_waits_for_its_age(tmp_path):
    from hubvib.foundation.output import remove_stale_scratch

    path = tmp_path / ".fe-ring-1.~1@other-host~abcdefgh"
    path.mkdir()
    assert remove_stale_scratch(tmp_path) == [] and path.exists()
    os.utime(path, (time.time() - 2 * 86400,) * 2)
    assert remove_stale_scratch(tmp_path) == [path] and not path.exists()
