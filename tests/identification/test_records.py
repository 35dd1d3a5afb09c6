"""Raw records: readers (CSV, WAV, UFF 58), identification of known modes within their
predicted uncertainty, and hubvib diagnose --record."""
import math

import numpy as np
import pytest

from hubvib.cli import main
from hubvib.identification.law import fisher_sigma_hz
from hubvib.identification.modes import identify_modes
from hubvib.identification.readers import RecordError, read_record
from hubvib.identification.records import Record, mode_psd, simulate

MODES = np.array([40.0, 55.0, 70.0, 70.4, 90.0])
ZETA = 0.02


def acceleration_record(modes, duration, seed, rate=None, snr=100.0):
    """Acceleration of simulated modes under unit white force: the exact sampled
    displacement differentiated twice in the frequency domain (``-(2 pi f)^2`` per FFT
    line), plus white noise at ``snr`` below the resonance peak of the acceleration PSD
    (the same for every mode under unit force)."""
    rate = rate or 4.4 * float(np.max(modes))
    rng = np.random.default_rng(seed)
    x = simulate(modes, ZETA, duration, rate, math.inf, rng).values
    f = np.fft.rfftfreq(x.size, 1 / rate)
    a = np.fft.irfft(-(2 * math.pi * f) ** 2 * np.fft.rfft(x), x.size)
    f1 = float(np.min(modes))
    peak = (2 * math.pi * f1) ** 4 * float(mode_psd(f1, ZETA, rate, f1))
    return Record(a + math.sqrt(peak / snr * rate) * rng.standard_normal(a.size), rate)


def write_csv(path, record):
    t = np.arange(record.values.size) / record.sample_rate
    path.write_text("time_s,acceleration_m_s2\n" + "\n".join(
        f"{float(a)!r},{float(b)!r}" for a, b in zip(t, record.values)) + "\n")
    return path


def test_known_modes_are_identified_within_their_predicted_uncertainty():
    record = acceleration_record(MODES, 120.0, 3)
    found = identify_modes(record, MODES * 1.005, ZETA)
    assert set(found.skipped) == {2, 3}, "the 70 / 70.4 Hz pair lies within 2 zeta f"
    for i, mode in zip(found.index, found.modes):
        assert abs(mode.frequency_hz - MODES[i]) < 4 * mode.sigma_hz, \
            f"mode {MODES[i]} Hz: {mode.frequency_hz:.4f} +- {mode.sigma_hz:.4f} Hz (4 sigma)"
        assert mode.sigma_hz >= 0.9 * fisher_sigma_hz(MODES[i], ZETA, 120.0, math.inf), \
            "no better than the noise-free bound"


@pytest.mark.slow
def test_identified_scatter_over_many_records_matches_the_bound():
    errors = []
    for seed in range(40):
        found = identify_modes(acceleration_record(MODES[[0, 1, 4]], 60.0, 100 + seed),
                               MODES[[0, 1, 4]], ZETA)
        errors.append([(m.frequency_hz - MODES[[0, 1, 4]][k]) / m.sigma_hz
                       for k, m in enumerate(found.modes)])
    z = np.array(errors)
    assert 0.7 < z.std() < 1.4, f"standardised errors scatter by {z.std():.2f} (bound: 1)"


def test_csv_wav_and_uff_records_read_back(tmp_path):
    import pyuff
    from scipy.io import wavfile

    record = acceleration_record([40.0], 2.0, 1, rate=1000.0)
    back = read_record(write_csv(tmp_path / "r.csv", record))
    assert back.sample_rate == pytest.approx(1000.0, rel=1e-9)
    np.testing.assert_allclose(back.values, record.values, rtol=1e-12)
    wavfile.write(tmp_path / "r.wav", 1000, record.values.astype(np.float32))
    wav = read_record(tmp_path / "r.wav")
    assert wav.sample_rate == 1000.0
    np.testing.assert_allclose(wav.values, record.values, rtol=1e-6)
    uff = pyuff.UFF(str(tmp_path / "r.uff"))
    labels = {f"{axis}_{what}": 0 for axis in ("abscissa", "ordinate", "orddenom", "z_axis")
              for what in ("len_unit_exp", "force_unit_exp", "temp_unit_exp")}
    labels |= {f"{axis}_axis_units_lab": "NONE" for axis in ("abscissa", "ordinate",
                                                             "orddenom", "z_axis")}
    dataset = pyuff.prepare_58(
        binary=0, id1="accelerometer", id2="-", id3="-", id4="-", id5="-", func_type=1,
        ver_num=0, load_case_id=0, rsp_ent_name="pt", rsp_node=1, rsp_dir=3,
        ref_ent_name="pt", ref_node=1, ref_dir=3, ord_data_type=4,
        num_pts=record.values.size, abscissa_spacing=1, abscissa_min=0.0,
        abscissa_inc=1e-3, z_axis_value=0.0, abscissa_spec_data_type=17,
        ordinate_spec_data_type=12, orddenom_spec_data_type=0, z_axis_spec_data_type=0,
        data=record.values, x=np.arange(record.values.size) / 1000.0, **labels)
    dataset["func_id"] = 0
    uff.write_sets(dataset, mode="overwrite")
    back = read_record(tmp_path / "r.uff")
    assert back.sample_rate == pytest.approx(1000.0, rel=1e-9)
    np.testing.assert_allclose(back.values, record.values, rtol=1e-6)


