"""Run a block of code with OpenBLAS (and MKL, where PARDISO loaded it) limited to a number
of threads (the FE solvers and the batched lumped solves both need it; stdlib only).

SuperLU's triangular solves with many right-hand sides call small BLAS
kernels; with two OpenBLAS threads on a busy 2-core machine they spin-wait
(many times slower than on one thread: ``docs/fe_accuracy.md#measured-behind-the-codes-choices``).  ``OPENBLAS_NUM_THREADS`` is read only when
the library loads, so the count is set through the library itself, in every
OpenBLAS found in ``/proc/self/maps`` (numpy and scipy each bundle one).
"""
from __future__ import annotations

import ctypes
import functools
import os
from contextlib import contextmanager

_PREFIXES = ("openblas", "scipy_openblas")
_SUFFIXES = ("", "64_")


@contextmanager
def blas_threads(count: int):
    """Every loaded OpenBLAS and MKL limited to ``count`` threads inside the block, restored
    after; a library loaded inside the block is not limited (load it first); nothing happens
    where none is found (another BLAS, or not Linux)."""
    handles = _handles()
    previous = [get() for get, _ in handles]
    try:
        for _, set_threads in handles:
            set_threads(count)
        yield
    finally:
        for (_, set_threads), n in zip(handles, previous):
            set_threads(n)


def blas_thread_counts() -> list[int]:
    """Current thread count of every loaded OpenBLAS and MKL (empty when none is found)."""
    return [get() for get, _ in _handles()]


def _handles() -> tuple:
    """(get, set) thread-count functions of every OpenBLAS and MKL loaded now: the maps
    are read again whenever a library was loaded or unloaded since the last reading
    (``_loads``), so a library loaded later (MKL with PARDISO) is found too (the
    detection stage's ~1,300 batched solves each read them)."""
    loads = _loads()
    last_loads, last_handles = _LAST[0]
    if loads is not None and loads == last_loads:
        return last_handles
    handles = _read_handles()
    if loads is not None:
        _LAST[0] = (loads, handles)
    return handles


#: the last reading, one tuple (threads replace it whole): ``_loads()`` then, its handles
_LAST: list = [(None, ())]


class _PhdrInfo(ctypes.Structure):
    _fields_ = [("addr", ctypes.c_void_p), ("name", ctypes.c_char_p),
                ("phdr", ctypes.c_void_p), ("phnum", ctypes.c_uint16),
                ("adds", ctypes.c_ulonglong), ("subs", ctypes.c_ulonglong)]


_PHDR_CALLBACK = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.POINTER(_PhdrInfo), ctypes.c_size_t,
                                  ctypes.c_void_p)


def _loads():
    """(libraries loaded, unloaded) by this process so far (glibc's ``dl_iterate_phdr``
    counters, read from its first entry), or None where they cannot be read."""
    iterate = _dl_iterate_phdr()
    if iterate is None:
        return None
    seen = []

    def first(info, size, _):
        if size >= ctypes.sizeof(_PhdrInfo):
            seen.append((info.contents.adds, info.contents.subs))
        return 1  # stop at the first entry

    iterate(_PHDR_CALLBACK(first), None)
    return seen[0] if seen else None


@functools.cache
def _dl_iterate_phdr():
    try:
        function = ctypes.CDLL(None).dl_iterate_phdr
    except (OSError, AttributeError):
        return None
    function.argtypes = [_PHDR_CALLBACK, ctypes.c_void_p]
    function.restype = ctypes.c_int
    return function


def _read_handles() -> tuple:
    try:
        with open("/proc/self/maps", encoding="utf-8") as maps:
            # the substring test on the raw line first: of ~1,000 mapped lines only those
            # that can name a BLAS are split (reading is most of the call's time)
            paths = sorted({line.split()[-1] for line in maps
                            if ("openblas" in (low := line.lower()) or "libmkl_rt" in low)
                            and _is_blas(os.path.basename(line.split()[-1]).lower())})
    except OSError:
        return ()
    return tuple(h for path in paths if (h := _library_handles(path)) is not None)


def _is_blas(name: str) -> bool:
    return "openblas" in name or name.startswith("libmkl_rt")


@functools.lru_cache(maxsize=None)
def _library_handles(path: str):
    try:
        library = ctypes.CDLL(path)
    except OSError:
        return None
    pairs = [(f"{p}_get_num_threads{s}", f"{p}_set_num_threads{s}")
             for p in _PREFIXES for s in _SUFFIXES]
    pairs.append(("MKL_Get_Max_Threads", "MKL_Set_Num_Threads"))  # libmkl_rt (PARDISO)
    for get_name, set_name in pairs:
        get = getattr(library, get_name, None)
        set_threads = getattr(library, set_name, None)
        if get is not None and set_threads is not None:
            get.restype = ctypes.c_int
            set_threads.argtypes = [ctypes.c_int]
            return get, set_threads
    return None
