"""File output: a reader never sees a half-written file, and a folder never a mixed set.

``atomic_path`` is the one way a file is written: to a temporary name in the
same folder, moved into place (``os.replace``) only when complete, with the
mode the umask gives (0644 under umask 022; ``mkstemp`` alone makes 0600).
``write_text``, ``write_json``, ``write_csv`` and ``save_figure`` use it; a
writer that needs a file name (meshio, pyvista, ``np.savez``) uses it directly::

    with atomic_path(folder / "ring.vtu") as tmp:
        meshio.write(tmp, mesh)

``output_set`` writes a whole set of files (a run's tables, plots, report)::

    with output_set(folder) as stage:
        write_csv(stage / "modes.csv", rows)
        ...

It checks before any work that ``folder`` can be written, locks it (a second
run into the same folder is refused: two runs never interleave their files),
lets the writers fill a hidden stage folder inside it, and only when the set
is complete moves every file into place and removes the files of the previous
set that this one does not have.  On any failure (a full disk, an interrupt,
an error) the stage is removed and the folder keeps its previous set.
"""
from __future__ import annotations

import csv
import errno
import io
import json
import math
import numbers
import os
import re
import shutil
import signal
import socket
import tempfile
import threading
import time
from contextlib import contextmanager
from pathlib import Path, PurePosixPath

#: lock file, stage folders and the list of the current set, all hidden in the output folder
LOCK_NAME = ".hubvib.lock"
STAGE_PREFIX = ".hubvib-stage-"
MANIFEST_NAME = ".hubvib-files.json"
_DISK_FULL = {errno.ENOSPC, errno.EDQUOT, errno.EFBIG}
#: hidden scratch files and folders older than this are stale whoever wrote them [s]: no
#: single write takes a day, and an owner on another host cannot be asked
STALE_SCRATCH_S = 24 * 3600
#: the owner a scratch name carries, ``~<pid>@<host>~`` (``remove_stale_scratch``)
_OWNER = re.compile(r"~(\d+)@([A-Za-z0-9-]*)~")


class OutputError(OSError):
    """A file or folder could not be written; ``str()`` is one line naming it."""

    def __str__(self) -> str:
        return f"cannot write {self.filename!r}: {self.strerror}"


class OutputFolderError(OutputError):
    """The output folder cannot be used (not a folder, not writable, busy)."""

    def __str__(self) -> str:
        return f"cannot write the output folder {self.filename!r}: {self.strerror}"


def file_mode() -> int:
    """Mode of a new file under the process umask (0o644 under umask 022)."""
    try:  # Linux >= 4.7 reports it without changing it
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("Umask:"):
                    return 0o666 & ~int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


@contextmanager
def atomic_path(path: Path):
    """A temporary path beside ``path``; when the block succeeds it replaces ``path``.

    The temporary name keeps the suffix (writers pick the format from it).  On
    failure it is removed and ``path`` is untouched; an ``OSError`` comes out as
    :class:`OutputError` naming ``path``.
    """
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.{_owner()}",
                                   suffix=path.suffix or ".tmp")
        os.close(fd)
    except OSError as exc:
        raise OutputError(exc.errno, exc.strerror, str(path)) from exc
    tmp = Path(tmp)
    try:
        yield tmp
        os.chmod(tmp, file_mode())
        os.replace(tmp, path)
    except OutputError:
        raise
    except OSError as exc:
        raise OutputError(exc.errno, exc.strerror, str(path)) from exc
    finally:
        tmp.unlink(missing_ok=True)


