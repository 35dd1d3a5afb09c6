"""``foundation.blas`` reads the process's mapped libraries again only when one was loaded
or unloaded since its last reading: the same handles as reading them every time."""
from __future__ import annotations

import ctypes
import ctypes.util
import sys

import pytest

from hubvib.foundation import blas


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's dl_iterate_phdr")
def test_a_library_loaded_since_is_read_again():
    import numpy  # noqa: F401 - its OpenBLAS mapped

    assert blas._handles() == blas._read_handles()
    before = blas._loads()
    assert before is not None and blas._handles() is blas._handles()
    name = next((n for n in ("uuid", "sqlite3", "expat", "crypt", "gdbm", "readline", "png", "jpeg")
                 if (path := ctypes.util.find_library(n)) and path not in
                 open("/proc/self/maps", encoding="utf-8").read()), None)
    if name is None:
        pytest.skip("no unloaded library to load")
    ctypes.CDLL(ctypes.util.find_library(name))
    assert blas._loads()[0] > before[0]
    assert blas._handles() == blas._read_handles()
    with blas.blas_threads(1):
        assert set(blas.blas_thread_counts()) <= {1}
