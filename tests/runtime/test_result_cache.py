"""The on-disk cache of slow deterministic results (hubvib.runtime.result_cache) and the
one-command parser of the CLI: what they return is what the uncached path returns."""
import subprocess
import sys

import numpy as np
import pytest

from hubvib.runtime.result_cache import cached_figure, cached_result

#: the entry module of the probes below
SOURCE = ("hubvib.detection.crack_detection",)


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    return tmp_path / "cache" / "results"


def _counted(value):
    calls = []

    def compute():
        calls.append(1)
        return value
    return compute, calls


def test_second_call_loads_the_same_result_without_computing(cache):
    value = {"omega": np.linspace(0.0, 1.0, 7), "name": "x"}
    compute, calls = _counted(value)
    first = cached_result("probe", (1.5, "a"), SOURCE, compute, dict)
    second = cached_result("probe", (1.5, "a"), SOURCE, compute, dict)
    assert len(calls) == 1, "the second call must load the entry, not compute"
    assert second["name"] == first["name"] and np.array_equal(second["omega"], first["omega"])
    cached_result("probe", (1.5, "b"), SOURCE, compute, dict)
    assert len(calls) == 2, "other inputs are another entry"
    assert len(list(cache.glob("probe-*.pickle"))) == 2


@pytest.mark.parametrize("module, recomputed", [
    ("hubvib.detection.crack_detection", True), ("hubvib.detection.pod", True),
    ("hubvib.lumped.eigensolve", True), ("hubvib.render.modes", False),
    ("hubvib.signal.mesh_curves", False)])
def test_an_edit_in_the_import_graph_is_another_entry(cache, edit_source, module, recomputed):
    """The entry module's import graph decides: an edit there is another entry, an edit
    elsewhere is not."""
    compute, calls = _counted(3.0)
    cached_result("probe", (), SOURCE, compute, float)
    cached_result("probe", (), SOURCE, compute, float)
    assert len(calls) == 1
    edit_source(module)
    cached_result("probe", (), SOURCE, compute, float)
    assert len(calls) == (2 if recomputed else 1), module


def test_the_modules_of_the_inputs_classes_count(cache, edit_source):
    """An input's methods run in the computation: an edit to its class's module is another
    entry although the entry module does not import it."""
    from hubvib.foundation.errors import InputError

    compute, calls = _counted(3.0)
    cached_result("probe", (InputError("x"),), ("hubvib.render.modes",), compute, float)
    edit_source("hubvib.foundation.errors")
    cached_result("probe", (InputError("x"),), ("hubvib.render.modes",), compute, float)
    assert len(calls) == 2


def test_a_damaged_entry_is_computed_again_with_a_notice(cache, capsys):
    compute, calls = _counted([1.0, 2.0])
    cached_result("probe", (2,), SOURCE, compute, list)
    entry, = cache.glob("probe-*.pickle")
    data = bytearray(entry.read_bytes())
    data[-3] ^= 0xFF
    entry.write_bytes(bytes(data))
    assert cached_result("probe", (2,), SOURCE, compute, list) == [1.0, 2.0]
    assert len(calls) == 2
    assert "checksum differs; computing again" in capsys.readouterr().err
    compute_other, _ = _counted("not a list")
    entry.write_bytes(b"garbage")
    assert cached_result("probe", (2,), SOURCE, compute_other, list) == "not a list"


def test_an_unwritable_cache_folder_still_returns_the_result(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("a file where the cache folder would be")
    monkeypatch.setenv("HUBVIB_CACHE", str(blocker))
    compute, calls = _counted(4.0)
    assert cached_result("probe", (), SOURCE, compute, float) == 4.0
    assert cached_result("probe", (), SOURCE, compute, float) == 4.0 and len(calls) == 2


def test_cached_figure_is_the_picture_save_figure_draws(cache, tmp_path):
    from hubvib.foundation.output import save_figure

    def figure(values):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots()
        ax.plot(values)
        return fig

    values = np.array([0.0, 1.0, 4.0, 9.0])
    direct = save_figure(figure(values), tmp_path / "direct.png").read_bytes()
    for name in ("first.png", "second.png"):  # drawn, then copied from the entry
        assert cached_figure(tmp_path / name, figure, (values,)).read_bytes() == direct
    assert len(list(cache.glob("figure-figure-*.pickle"))) == 1


def test_a_named_command_imports_its_module_only():
    probe = ("import sys; from hubvib.cli import _parse; _parse(['scenes']); "
             "print(sorted(m for m in sys.modules if m.startswith('hubvib.commands.')))")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "['hubvib.commands.scenes']", out


def _printed(capsys, parse, argv):
    with pytest.raises(SystemExit) as stop:
        parse(argv)
    printed = capsys.readouterr()
    return stop.value.code, printed.out, printed.err


def test_one_command_parser_prints_what_the_whole_parser_prints(capsys):
    """Usage errors inside a command, a misspelt command and a command's help: the same
    exit code and text as the parser of every command."""
    from hubvib.cli import _parse, _parser

    for argv in (["spectrum", "--bogus"], ["torus_screw"], ["spectrum", "--method", "nope"],
                 ["spectrum", "--help"]):
        whole = _printed(capsys, _parser().parse_args, argv)
        assert _printed(capsys, _parse, argv) == whole, argv
        assert whole[0] == (0 if "--help" in argv else 2)
