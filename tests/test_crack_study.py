"""The crack-sensitivity study end to end: FE cases, cache, resume, stage isolation."""
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from hubvib.cli import main

pytest.importorskip("gmsh")
pytest.importorskip("skfem")

FAST = """
[reducer]
preset = "raba118"
[crack]
depths = {depths}
accuracy = "fast"
workers = {workers}
[output]
plots = false
renders = false
"""


def _scene(tmp_path, depths=(0.0, 0.008, 0.016), workers=2) -> Path:
    path = tmp_path / "scene.toml"
    path.write_text(FAST.format(depths=list(depths), workers=workers))
    return path


def _run_json(capsys, scene, out):
    assert main(["run", str(scene), "--out", str(out), "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_crack_study_physics_and_cache(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    scene = _scene(tmp_path)
    first = _run_json(capsys, scene, tmp_path / "a")
    assert first["fe_cases_computed"] == 3
    stiffness = np.genfromtxt(tmp_path / "a" / "stiffness_vs_depth.csv", delimiter=",",
                              names=True)
    # c_ru falls monotonically with depth (mean over carrier positions, test_fem.py)
    assert np.all(np.diff(stiffness["fe_c_ru_N_m"]) < 0)
    assert stiffness["lumped_c_ru_N_m"][0] == pytest.approx(1e6, rel=1e-12)  # ratio on the paper
    # the cracked tooth softens planet 1's ring mesh over its engagement, more when deeper
    ratio = stiffness["fe_c_rp_engaged_ratio"]
    assert ratio[0] == 1 and np.all(np.diff(ratio) < 0) and ratio[-1] > 0.8
    assert np.all(stiffness["fe_c_rp_engaged_min_ratio"][1:] < ratio[1:])
    modes = first["modes"]
    # Lin & Parker 1999: rotational modes follow c_ru, translational ones c_r, none of
    # them both
    follows = {m["mode"]: m["follows"].split("+") for m in modes}
    for m in modes:
        assert not {"c_ru", "c_r"} <= set(follows[m["mode"]])
        if "c_ru" in follows[m["mode"]]:
            assert m["kind"] == "rotational"
        if "c_r" in follows[m["mode"]]:
            assert m["kind"] == "translational"
    assert modes[0]["shift_at_deepest_percent"] < 0
    # one softer planet mesh breaks the cyclic symmetry: intact pairs split
    results = json.loads((tmp_path / "a" / "results.json").read_text())
    f = {(r["depth_mm"], r["mode"]): r["frequency_hz"] for r in results["frequencies"]}
    pairs = [(a["mode"], b["mode"]) for a, b in zip(modes, modes[1:])
             if a["kind"] == b["kind"] == "translational"
             and abs(a["frequency_intact_hz"] / b["frequency_intact_hz"] - 1) < 1e-7]
    assert pairs
    deepest = 1e3 * 0.016
    assert all(abs(f[deepest, a] / f[deepest, b] - 1) > 1e-6 for a, b in pairs)
    # changing only a lumped parameter reruns only the lumped stage
    scene.write_text(scene.read_text().replace('preset = "raba118"',
                                               'preset = "raba118"\n[reducer.parameters]\nm_r = 7.0'))
    second = _run_json(capsys, scene, tmp_path / "b")
    assert second["fe_cases_computed"] == 0


def test_direct_application_uses_fe_values(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("HUBVIB_CACHE", str(tmp_path / "cache"))
    scene = _scene(tmp_path, depths=(0.0, 0.01), workers=1)
    scene.write_text(scene.read_text().replace("[crack]", '[crack]\napply = "direct"'))
    _run_json(capsys, scene, tmp_path / "out")
    rows = np.genfromtxt(tmp_path / "out" / "stiffness_vs_depth.csv", delimiter=",", names=True)
    np.testing.assert_array_equal(rows["lumped_c_ru_N_m"], rows["fe_c_ru_N_m"])


def _modules_after_run(scene, out, cache):
    code = ("import sys; from hubvib.cli import main; "
            f"assert main(['run', {str(scene)!r}, '--out', {str(out)!r}]) == 0; "
            "print(sorted({'gmsh', 'skfem', 'pyvista', 'meshio'} & set(sys.modules)))")
    env = dict(os.environ, HUBVIB_CACHE=str(cache))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, check=True)
    return done.stdout.strip().splitlines()[-1]


def test_stages_the_scene_does_not_need_are_never_imported(tmp_path):
    lumped_only = Path(__file__).parents[1] / "scenes" / "raba118_c_ru.toml"
    assert _modules_after_run(lumped_only, tmp_path / "a", tmp_path / "cache") == "[]"
    # FE in this process (one worker), no renders asked: gmsh and skfem yes, pyvista never
    fe = _scene(tmp_path, depths=(0.0, 0.01), workers=1)
    assert _modules_after_run(fe, tmp_path / "b", tmp_path / "cache") == \
        "['gmsh', 'skfem']"


def test_kill_minus_9_mid_sweep_then_resume(tmp_path):
    cache, out = tmp_path / "cache", tmp_path / "out"
    scene = _scene(tmp_path, depths=(0.0, 0.004, 0.008, 0.012), workers=1)
    env = dict(os.environ, HUBVIB_CACHE=str(cache))
    command = [sys.executable, "-m", "hubvib.cli", "run", str(scene), "--out", str(out)]
    process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, start_new_session=True)
    folder = cache / "stiffness"
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and len(list(folder.glob("*.json"))) < 2:
        time.sleep(0.05)
    os.killpg(process.pid, signal.SIGKILL)
    process.wait()
    before = {p: p.stat().st_mtime_ns for p in folder.glob("*.json")}
    assert 2 <= len(before) < 4, "the kill must land mid-sweep"
    for path in before:
        assert np.isfinite(json.loads(path.read_text())["c_ru_N_m"])  # no corrupt case
    done = subprocess.run(command + ["--json"], env=env, capture_output=True, text=True,
                          check=True)
    assert json.loads(done.stdout)["fe_cases_computed"] == 4 - len(before)  # none recomputed
    assert {p: p.stat().st_mtime_ns for p in before} == before
    assert len(list(folder.glob("*.json"))) == 4  # none lost
    assert (out / "report.md").exists()
