"""A CSV of natural frequencies identified on a reducer (input of ``hubvib diagnose``).

Columns (header line first, comma-separated)::

    frequency_hz      required; identified natural frequency [Hz], > 0, no duplicates
    mode              optional; the model mode it belongs to (1 = lowest), no duplicates
    baseline_hz       optional; the same mode measured on this reducer intact [Hz], > 0
    damping_ratio     optional; the mode's identified damping ratio [-], in (0, 0.5)
    record_s          optional; length of the record it was identified from [s], > 0
    sigma_hz          optional; standard deviation of the identified frequency [Hz], > 0
                      (instead of damping_ratio / record_s)

Without ``mode`` each frequency is paired with a model mode by nearest value;
without ``baseline_hz`` the model's intact spectrum is the baseline.  Without
``sigma_hz`` the identification scatter follows from the row's damping and
record length (the scene's ``[detection] damping_ratio`` / ``record_length_s``
where a column is missing).  Every error names the file line or the column.
"""
from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hubvib.foundation.files import read_text

COLUMNS = ("frequency_hz", "mode", "baseline_hz", "damping_ratio", "record_s", "sigma_hz")
#: column -> (what it is, low, high) of the optional per-row numbers (open interval)
_RANGES = {"damping_ratio": ("a damping ratio", 0.0, 0.5),
           "record_s": ("a record length in s", 0.0, math.inf),
           "sigma_hz": ("a standard deviation in Hz", 0.0, math.inf)}


class MeasuredError(ValueError):
    """The measured-frequency CSV is invalid; the message names the line or column."""


@dataclass(frozen=True)
class Measured:
    """Identified natural frequencies.

    Attributes
    ----------
    frequency_hz : ndarray
        [Hz], in file order.
    mode : ndarray of int or None
        Model mode numbers (1-based) when the file gives them.
    baseline_hz : ndarray or None
        The reducer's own intact frequencies [Hz] when the file gives them.
    damping_ratio, record_s, sigma_hz : ndarray or None
        Per-row damping [-], record length [s] and frequency standard deviation [Hz]
        when the file gives them.
    lines : tuple of int
        File line of each row (the header is line 1).
    source : str
        File name, for messages.
    """

    frequency_hz: np.ndarray
    mode: np.ndarray | None
    baseline_hz: np.ndarray | None
    lines: tuple[int, ...]
    source: str
    damping_ratio: np.ndarray | None = None
    record_s: np.ndarray | None = None
    sigma_hz: np.ndarray | None = None


def read_measured(path: Path | str) -> Measured:
    """Read and validate a measured-frequency CSV (see the module docstring)."""
    path = Path(path)
    return parse_measured(read_text(path, "--measured", MeasuredError, kind="CSV"), path.name)


def parse_measured(text: str, source: str = "measured.csv") -> Measured:
    rows = [(number, row) for number, row in enumerate(csv.reader(io.StringIO(text)), start=1)
            if any(cell.strip() for cell in row)]
    if not rows:
        raise MeasuredError(f"{source}: empty; it needs a header line with the column "
                            f"frequency_hz and one line per identified frequency")
    header_line, header = rows[0]
    header = [h.strip() for h in header]
    unknown = [h for h in header if h not in COLUMNS]
    if unknown or "frequency_hz" not in header or len(set(header)) != len(header):
        raise MeasuredError(f"{source} line {header_line}: header {header}; it needs the column "
                            f"frequency_hz and may add {', '.join(COLUMNS[1:])} (each once)")
    if "sigma_hz" in header and ({"damping_ratio", "record_s"} & set(header)):
        raise MeasuredError(f"{source} line {header_line}: header {header}; give either "
                            f"sigma_hz or damping_ratio / record_s, not both")
    if len(rows) == 1:
        raise MeasuredError(f"{source}: no frequencies below the header")
    columns = {name: [] for name in header}
    lines = []
    for number, row in rows[1:]:
        if len(row) != len(header):
            raise MeasuredError(f"{source} line {number}: {len(row)} value(s), but the header "
                                f"has {len(header)} columns ({', '.join(header)})")
        for name, cell in zip(header, row):
            columns[name].append(_value(source, number, name, cell.strip()))
        lines.append(number)
    frequency = np.array(columns["frequency_hz"])
    seen = {}
    for value, number in zip(frequency, lines):
        if value in seen:
            raise MeasuredError(f"{source} line {number}: frequency_hz = {value:g} repeats "
                                f"line {seen[value]}; each identified frequency once")
        seen[value] = number
    mode = None
    if "mode" in columns:
        mode = np.array(columns["mode"], dtype=int)
        first = {}
        for value, number in zip(mode, lines):
            if value in first:
                raise MeasuredError(f"{source} line {number}: mode = {value} repeats line "
                                    f"{first[value]}")
            first[value] = number
    optional = {name: np.array(columns[name]) if name in columns else None
                for name in ("baseline_hz", *_RANGES)}
    return Measured(frequency, mode, optional["baseline_hz"], tuple(lines), source,
                    optional["damping_ratio"], optional["record_s"], optional["sigma_hz"])


def _value(source, number, name, cell):
    where = f"{source} line {number}: {name} = {cell!r}"
    if name == "mode":
        try:
            value = int(cell)
        except ValueError:
            raise MeasuredError(f"{where}, but it must be a mode number (an integer >= 1)"
                                ) from None
        if not 1 <= value <= 10_000:  # a model has 9 + 3N <= 45 modes; bounded before numpy
            raise MeasuredError(f"{where}, but it must be a mode number (an integer 1..10000)")
        return value
    if name in _RANGES:
        what, low, high = _RANGES[name]
        try:
            value = float(cell)
        except ValueError:
            value = math.nan
        if not (math.isfinite(value) and low < value < high):
            raise MeasuredError(f"{where}, but it must be {what} in ({low:g}, {high:g})")
        return value
    try:
        value = float(cell)
    except ValueError:
        raise MeasuredError(f"{where}, but it must be a frequency in Hz (a number > 0)"
                            ) from None
    if not (math.isfinite(value) and value > 0):
        raise MeasuredError(f"{where}, but it must be a frequency in Hz (a finite number > 0)")
    return value