@contextmanager
def atomic_folder(path: Path):
    """A scratch folder beside ``path``; when the block succeeds it takes ``path``'s place
    whole (a folder already there is removed first).  On failure it is removed and
    ``path`` is untouched."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    scratch = Path(tempfile.mkdtemp(dir=path.parent, prefix=f".{path.name}.{_owner()}"))
    try:
        yield scratch
        shutil.rmtree(path, ignore_errors=True)
        os.replace(scratch, path)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def _host() -> str:
    return re.sub(r"[^A-Za-z0-9-]", "-", socket.gethostname())[:32]


def _owner() -> str:
    """``~<pid>@<host>~``: who writes a scratch file or folder (read back by
    ``remove_stale_scratch``)."""
    return f"~{os.getpid()}@{_host()}~"


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # another user's process, or no way to ask: take it as running
        return True
    return True


def remove_stale_scratch(folder: Path, max_age: float = STALE_SCRATCH_S) -> list[Path]:
    """Remove the hidden entries of ``folder`` that no running process will finish: those
    whose owner (``atomic_path``, ``atomic_folder``) on this host has exited, and any
    older than ``max_age`` [s] (an owner on another host, or a name without one).  For
    folders where every hidden entry is such scratch (the cache's); returns what went."""
    try:
        entries = list(Path(folder).iterdir())
    except OSError:
        return []
    host, now, removed = _host(), time.time(), []
    for entry in entries:
        if not entry.name.startswith("."):
            continue
        owner = _OWNER.search(entry.name)
        try:
            stale = ((owner is not None and owner.group(2) == host
                      and not _running(int(owner.group(1))))
                     or now - entry.lstat().st_mtime > max_age)
            if not stale:
                continue
            if entry.is_dir() and not entry.is_symlink():
                shutil.rmtree(entry)
            else:
                entry.unlink()
        except OSError:
            continue  # gone meanwhile, or not ours to remove
        removed.append(entry)
    return removed


def write_text(path: Path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    with atomic_path(path) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="") as handle:
            handle.write(text)
    return Path(path)


def finite_or_none(x) -> float | None:
    """``x`` as a float for JSON, None where it is NaN or infinite."""
    x = float(x)
    return x if math.isfinite(x) else None


def explained(payload: dict, **reasons: str) -> dict:
    """``payload`` with ``<key>_reason`` right after each ``key`` of ``reasons`` whose value
    is null or a list holding a null: the rule that every null a results file writes says
    why.  A key ``payload`` does not hold gets no reason: there is no null to explain."""
    out = {}
    for key, value in payload.items():
        out[key] = value
        if key in reasons and (value is None or (isinstance(value, list)
                                                 and any(v is None for v in value))):
            out[f"{key}_reason"] = reasons[key]
    return out


def json_text(data, indent: int | None = 2) -> str:
    """Standard JSON (no NaN or Infinity); a non-finite number is a ``ValueError`` naming it."""
    try:
        return json.dumps(data, indent=indent, allow_nan=False)
    except ValueError:
        where, value = _non_finite(data, "")
        if where is None:
            raise
        raise ValueError(f"{where or 'value'} = {value!r} is not a finite number; "
                         "standard JSON cannot hold it") from None


def write_json(path: Path, data) -> Path:
    return write_text(path, json_text(data) + "\n")


def csv_cell(value):
    """A table cell as written: a NaN (a value that has none) as an empty cell, every
    other value as it is (``csv`` writes ``None`` as an empty cell too)."""
    if (isinstance(value, numbers.Real) and not isinstance(value, numbers.Integral)
            and math.isnan(value)):
        return ""
    return value


def csv_text(rows: list[dict], fieldnames=None) -> str:
    """``rows`` as CSV text with a header (``fieldnames``, default the first row's keys;
    none and no rows: empty); a NaN is an empty cell (``csv_cell``), never ``nan``."""
    fieldnames = list(rows[0]) if fieldnames is None and rows else fieldnames
    buffer = io.StringIO()
    if fieldnames:
        writer = csv.DictWriter(buffer, fieldnames=fieldnames)
        writer.writeheader()
        writer.writerows({k: csv_cell(v) for k, v in row.items()} for row in rows)
    return buffer.getvalue()


def write_csv(path: Path, rows: list[dict], fieldnames=None) -> Path:
    """``csv_text(rows, fieldnames)`` written to ``path`` atomically."""
    return write_text(path, csv_text(rows, fieldnames))


def save_figure(figure, path: Path) -> Path:
    """Save a matplotlib figure atomically as PNG and close it."""
    try:
        with atomic_path(path) as tmp:
            figure.savefig(tmp, dpi=120, bbox_inches="tight")
    finally:
        import matplotlib.pyplot as plt

        plt.close(figure)
    return Path(path)


def check_folder(folder: Path) -> list[Path]:
    """Make sure ``folder`` is a folder this process can write into, creating it if needed.

    Returns the folders it created (deepest first), for :func:`remove_if_empty`.
    Raises :class:`OutputError` naming the folder (a file, read-only, under
    ``/proc``, a name too long, ...).
    """
    folder = Path(folder)
    created = []
    try:
        probe = folder
        while not probe.exists() and probe != probe.parent:
            created.append(probe)
            probe = probe.parent
        if folder.exists() and not folder.is_dir():
            raise OutputFolderError(errno.ENOTDIR, "it exists and is not a folder", str(folder))
        folder.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=folder).close()
    except OutputError:
        remove_if_empty(created)
        raise
    except OSError as exc:
        remove_if_empty(created)
        raise OutputFolderError(exc.errno, exc.strerror, str(folder)) from None
    return created


def remove_if_empty(folders: list[Path]) -> None:
    """Remove these folders, deepest first, as long as they are empty."""
    for folder in folders:
        try:
            folder.rmdir()
        except OSError:
            return


