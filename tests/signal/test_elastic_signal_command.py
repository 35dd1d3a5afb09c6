"""``hubvib signal`` on a scene with ``[elastic] ring = "elastic"``: one record per depth from
the elastic ring, named as the rigid route's, with its summary (records made by a stand-in
for the FE work: the files and the routing are under test here)."""
from __future__ import annotations

import json

import numpy as np

from hubvib.cli import main
from hubvib.identification.readers import read_record
from hubvib.signal.elastic_record import DepthRecord

SCENE = """# elastic-ring records
[reducer]
preset = "raba118"

[crack]
depths = [0.0, 0.003]
tooth = 0
start = "root"
accuracy = "fast"
workers = 1

[signal]
revolutions = 2
sample_rate_hz = 20000.0
damping_ratio = 0.02
roc_records = 0
ambient_force_psd_N2_Hz = 10.0

[elastic]
ring = "elastic"
sensor_angle_deg = 0.0
"""


def test_elastic_scene_writes_one_record_per_depth(tmp_path, monkeypatch, capsys):
    made = []

    def records(scene, progress=None, curves=None):
        made.append(scene.elastic.ring)
        rng = np.random.default_rng(0)
        return [DepthRecord(d, rng.standard_normal(400), 20000.0, 0.1, 800, 0.1, 30)
                for d in scene.crack.depths]

    monkeypatch.setattr("hubvib.signal.elastic_record.scene_records", records)
    path = tmp_path / "scene.toml"
    path.write_text(SCENE)
    assert main(["signal", str(path), "--out", str(tmp_path / "out"), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert made == ["elastic"]
    assert [d["depth_mm"] for d in data["depths"]] == [0.0, 3.0]
    for name in ("signal_0mm", "signal_3mm"):
        csv = read_record(tmp_path / "out" / f"{name}.csv")
        wav = read_record(tmp_path / "out" / f"{name}.wav")
        assert csv.values.size == wav.values.size == 400
        assert abs(csv.sample_rate - 20000.0) < 1e-6 and wav.sample_rate == 20000.0
        assert np.allclose(wav.values / np.abs(wav.values).max(),
                           csv.values / np.abs(csv.values).max(), atol=1e-6), name
    assert not (tmp_path / "out" / "indicators.csv").exists(), "the rigid study ran too"