@pytest.mark.parametrize("name, text, message", [
    ("a.txt", "x", r"unknown record format '.txt'"),
    ("a.csv", "t,a\n0,1\n", r"line 1: header must be time_s,acceleration_m_s2"),
    ("a.csv", "time_s,acceleration_m_s2\n0,1\n0.1,x\n", r"line 3: '0.1,x'; it needs two"),
    ("a.csv", "time_s,acceleration_m_s2\n" + "".join(
        f"{t},{0.0}\n" for t in (0, 0.1, 0.2, 0.35, 0.4)), r"line 5: time_s = 0.35 breaks"),
    ("a.csv", "time_s,acceleration_m_s2\n" + "".join(f"{0.1 * k},0\n" for k in range(10)),
     r"10 samples, finite: True; a record needs at least 64"),
])
def test_bad_records_name_file_and_line(tmp_path, name, text, message):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(RecordError, match=message):
        read_record(path)


def test_cli_record_flags_go_together(tmp_path, capsys):
    path = tmp_path / "r.csv"
    path.write_text("time_s,acceleration_m_s2\n0,0\n")
    assert main(["diagnose", "--scene", "raba118_crack", "--record", str(path)]) == 2
    assert "--record and --baseline-record go together" in capsys.readouterr().err
    assert main(["diagnose", "--scene", "raba118_crack"]) == 2
    assert "give either --measured" in capsys.readouterr().err
    assert main(["diagnose", "--scene", "raba118_crack", "--record", str(path),
                 "--baseline-record", str(tmp_path / "none.wav")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("hubvib: error: --record") and "a record needs at least 64" in err


SCENE = """
[reducer]
preset = "raba118"
[crack]
depths = [0.0, 0.003075, 0.00615, 0.009225, 0.0123, 0.015375, 0.01845, 0.021525, 0.0246]
apply = "direct"
accuracy = "fast"
[detection]
samples = 300
[output]
plots = false
"""


@pytest.mark.slow
def test_diagnose_from_two_records_end_to_end(tmp_path, monkeypatch, capsys):
    # the synthetic crack model's intact modes below 1.9 kHz, simulated as two independent
    # intact 4 kHz acceleration records, written as CSV
    import json

    import hubvib.detection.diagnosis
    from tests.helpers.synthetic_rows import synthetic_fe_cases

    from hubvib.detection.diagnosis import reference
    from hubvib.detection.options import DetectionOptions
    from tests.helpers.synthetic_rows import TIMING, synthetic_model

    def fe_cases(sweep, progress=True):
        return synthetic_fe_cases(sweep.depths), 0

    monkeypatch.setattr(hubvib.detection.diagnosis, "crack_cases", fe_cases)
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE)
    f0 = reference(synthetic_model("direct"), DetectionOptions(samples=100),
                   TIMING).nominal_hz[0]
    below = f0[f0 < 1900]
    paths = []
    for seed in (1, 2):
        paths.append(write_csv(tmp_path / f"r{seed}.csv",
                               acceleration_record(below, 60.0, seed, rate=4000.0)))
    assert main(["diagnose", "--scene", str(scene), "--record", str(paths[1]),
                 "--baseline-record", str(paths[0]), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["modes"] == [1, 6], "the well-separated modes below Nyquist"
    assert "neighbour" in data["skipped_modes"]["7"]
    assert "close modes" in data["skipped_modes"]["2"]
    assert "Nyquist" in data["skipped_modes"]["16"]
    shift, sigma = np.array(data["shift_hz"]), np.array(data["sigma_hz"])
    assert (np.abs(shift) < 4 * np.sqrt(2) * sigma).all(), \
        "two intact records differ by their identification scatter only (4 sigma)"
    assert data["verdict"] != "crack indicated"


@pytest.mark.parametrize("suffix", [".csv", ".wav", ".uff"])
def test_record_that_is_a_pipe_or_a_device_is_refused_at_once(tmp_path, suffix):
    """The record readers: a FIFO would block and /dev/zero never end;
    both are refused in one line naming the flag and the file."""
    import os

    fifo = tmp_path / f"pipe{suffix}"
    os.mkfifo(fifo)
    with pytest.raises(RecordError, match=r"--record .*pipe.* not a regular file"):
        read_record(fifo)
    device = tmp_path / f"zero{suffix}"
    device.symlink_to("/dev/zero")
    with pytest.raises(RecordError, match=r"--baseline-record .*zero.* not a regular file"):
        read_record(device, "--baseline-record")


@pytest.mark.parametrize("seed", [0, 2])
def test_a_fit_that_leaves_its_band_is_not_found_and_never_quoted(seed):
    """White noise plus a strong line outside the band: the fit runs off to the line
    (seed 2) or to an absurd damping (seed 0); both are 'no resonance found', and the
    message quotes only the band, no number of the failed fit."""
    import re

    from hubvib.identification.bfft import IdentificationError, identify_mode

    rng = np.random.default_rng(seed)
    t = np.arange(4000) / 400.0
    x = rng.standard_normal(t.size) + 30 * np.sin(2 * np.pi * 75.0 * t)
    lo, hi = 53.5 * (1 - 6 * 0.02), 53.5 * (1 + 6 * 0.02)
    with pytest.raises(IdentificationError, match=r"no resonance found in its band") as caught:
        identify_mode(x, 400.0, 53.5, 0.02, acceleration=True)
    numbers = [float(v) for v in re.findall(r"\d+(?:\.\d+)?(?:e[+-]?\d+)?", str(caught.value))]
    assert numbers and all(lo - 0.01 <= v <= hi + 0.01 for v in numbers), str(caught.value)


def test_identified_modes_lie_in_their_band_with_bounded_damping():
    """Over records of noise and of a mode's neighbour, every mode the identifier returns
    lies inside its band with a half-power bandwidth inside the band."""
    from hubvib.identification.bfft import IdentificationError, identify_mode

    for seed in range(12):
        rng = np.random.default_rng(seed)
        t = np.arange(4000) / 400.0
        x = rng.standard_normal(t.size) + 30 * np.sin(2 * np.pi * 75.0 * t)
        try:
            mode = identify_mode(x, 400.0, 53.5, 0.02, acceleration=True)
        except IdentificationError:
            continue
        assert 53.5 * (1 - 0.12) < mode.frequency_hz < 53.5 * (1 + 0.12)
        assert 0 < mode.damping_ratio < 6 * 0.02


def _synthetic_fe(monkeypatch):
    """The diagnosis's FE cases replaced by the synthetic crack model's rows."""
    import hubvib.detection.diagnosis
    from tests.helpers.synthetic_rows import synthetic_fe_cases

    def fe_cases(sweep, progress=True):
        return synthetic_fe_cases(sweep.depths), 0

    monkeypatch.setattr(hubvib.detection.diagnosis, "crack_cases", fe_cases)


def test_records_without_an_identifiable_mode_get_a_verdict_not_an_error(
        tmp_path, monkeypatch, capsys):
    """Two valid records of white noise, too short for the lowest modes: no mode of the
    model is identified in both.  That is an answer (exit 0), `not identifiable from these
    records`, with a short reason per mode and what would help, not a one-line error."""
    import json

    _synthetic_fe(monkeypatch)
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE.replace("samples = 300", "samples = 100"))
    rng = np.random.default_rng(5)
    paths = [write_csv(tmp_path / f"r{k}.csv", Record(rng.standard_normal(1200), 4000.0))
             for k in (0, 1)]
    argv = ["diagnose", "--scene", str(scene), "--record", str(paths[1]),
            "--baseline-record", str(paths[0])]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "verdict: not identifiable from these records" in out
    assert "what would help:" in out and "records of at least" in out
    assert max(map(len, out.splitlines())) <= 100, "short lines, no wall of text"
    assert main(argv + ["--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["verdict"] == "not identifiable from these records" and data["modes"] == []
    assert data["depth_m"] is None and data["what_would_help"]
    assert set(map(int, data["skipped_modes"])) == set(range(1, 19)), "a reason per mode"
    assert all(len(why) < 160 for why in data["skipped_modes"].values())


def test_skipped_modes_and_remedies_name_their_ring_model():
    """A mode number means different modes in the two ring models: each line of what was
    not identified, and each remedy's modes, says whose number it is."""
    from hubvib.detection.from_records import DEGENERATE, skipped_lines, what_would_help

    lines = skipped_lines({3: DEGENERATE.format(other=4), 4: DEGENERATE.format(other=3),
                           9: "no resonance found in its band"}, "rigid")
    assert lines[0].startswith("rigid modes 3/4: degenerate pairs"), lines
    helps = what_would_help({10: "modal damping below 0.765 %", 15: "modal damping below "
                             "1.65 %", 1: "a longer record", 2: "a longer record"}, "elastic")
    for line in lines:
        assert line.startswith("rigid mode"), line
    assert helps == ["modal damping below 0.765 % (elastic mode 10), 1.65 % (elastic mode 15)",
                     "a longer record (elastic modes 1, 2)"]