@contextmanager
def folder_lock(folder: Path, wait: bool = False):
    """Hold an exclusive lock on ``folder`` (POSIX ``flock`` on a hidden lock file).

    With ``wait=False`` a folder another process holds is refused at once with
    :class:`OutputError` (EBUSY) naming the folder and the holder's pid.  The
    lock file is removed on release.
    """
    try:
        import fcntl
    except ImportError:  # not POSIX: no lock
        yield
        return
    path = Path(folder) / LOCK_NAME
    # a Ctrl-C between creating the file and the try below left an empty lock file
    # behind: it waits until then (not while waiting for another run: that stays stoppable)
    held = _InterruptsHeld(active=not wait)
    try:
        fd = _take_lock(path, folder, wait, fcntl)
    except BaseException:
        held.release()
        raise
    try:
        held.release()  # a Ctrl-C that came meanwhile is raised here, inside the try
        yield
    finally:
        path.unlink(missing_ok=True)
        os.close(fd)


def _take_lock(path: Path, folder: Path, wait: bool, fcntl) -> int:
    """The descriptor of the lock file at ``path``, locked and holding this pid."""
    while True:
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise OutputFolderError(exc.errno, exc.strerror, str(folder)) from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except BlockingIOError:
            holder = os.read(fd, 32).decode("ascii", "replace").strip() or "unknown"
            os.close(fd)
            raise OutputFolderError(
                errno.EBUSY, f"another hubvib run (pid {holder}) is writing into it; wait for "
                "it to finish or choose another output folder", str(folder)) from None
        try:  # the previous holder removes the file on release: lock the one at the path
            same = os.path.samestat(os.fstat(fd), os.stat(path))
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)
    os.ftruncate(fd, 0)
    os.write(fd, f"{os.getpid()}\n".encode("ascii"))
    return fd


class _InterruptsHeld:
    """SIGINT recorded instead of raised until :meth:`release` (main thread only; Python
    runs signal handlers in the main thread whichever thread the kernel picked)."""

    def __init__(self, active: bool = True):
        self.pending = False
        self.active = active and threading.current_thread() is threading.main_thread()
        if self.active:
            self.previous = signal.signal(signal.SIGINT, self._record)

    def _record(self, signum, frame):
        self.pending = True

    def release(self) -> None:
        """Restore the previous handler; act on a SIGINT that came meanwhile."""
        if not self.active:
            return
        self.active, previous = False, self.previous
        signal.signal(signal.SIGINT, previous if previous is not None else signal.SIG_DFL)
        if self.pending:
            if callable(previous):
                previous(signal.SIGINT, None)  # default_int_handler: KeyboardInterrupt
            elif previous != signal.SIG_IGN:
                raise KeyboardInterrupt


@contextmanager
def locked_folder(folder: Path):
    """``folder`` checked and locked for a command that writes into it directly (a
    resumable study appends to its own files); removed again if it was created and
    stays empty."""
    created = check_folder(folder)
    try:
        with folder_lock(folder):
            yield Path(folder)
    finally:
        remove_if_empty(created)


@contextmanager
def output_set(folder: Path):
    """Write one set of files into ``folder`` completely or not at all; yields the stage.

    See the module docstring.  An ``OSError`` while writing comes out as
    :class:`OutputError` naming the file and saying what was discarded.
    """
    folder = Path(folder)
    with locked_folder(folder):
        for stale in folder.glob(f"{STAGE_PREFIX}*"):  # left by a killed run
            shutil.rmtree(stale, ignore_errors=True)
        try:
            stage = Path(tempfile.mkdtemp(prefix=STAGE_PREFIX, dir=folder))
        except OSError as exc:
            raise OutputFolderError(exc.errno, exc.strerror, str(folder)) from None
        try:
            yield stage
            with _signals_deferred():
                _commit(stage, folder)
        except OSError as exc:
            name = _inside(exc.filename, folder, stage)
            if not (isinstance(exc, OutputError) or name or exc.errno in _DISK_FULL):
                raise  # not about this output (e.g. reading an input): as it is
            done = _files(stage)
            name = name or str(folder)
            raise OutputError(
                exc.errno, f"{exc.strerror}; nothing of this run was written to {str(folder)!r} "
                f"({len(done)} finished file(s) discarded: "
                f"{', '.join(p.as_posix() for p in done) or 'none'})", name) from None
        finally:
            with _signals_deferred():  # a stop that comes now still removes the whole stage
                shutil.rmtree(stage, ignore_errors=True)


