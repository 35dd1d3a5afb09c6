"""``K x`` for a symmetric matrix stored as its upper block triangle, by MKL's sparse BLAS.

MKL's inspector-executor ``mkl_sparse_d_mv`` multiplies a block-CSR matrix marked
symmetric (upper triangle stored) without forming the lower triangle; scipy has to
transpose it slice by slice, several times slower on the solid ring.
``tests/fem/test_solid.py`` checks it against the
whole CSR matrix.  The handle shares the caller's arrays (no copy of the matrix).
"""
from __future__ import annotations

import ctypes

import numpy as np

from .pardiso import mkl_runtime

#: MKL's sparse BLAS enumerations (mkl_spblas.h)
_ZERO_BASED, _ROW_MAJOR, _NO_TRANSPOSE = 0, 101, 10
_SYMMETRIC, _UPPER, _NON_UNIT = 21, 41, 50


class _Description(ctypes.Structure):
    _fields_ = [("type", ctypes.c_int), ("mode", ctypes.c_int), ("diag", ctypes.c_int)]


class SymmetricBlockProduct:
    """``x -> K x`` (x (n,) or (n, k)) for the symmetric K whose upper block triangle
    (diagonal blocks whole, blocks row-major) is ``(indptr, indices, values)``."""

    def __init__(self, indptr, indices, values):
        self._library = mkl_runtime()
        self.block = values.shape[1]
        self.n = (len(indptr) - 1) * self.block
        self._indptr = np.ascontiguousarray(indptr, dtype=np.int32)
        self._indices = np.ascontiguousarray(indices, dtype=np.int32)
        self._values = np.ascontiguousarray(values, dtype=np.float64)
        self._handle = ctypes.c_void_p()
        rows, pointer = ctypes.c_int32(len(indptr) - 1), ctypes.c_void_p
        status = self._library.mkl_sparse_d_create_bsr(
            ctypes.byref(self._handle), _ZERO_BASED, _ROW_MAJOR, rows, rows,
            ctypes.c_int32(self.block), pointer(self._indptr.ctypes.data),
            pointer(self._indptr[1:].ctypes.data), pointer(self._indices.ctypes.data),
            pointer(self._values.ctypes.data))
        if status != 0:
            raise RuntimeError(f"mkl_sparse_d_create_bsr failed with status {status}")
        self._mv = self._library.mkl_sparse_d_mv
        self._mv.argtypes = [ctypes.c_int, ctypes.c_double, ctypes.c_void_p, _Description,
                             ctypes.c_void_p, ctypes.c_double, ctypes.c_void_p]
        self._description = _Description(_SYMMETRIC, _UPPER, _NON_UNIT)

    def __call__(self, x):
        x = np.asarray(x, dtype=np.float64)
        columns = x.reshape(self.n, -1)
        y = np.empty_like(columns, order="F")
        for j in range(columns.shape[1]):
            column = np.ascontiguousarray(columns[:, j])
            status = self._mv(_NO_TRANSPOSE, 1.0, self._handle, self._description,
                              column.ctypes.data, 0.0, y[:, j].ctypes.data)
            if status != 0:
                raise RuntimeError(f"mkl_sparse_d_mv failed with status {status}")
        return y.reshape(x.shape)

    def __del__(self):
        try:
            if self._handle:
                self._library.mkl_sparse_destroy(self._handle)
                self._handle = ctypes.c_void_p()
        except Exception:  # interpreter shutdown: the library may be gone
            pass
