"""MKL PARDISO for symmetric positive definite systems, called phase by phase.

pypardiso (our MKL loader) hands PARDISO a scalar CSR matrix, runs analysis and
factorisation with MKL's default parameters, copies or hashes the matrix to
recognise it again and converts the index arrays to 1-based on every solve.
Here (the figures on the default solid ring: ``docs/fe_accuracy.md#measured-behind-the-codes-choices``):

- the matrix goes in as 3 x 3 node blocks (``iparm[36]``): the fill-reducing
  ordering works on the node graph, 9 times smaller, and the analysis is faster;
- the two-level parallel factorisation (``iparm[23] = 1``) uses both cores on
  block input, where the default left one idle;
- the factorisation may be single precision (``iparm[27]``, float32 values), faster
  than double; ``solvers`` then refines the solution in double precision
  against the double matrix, to the residual of a double factorisation;
- one factorisation serves any number of right-hand sides; indices are 0-based.

The matrix is the upper triangle (upper block triangle, diagonal blocks whole)
with sorted column indices (PARDISO's ``mtype = 2``).
"""
from __future__ import annotations

import ctypes
import functools
import glob
import sys

import numpy as np

SPD = 2
#: MKL iparm entries (0-based)
_USER, _ORDERING, _PIVOT, _PARALLEL, _PRECISION, _ZERO_BASED, _BLOCK = 0, 1, 9, 23, 27, 34, 36
_PEAK_ANALYSIS, _PEAK_FACTOR, _FACTOR_MEMORY = 14, 15, 16

#: PARDISO's error codes (MKL reference)
ERRORS = {-1: "input inconsistent", -2: "not enough memory", -3: "reordering problem",
          -4: "zero pivot, numerical factorization or iterative refinement problem",
          -5: "unclassified (internal) error", -6: "reordering failed",
          -7: "diagonal matrix is singular", -8: "32-bit integer overflow problem",
          -9: "not enough memory for OOC", -10: "error opening OOC files",
          -11: "read/write error with OOC files", -12: "pardiso_64 called from 32-bit library"}


class PardisoError(ArithmeticError):
    """PARDISO returned an error code; ``code`` holds it."""

    def __init__(self, code: int, phase: int):
        self.code = code
        super().__init__(f"PARDISO phase {phase} failed with error {code}: "
                         f"{ERRORS.get(code, 'unknown')}")


@functools.cache
def mkl_runtime() -> ctypes.CDLL:
    """``libmkl_rt`` beside the interpreter (or the base interpreter of a virtual
    environment) where pip puts it, else wherever pypardiso's loader finds it (a recursive
    search, slow)."""
    # a virtual environment's prefix holds no libraries: look beside the base interpreter too
    found = [p for prefix in dict.fromkeys((sys.prefix, sys.base_prefix))
             for p in sorted(glob.glob(f"{prefix}/lib/libmkl_rt.so*"), key=len)]
    for path in found:
        try:
            return ctypes.CDLL(path)
        except OSError:
            continue
    from pypardiso.pardiso_wrapper import PyPardisoSolver

    return PyPardisoSolver().libmkl


@functools.cache
def mkl_library():
    """MKL's ``pardiso`` entry point (in ``mkl_runtime``)."""
    library = mkl_runtime()
    function = library.pardiso
    i32 = ctypes.POINTER(ctypes.c_int32)
    function.argtypes = [ctypes.POINTER(ctypes.c_int64), i32, i32, i32, i32, i32,
                         ctypes.c_void_p, i32, i32, i32, i32, i32, i32,
                         ctypes.c_void_p, ctypes.c_void_p, i32]
    function.restype = None
    return function


