"""The one reader for every file the user (or the cache) hands in: regular files only,
size-limited, UTF-8 text, every refusal one line naming what the file is and where.

Scene files, ``--params``, design files (``--design``, ``[design] file =``),
``diagnose --measured``, ``harmonics --periods``, the lift table and the FE cache
entries all go through :func:`read_text`.  A FIFO would block forever and
``/dev/zero`` (or a cache entry symlinked to it) would never end: the file is
opened without blocking and checked with ``fstat`` on the open descriptor (so a
symlink or a swap between the check and the read cannot slip through), and at
most ``max_bytes + 1`` bytes are read (bounded even when the size lies, as in
``/proc``).
"""
from __future__ import annotations

import codecs
import os
import stat
from pathlib import Path

from hubvib.foundation.errors import InputError

#: largest TOML or small CSV file read [bytes]; a real scene or design is well under 10 kB
MAX_FILE_BYTES = 1 << 20
#: largest data table read [bytes] (a pulse-period record: 10^6 periods ~ 20 MB)
MAX_TABLE_BYTES = 64 << 20


def read_text(path: Path | str, what: str, error=InputError, kind: str = "TOML",
              max_bytes: int = MAX_FILE_BYTES) -> str:
    """The UTF-8 text of ``path``; every refusal names ``what`` and the file.

    Parameters
    ----------
    path : the file
    what : how the message names it (``"design file"``, ``"--periods"``)
    error : the exception class raised (a subclass of ``ValueError``)
    kind : the format the text should be in, for the messages (``"TOML"``, ``"CSV"``)
    max_bytes : the largest size accepted [bytes]

    Raises
    ------
    error
        The file is missing, not a regular file (directory, device, pipe, socket),
        larger than ``max_bytes``, UTF-16, binary (NUL bytes) or not UTF-8.  A UTF-8
        byte-order mark is skipped.
    """
    name = f"{what} {str(path)!r}"
    data = read_bytes(path, what, error, kind, max_bytes)
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        raise error(f"{name} is UTF-16 text; {kind} must be UTF-8 (save it as UTF-8)")
    if b"\0" in data:
        raise error(f"{name} is a binary file (it holds NUL bytes), not {kind} text")
    try:
        return data.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise error(f"{name} is not UTF-8 text (line {line}, byte {exc.start} is "
                    f"0x{data[exc.start]:02x}); {kind} must be UTF-8") from None


def read_bytes(path: Path | str, what: str, error=InputError, kind: str = "TOML",
               max_bytes: int = MAX_FILE_BYTES) -> bytes:
    """The bytes of the regular file ``path`` (at most ``max_bytes``); the refusals of
    :func:`read_text` for a missing file, a directory, a device, pipe or socket, or a file
    that is too large."""
    name = f"{what} {str(path)!r}"
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)  # a FIFO opens at once, unread
    except IsADirectoryError:
        raise error(f"{name} is a directory, not a {kind} file") from None
    except OSError as exc:
        raise error(f"cannot read {name}: {exc.strerror}") from None
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise error(f"{name} is a directory, not a {kind} file")
        if not stat.S_ISREG(info.st_mode):
            raise error(f"{name} is not a regular file (a device, pipe or socket); "
                        f"give a {kind} file")
        if info.st_size > max_bytes:
            raise error(_too_large(name, kind, max_bytes))
        os.set_blocking(fd, True)
        with os.fdopen(fd, "rb", closefd=False) as handle:
            data = handle.read(max_bytes + 1)  # bounded even if the size lied (/proc)
    except OSError as exc:
        raise error(f"cannot read {name}: {exc.strerror or exc}") from None
    finally:
        os.close(fd)
    if len(data) > max_bytes:
        raise error(_too_large(name, kind, max_bytes))
    return data


def _too_large(name: str, kind: str, max_bytes: int) -> str:
    return f"{name} is larger than {max_bytes} bytes, the most a {kind} file may hold here"
