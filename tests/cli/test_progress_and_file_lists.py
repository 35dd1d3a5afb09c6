"""Long commands say how far they are on stderr (a line per step off a terminal) and keep
stdout for their answer; a ``written:`` line counts a long run of files of one kind."""
import functools
import json
import time

import pytest

from hubvib.cli import main


def test_written_line_counts_a_long_run_of_one_kind():
    from hubvib.foundation.output import written_line

    vtu = [f"out/crack_step_{i:02d}.vtu" for i in range(22)]
    line = written_line([*vtu, "out/crack_path.png", "out/crack_path.json"])
    assert line == ("written: 22 VTU files in out/ (crack_step_00.vtu .. crack_step_21.vtu), "
                    "out/crack_path.png, out/crack_path.json")


def test_written_line_names_a_short_list_as_before():
    from hubvib.foundation.output import LISTED_FILES, written_line

    files = [f"out/{i}.csv" for i in range(LISTED_FILES)] + ["other/0.csv", "out/a.png"]
    assert written_line(files) == "written: " + ", ".join(files)


def test_stiffness_reports_each_fe_part_on_stderr(monkeypatch, capsys):
    """One progress line per FE part (mesh stiffness, ring), stdout the table alone."""
    from hubvib.studies import stiffness

    def fake(design, crack_depth, solver, solid, on_part=None):
        for label in ("c_sp, c_rp", "c_ru, c_r intact"):
            on_part(label)
        return {}

    monkeypatch.setattr(stiffness, "stiffness_table", fake)
    assert main(["stiffness", "--json"]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out)["cases"] == {}
    lines = captured.err.splitlines()
    assert [line.split(",")[0] for line in lines] == ["FE stiffness: 1/2 parts (c_sp",
                                                      "FE stiffness: 2/2 parts (c_ru"], lines
    assert stiffness.stiffness_parts(0.0, False) == 2
    assert stiffness.stiffness_parts(1e-3, True) == 5


@pytest.mark.slow
def test_stability_reports_each_case_on_stderr(capsys):
    from hubvib.reducer import lumped_preset
    from hubvib.validation.stability import cases

    assert main(["stability", "--repeats", "1", "--json"]) == 0
    captured = capsys.readouterr()
    data = json.loads(captured.out)  # stdout: the answer alone
    assert data["passed"] and data["target"] == 1e-6
    total = len(cases(lumped_preset("raba118")))
    assert [line.split(":")[0] for line in captured.err.splitlines()] == (
        ["stability cases"] * total)
    assert captured.err.splitlines()[-1].startswith(f"stability cases: {total}/{total} cases")


@pytest.mark.slow
def test_crack_path_reports_each_step_and_counts_its_meshes(monkeypatch, capsys, tmp_path):
    """A line per growth step on stderr while it runs; the 4 step meshes on one count."""
    from hubvib.fem import crack_propagation
    from hubvib.meshing.ring_mesh import MeshOptions

    coarse = MeshOptions(size=3e-3, tooth_size=0.8e-3, load_size=0.3e-3)
    monkeypatch.setattr(crack_propagation, "GrowthOptions",
                        functools.partial(crack_propagation.GrowthOptions, mesh=coarse))
    seen = []
    real_grow = crack_propagation.grow_crack

    def grow(*args, on_step=None, **kwargs):
        def step(*step_args):
            on_step(*step_args)
            seen.append((time.perf_counter(), capsys.readouterr().err))
        return real_grow(*args, on_step=step, **kwargs)

    import hubvib.studies.lefm_path as study
    monkeypatch.setattr(study, "grow_crack", grow)
    out = tmp_path / "path"
    assert main(["crack-path", "--steps", "4", "--out", str(out)]) == 0
    stdout = capsys.readouterr().out
    assert [err.strip().split(" (")[0] for _, err in seen] == [
        f"crack growth: {k}/4 steps" for k in range(1, 5)], "each step's line as it ends"
    [written] = [line for line in stdout.splitlines() if line.startswith("written:")]
    assert f"4 VTU files in {out}/ (crack_step_00.vtu .. crack_step_03.vtu)" in written
    assert "crack growth" not in stdout