class Pardiso:
    """Cholesky factorisation of an SPD matrix given by its upper triangle.

    Parameters
    ----------
    indptr, indices, data
        The upper triangle (with the diagonal) in CSR, or with ``block`` > 1 in
        block CSR: ``data`` (blocks, block, block) holds the upper block triangle,
        diagonal blocks whole; column indices sorted within each row.
    block : int
        Block size (1: CSR).
    single : bool
        Factorise in single precision (``data`` rounded to float32); ``solve`` is then
        single precision too and its result needs refining (``solvers``).
    """

    def __init__(self, indptr, indices, data, block: int = 1, single: bool = False):
        self._pardiso = mkl_library()
        self.rows = len(indptr) - 1
        self.n = self.rows * block
        self.dtype = np.float32 if single else np.float64
        self._pt = np.zeros(64, dtype=np.int64)
        self.iparm = np.zeros(64, dtype=np.int32)
        self.iparm[_USER] = 1  # our values; zero means MKL's default
        self.iparm[_ORDERING] = 2  # METIS nested dissection (serial: repeatable)
        self.iparm[_PIVOT] = 8  # perturbation 1e-8, MKL's default for symmetric types
        self.iparm[_PARALLEL] = 1 if block > 1 else 0
        self.iparm[_PRECISION] = 1 if single else 0
        self.iparm[_ZERO_BASED] = 1
        self.iparm[_BLOCK] = block if block > 1 else 0
        self._indptr = np.ascontiguousarray(indptr, dtype=np.int32)
        self._indices = np.ascontiguousarray(indices, dtype=np.int32)
        self._data = np.ascontiguousarray(data, dtype=self.dtype)
        if len(self._data) != len(self._indices) or self._indptr[-1] != len(self._indices):
            raise ValueError(f"PARDISO: {len(self._indices)} column indices, {len(self._data)} "
                             f"values, indptr ends at {self._indptr[-1]}")
        try:
            self._call(11)  # analysis: ordering and symbolic factorisation
            self._call(22)  # numeric factorisation
        except PardisoError:  # the caller never gets this object: release what phase 11 took
            self.free()
            raise

    def solve(self, f: np.ndarray) -> np.ndarray:
        """``K u = f`` for f (n,) or (n, k), in the factorisation's precision."""
        f = np.asarray(f)
        columns = np.asfortranarray(f.reshape(self.n, -1), dtype=self.dtype)
        u = np.zeros_like(columns)
        self._call(33, columns, u)
        return u.reshape(f.shape)

    @property
    def memory_bytes(self) -> int:
        """Peak memory PARDISO reported for analysis and factorisation [byte]."""
        peak = max(int(self.iparm[_PEAK_ANALYSIS]),
                   int(self.iparm[_PEAK_FACTOR]) + int(self.iparm[_FACTOR_MEMORY]))
        return 1024 * peak

    def free(self) -> None:
        """Release PARDISO's memory (the object cannot solve afterwards)."""
        if self._pt.any():
            self._call(-1)
            self._pt[:] = 0

    def __del__(self):
        try:
            self.free()
        except Exception:  # interpreter shutdown: the library may be gone
            pass

    def _call(self, phase: int, f=None, u=None) -> None:
        i32 = ctypes.c_int32
        error = i32(0)
        columns = 1 if f is None else f.shape[1]
        dummy = np.zeros(1, dtype=self.dtype)
        self._pardiso(
            self._pt.ctypes.data_as(ctypes.POINTER(ctypes.c_int64)), ctypes.byref(i32(1)),
            ctypes.byref(i32(1)), ctypes.byref(i32(SPD)), ctypes.byref(i32(phase)),
            ctypes.byref(i32(self.rows)), self._data.ctypes.data,
            self._indptr.ctypes.data_as(ctypes.POINTER(i32)),
            self._indices.ctypes.data_as(ctypes.POINTER(i32)),
            None, ctypes.byref(i32(columns)), self.iparm.ctypes.data_as(ctypes.POINTER(i32)),
            ctypes.byref(i32(0)), (dummy if f is None else f).ctypes.data,
            (dummy if u is None else u).ctypes.data, ctypes.byref(error))
        if error.value != 0:
            raise PardisoError(error.value, phase)
