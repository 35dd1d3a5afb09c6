"""``hubvib diagnose --record --ring elastic``: the coupled modes identified in both records
become measured frequencies with their scatter, a peak of the intact record further from
its model mode than a quarter of the mode's half-power half-width is left out (named), and
nothing identified is one line."""
from types import SimpleNamespace

import numpy as np
import pytest

from hubvib.commands import diagnose


def _scene(zeta=0.02):
    return SimpleNamespace(signal=SimpleNamespace(damping_ratio=zeta))


def _found(baseline, model, modes=(3, 7, 9)):
    modes = np.asarray(modes)
    return SimpleNamespace(modes=modes, frequency_hz=np.asarray(baseline) - 5.0,
                           baseline_hz=np.asarray(baseline, dtype=float),
                           sigma_hz=np.full(modes.size, 1.5), model_hz=np.asarray(model),
                           skipped_modes={0: "not seen at the sensor"})


def test_identified_modes_near_the_model_become_measured(monkeypatch):
    from hubvib.detection import from_records
    from hubvib.identification import elastic_records

    model = [1000.0, 2000.0, 3000.0]
    # the second mode's intact peak lies 2.5 % (more than zeta / 4 = 0.5 %) from its model
    # mode, the third 0.33 %
    found = _found([1001.0, 2050.0, 2990.0], model)
    monkeypatch.setattr(elastic_records, "scene_identification", lambda *a, **k: found)
    measured, left_out = from_records.elastic_measured(_scene(), None, None)
    assert list(measured.mode) == [4, 10], "model modes 1-based, the far one left out"
    assert np.allclose(measured.baseline_hz, [1001.0, 2990.0])
    assert np.allclose(measured.frequency_hz, [996.0, 2985.0])
    assert np.allclose(measured.sigma_hz, [1.5, 1.5])
    assert len(left_out) == 1 and "elastic mode 8: identified at 2050.0 Hz" in left_out[0]


def test_the_command_names_what_it_leaves_out(monkeypatch, capsys):
    from hubvib.identification import elastic_records, readers

    found = _found([1001.0, 2050.0, 2990.0], [1000.0, 2000.0, 3000.0])
    monkeypatch.setattr(elastic_records, "scene_identification", lambda *a, **k: found)
    monkeypatch.setattr(readers, "read_record", lambda path, flag: path)
    measured = diagnose._elastic_record_measured(_scene(), "now.wav", "intact.wav")
    assert list(measured.mode) == [4, 10]
    assert "elastic mode 8: identified at 2050.0 Hz" in capsys.readouterr().err


def test_nothing_identified_near_the_model_is_one_error(monkeypatch):
    from hubvib.detection import from_records
    from hubvib.identification import elastic_records, readers

    found = _found([1100.0, 2200.0, 3300.0], [1000.0, 2000.0, 3000.0])
    monkeypatch.setattr(elastic_records, "scene_identification", lambda *a, **k: found)
    measured, left_out = from_records.elastic_measured(_scene(), None, None)
    assert measured is None and "mode 1: not seen at the sensor" in left_out[-1]
    monkeypatch.setattr(readers, "read_record", lambda path, flag: path)
    with pytest.raises(ValueError, match="no coupled mode of the elastic ring is identified "
                                         "in both records near its model frequency"):
        diagnose._elastic_record_measured(_scene(), "now.wav", "intact.wav")
