"""One mode identity through every table, file and figure of a crack-study report: a split
pair is followed from modes.csv to the short answer (synthetic FE rows, fast)."""
import csv
import json
import math
from dataclasses import replace

import numpy as np
import pytest
from tests.helpers.crack_scenes import synthetic_scene
from tests.helpers.synthetic_rows import TIMING, synthetic_fe_rows

from hubvib.detection.numbers import shift_hz
from hubvib.reports.crack_files import write_crack_study
from hubvib.studies.crack_study import crack_study_from_fe


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    scene = replace(synthetic_scene("series"), plots=False)
    result = crack_study_from_fe(scene, synthetic_fe_rows(scene.crack.depths), timing=TIMING)
    folder = tmp_path_factory.mktemp("identity")
    write_crack_study(result, folder)
    return result, folder


def _csv(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def _follow(result, folder, mode):
    """Every place of the report that shows ``mode`` (1-based, the lower member of a split
    pair) shows the same member."""
    i = mode - 1
    name = f"{mode} (split pair {mode}/{mode + 1}, lower)"
    deepest = 1e3 * result.depths[-1]
    study = result.detection
    carrier, pod = study.carrier, study.pod

    # modes.csv and results.json "modes": the name, and the instantaneous shift at the
    # deepest crack is planet 1 on the cracked tooth, as the carrier study computes it
    row = next(r for r in _csv(folder / "modes.csv") if int(r["mode"]) == mode)
    modes_json = json.loads((folder / "results.json").read_text())["modes"]
    inst = (carrier.omega_in[-1, i] - carrier.omega_in[0, i]) / (2 * math.pi)
    assert float(row["shift_at_deepest_hz"]) == pytest.approx(inst, rel=1e-9, abs=1e-9)
    assert modes_json[i]["shift_at_deepest_hz"] == pytest.approx(inst, rel=1e-9, abs=1e-9)
    assert row.get("mode_name") == name
    assert modes_json[i].get("mode_name") == name
    # the lower member drops at least as far as the upper one at every depth
    assert np.all(result.omega[:, i] <= result.omega[:, i + 1])

    # pod.csv: the record's shift is the time average of the same member in and out of mesh
    pod_row = next(r for r in _csv(folder / "pod.csv")
                   if int(r["mode"]) == mode and float(r["depth_mm"]) == pytest.approx(deepest))
    assert pod_row["mode_name"] == name
    averaged = carrier.omega_observed[-1, i] / (2 * math.pi)
    assert pod.nominal.frequency_hz[-1, i] == pytest.approx(averaged, rel=1e-12)
    assert float(pod_row["shift_hz"]) == pytest.approx(
        float(row["record_shift_at_deepest_hz"]), rel=1e-12, abs=1e-12)

    # frequency_vs_depth.csv: the in-mesh frequency the carrier table prints
    freq_row = next(r for r in _csv(folder / "frequency_vs_depth.csv")
                    if int(r["mode"]) == mode and float(r["depth_mm"]) == pytest.approx(deepest))
    assert freq_row["mode_name"] == name
    in_mesh = carrier.omega_in[-1, i] / (2 * math.pi)
    assert float(freq_row["frequency_hz"]) == pytest.approx(in_mesh, rel=1e-12)

    # the carrier-position table of report.md
    text = (folder / "report.md").read_text()
    line = next(ln for ln in text.splitlines() if ln.startswith(f"| {name} |"))
    assert f"| {in_mesh:.3f} |" in line

    # carrier_position.png: the row label of the mode
    from hubvib.detection.plots import carrier_figure

    fig = carrier_figure("test", carrier, result.kind)
    labels = [t.get_text() for t in fig.axes[0].get_yticklabels()]
    assert any(t.startswith(f"rigid {name}: ") for t in labels), labels
    assert fig.axes[1].get_title().startswith("one passage, rigid "), fig.axes[1].get_title()
    return text, float(pod_row["shift_hz"]), float(row["frequency_intact_hz"])


@pytest.mark.parametrize("mode", [3, 5, 7])
def test_a_split_pair_is_one_member_in_every_table_file_and_figure(report, mode):
    result, folder = report
    _follow(result, folder, mode)


def test_a_watched_split_pair_has_the_same_name_and_shift_in_the_short_answer(report):
    result, folder = report
    watched = [int(i) + 1 for i in result.detection.watched_modes()]
    names = result.names
    pairs = [m for m in watched if "split pair" in names[m - 1] and "lower" in names[m - 1]]
    assert pairs, f"no watched lower member of a split pair among {watched}"
    mode = pairs[0]
    text, record_shift, f0 = _follow(result, folder, mode)
    short = text.split("## Short answer", 1)[1]
    table = [ln for ln in short.splitlines() if ln.startswith("| depth [mm] |")][0]
    header = [c.strip() for c in table.strip("|").split("|")]
    column = header.index(f"rigid mode {names[mode - 1]} [Hz]")
    lines = short.splitlines()
    start = lines.index(table) + 2  # below the header and its rule
    last = [c.strip() for c in lines[start + len(result.depths) - 1].strip("|").split("|")]
    assert last[column].split()[0] == shift_hz(record_shift, f0).split()[0]


def test_repeated_intact_frequencies_are_named_as_split_pairs():
    from hubvib.detection.mode_names import mode_names, repeated_groups

    omega = np.array([1.0, 2.0, 2.0 * (1 + 1e-9), 3.0, 4.0, 4.0, 4.0])
    assert repeated_groups(omega) == [[0], [1, 2], [3], [4, 5, 6]]
    assert mode_names(omega)[:4] == ["1", "2 (split pair 2/3, lower)",
                                     "3 (split pair 2/3, upper)", "4"]
    assert mode_names(omega)[6] == "7 (split group 5/6/7, 3 of 3)"
