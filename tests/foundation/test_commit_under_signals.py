"""A stop signal while an output set moves into place waits until the set is complete,
whichever thread of the process the kernel hands it to."""
from __future__ import annotations

import signal
import threading
import time

import pytest

import hubvib.foundation.output as output


def test_a_ctrl_c_taken_by_another_thread_waits_for_the_whole_set(tmp_path, monkeypatch):
    """The kernel gives a process-directed signal to any thread that does not block it; a
    signal mask in the main thread alone let Python raise KeyboardInterrupt in the middle of
    the moves (files in place, the set's list not written)."""
    other = threading.Thread(target=time.sleep, args=(2.0,), daemon=True)
    other.start()
    commit = output._commit

    def commit_while_signalled(stage, folder):
        signal.pthread_kill(other.ident, signal.SIGINT)  # taken by the other thread
        time.sleep(0.2)  # the main thread runs Python handlers meanwhile
        commit(stage, folder)

    monkeypatch.setattr(output, "_commit", commit_while_signalled)
    with pytest.raises(KeyboardInterrupt):
        with output.output_set(tmp_path / "out") as stage:
            for name in ("a.csv", "b.csv"):
                (stage / name).write_text("1\n")
    names = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert names == [output.MANIFEST_NAME, "a.csv", "b.csv"], (
        f"the set moved completely, its list written, nothing else left: {names}")


def test_a_ctrl_c_while_the_stage_is_removed_still_removes_all_of_it(tmp_path, monkeypatch):
    """The stop that comes right after the set moved into place, while the emptied stage
    folder is removed: the removal finishes first, then the stop is raised."""
    rmtree = output.shutil.rmtree

    def rmtree_while_signalled(path, *args, **kwargs):
        if output.STAGE_PREFIX in str(path):
            signal.raise_signal(signal.SIGINT)
        rmtree(path, *args, **kwargs)

    monkeypatch.setattr(output.shutil, "rmtree", rmtree_while_signalled)
    with pytest.raises(KeyboardInterrupt):
        with output.output_set(tmp_path / "out") as stage:
            (stage / "sub").mkdir()
            (stage / "sub" / "a.csv").write_text("1\n")
    names = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert names == [output.MANIFEST_NAME, "sub"], (
        f"the set in place, the stage and the lock gone: {names}")
