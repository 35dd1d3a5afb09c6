"""Accelerometer records from files: CSV, WAV or UFF 58 (SI).

``.csv``  header ``time_s,acceleration_m_s2``, one sample per line, time uniform
          and increasing [s], acceleration [m/s^2];
``.wav``  one channel; amplitude in whatever unit the file holds (frequencies do
          not depend on it);
``.uff`` / ``.unv``  the first dataset 58 holding a time response (function type 1),
          read with pyuff (the format modal test systems export).

Every error names the file and, for a CSV, the line.
"""
from __future__ import annotations

import csv
import io
import math
import stat
from pathlib import Path

import numpy as np

from hubvib.foundation.files import read_bytes, read_text

from .records import Record

#: fewest samples of a usable record
MIN_SAMPLES = 64
#: largest record file read [bytes]: 600 s at 51.2 kHz is about 0.6 GB as CSV text
MAX_RECORD_BYTES = 1 << 30
CSV_HEADER = ["time_s", "acceleration_m_s2"]


class RecordError(ValueError):
    """A record file cannot be used; the message names the file (and line)."""


def read_record(path: Path | str, flag: str = "--record") -> Record:
    """Read an acceleration record (see the module docstring); ``flag`` names the option
    the file came from in error messages."""
    path = Path(path)
    where = f"{flag} {str(path)!r}"
    suffix = path.suffix.lower()
    readers = {".csv": _csv, ".wav": _wav, ".uff": _uff, ".unv": _uff}
    if suffix not in readers:
        raise RecordError(f"{where}: unknown record format {suffix or '(none)'!r}; allowed: "
                          ".csv (time_s,acceleration_m_s2), .wav, .uff / .unv (dataset 58)")
    record = readers[suffix](path, flag)
    if record.values.size < MIN_SAMPLES or not np.isfinite(record.values).all():
        raise RecordError(f"{where}: {record.values.size} samples, finite: "
                          f"{bool(np.isfinite(record.values).all())}; a record needs at "
                          f"least {MIN_SAMPLES} finite samples")
    return record


def _csv(path: Path, flag: str) -> Record:
    where = f"{flag} {str(path)!r}"
    text = read_text(path, flag, RecordError, kind="CSV record", max_bytes=MAX_RECORD_BYTES)
    rows = [(n, r) for n, r in enumerate(csv.reader(io.StringIO(text)), start=1)
            if any(c.strip() for c in r)]
    if not rows or [c.strip() for c in rows[0][1]] != CSV_HEADER:
        raise RecordError(f"{where} line {rows[0][0] if rows else 1}: header must be "
                          f"{','.join(CSV_HEADER)}")
    values = np.empty((len(rows) - 1, 2))
    for k, (number, row) in enumerate(rows[1:]):
        try:
            values[k] = [float(row[0]), float(row[1])]
        except (ValueError, IndexError):
            raise RecordError(f"{where} line {number}: {','.join(row)!r}; it needs two "
                              "numbers (time [s], acceleration [m/s^2])") from None
    time = values[:, 0]
    if time.size < 2:
        raise RecordError(f"{where}: {time.size} sample(s); a record needs at least "
                          f"{MIN_SAMPLES}")
    step = np.diff(time)
    dt = float(np.median(step))
    bad = np.flatnonzero(~(np.abs(step - dt) <= 1e-6 * dt)) if dt > 0 else np.array([0])
    if bad.size:
        number = rows[int(bad[0]) + 2][0]
        raise RecordError(f"{where} line {number}: time_s = {float(time[bad[0] + 1])!r} breaks the "
                          f"uniform sampling of {dt:g} s; the time must increase in equal steps")
    return Record(values[:, 1].copy(), 1.0 / dt)


def _wav(path: Path, flag: str) -> Record:
    from scipy.io import wavfile

    where = f"{flag} {str(path)!r}"
    raw = read_bytes(path, flag, RecordError, kind="WAV record", max_bytes=MAX_RECORD_BYTES)
    try:
        rate, data = wavfile.read(io.BytesIO(raw))
    except (OSError, ValueError) as exc:
        raise RecordError(f"{where}: not a readable WAV file ({exc})") from None
    data = np.asarray(data)
    if data.ndim != 1:
        raise RecordError(f"{where}: {data.shape[1]} channels; a record has one")
    return Record(data.astype(float), float(rate))


def _uff(path: Path, flag: str) -> Record:
    import pyuff

    where = f"{flag} {str(path)!r}"
    _check_regular(path, where)  # pyuff opens the file by name
    try:
        sets = pyuff.UFF(str(path)).read_sets()
    except Exception as exc:  # pyuff raises bare Exceptions on malformed files
        raise RecordError(f"{where}: not a readable UFF file ({exc})") from None
    sets = [sets] if isinstance(sets, dict) else list(sets)
    for data in sets:
        if data.get("type") == 58 and int(data.get("func_type", 0)) == 1:
            x = np.asarray(data["x"], dtype=float)
            step = float(data.get("abscissa_inc") or (x[1] - x[0]))
            if not (math.isfinite(step) and step > 0):
                raise RecordError(f"{where}: dataset 58 abscissa increment {step!r}; it must "
                                  "be a positive time step [s]")
            return Record(np.real(np.asarray(data["data"])).astype(float), 1.0 / step)
    raise RecordError(f"{where}: no dataset 58 with a time response (function type 1)")


def _check_regular(path: Path, where: str) -> None:
    """Refuse what :func:`hubvib.foundation.files.read_bytes` refuses (missing, not a
    regular file, too large) for a reader that opens the file itself."""
    try:
        info = path.stat()
    except OSError as exc:
        raise RecordError(f"cannot read {where}: {exc.strerror}") from None
    if not stat.S_ISREG(info.st_mode):
        raise RecordError(f"{where} is not a regular file (a directory, device, pipe or "
                          "socket); give a record file")
    if info.st_size > MAX_RECORD_BYTES:
        raise RecordError(f"{where} is larger than {MAX_RECORD_BYTES} bytes, the most a "
                          "record file may hold here")