def _inside(filename, folder: Path, stage: Path) -> str:
    """``filename`` if it lies in ``folder`` (from the stage: where it would have gone),
    else ``""``."""
    if not filename:
        return ""
    path = Path(os.path.abspath(filename))
    for base, target in ((stage, folder), (folder, folder)):
        try:
            return str(target / path.relative_to(os.path.abspath(base)))
        except ValueError:
            continue
    return ""


def _files(stage: Path) -> list[PurePosixPath]:
    return sorted(PurePosixPath(p.relative_to(stage).as_posix()) for p in stage.rglob("*")
                  if p.is_file() and not p.name.startswith("."))


def _commit(stage: Path, folder: Path) -> None:
    new = _files(stage)
    for rel in new:  # refuse before moving anything: a half-moved set is a mixed set
        target = folder / rel
        if target.is_dir() and not target.is_symlink():
            raise OutputError(errno.EISDIR, "a folder of that name is in the way", str(target))
    mode = file_mode()
    for rel in new:
        (folder / rel).parent.mkdir(parents=True, exist_ok=True)
        os.chmod(stage / rel, mode)  # whatever wrote it (meshio, pyvista): the umask's mode
        os.replace(stage / rel, folder / rel)
    inside = folder.resolve()
    for rel in set(_previous_set(folder)) - set(new):
        old = folder / rel
        if old.is_file() and not old.is_symlink() and inside in old.resolve().parents:
            old.unlink()
            remove_if_empty([p for p in old.parents if folder in p.parents])
    write_json(folder / MANIFEST_NAME, {"files": [p.as_posix() for p in new]})


def _previous_set(folder: Path) -> list[PurePosixPath]:
    """The files the last set wrote, as listed by it (entries outside the folder ignored)."""
    try:
        entries = json.loads((folder / MANIFEST_NAME).read_text(encoding="utf-8"))["files"]
    except (OSError, ValueError, KeyError, TypeError):
        return []
    safe = []
    for entry in entries if isinstance(entries, list) else []:
        rel = PurePosixPath(entry) if isinstance(entry, str) else None
        if rel is not None and entry and not rel.is_absolute() and ".." not in rel.parts:
            safe.append(rel)
    return safe


@contextmanager
def _signals_deferred():
    """Ctrl-C and SIGTERM wait until the block is done (the moves take milliseconds).

    Their handlers are swapped for a recorder, not blocked with a signal mask: a mask is the
    calling thread's, and the kernel hands a process-directed signal to any thread that does
    not block it (a progress ticker, a pool's manager thread), after which Python ran the
    handler in the main thread in the middle of the moves (the files in place, the list of
    the set not)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    pending = []
    stops = [s for s in (signal.SIGINT, getattr(signal, "SIGTERM", None)) if s is not None]
    previous = {s: signal.signal(s, lambda signum, frame: pending.append(signum)) for s in stops}
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, signal.SIG_DFL if handler is None else handler)
        for signum in dict.fromkeys(pending):  # each once, in the order they came
            handler = previous[signum]
            if callable(handler):
                handler(signum, None)
            elif handler == signal.SIG_DFL:
                signal.raise_signal(signum)


def _non_finite(data, where: str):
    """Path (``""`` for ``data`` itself) and value of the first non-finite float in nested
    dicts/lists, or ``(None, None)``."""
    if isinstance(data, float) and not math.isfinite(data):
        return where, data
    items = data.items() if isinstance(data, dict) else (
        enumerate(data) if isinstance(data, (list, tuple)) else ())
    for key, value in items:
        found = _non_finite(value, f"{where}[{key}]" if isinstance(key, int) else
                            f"{where}.{key}" if where else str(key))
        if found[0] is not None:
            return found
    return None, None


#: files of one folder and kind listed one by one on a ``written:`` line; more are counted
LISTED_FILES = 3


def written_line(files) -> str:
    """``written: ...`` for ``files`` (paths) on one line: each file named, except where more
    than ``LISTED_FILES`` share a folder and a suffix, which are counted with the first and
    last name (``22 VTU files in out/ (crack_step_00.vtu .. crack_step_21.vtu)``), in the
    order of their first file."""
    groups: dict = {}
    for file in map(Path, files):
        groups.setdefault((file.parent, file.suffix.lower()), []).append(file)
    parts = []
    for (folder, suffix), members in groups.items():
        if len(members) <= LISTED_FILES:
            parts += [str(f) for f in members]
            continue
        kind = suffix.lstrip(".").upper() or "extensionless"
        parts.append(f"{len(members)} {kind} files in {folder}{os.sep} ({members[0].name} .. "
                     f"{members[-1].name})")
    return f"written: {', '.join(parts)}"
