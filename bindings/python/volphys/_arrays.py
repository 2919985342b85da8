"""Conversions between Python data and the flat C arrays of the ABI.

Inputs: anything numpy can turn into an (n, 3) float32 / (n, k) int32 array, or, without
numpy, (nested) sequences. Each input helper returns (pointer, rows, keepalive): the caller
must hold `keepalive` until the C call returns, since the pointer aims into it.
Outputs: numpy arrays when numpy is importable, else lists of tuples.
"""
import ctypes
from ctypes import POINTER, c_float, c_int32

try:
    import numpy as np
except ImportError:  # numpy is optional: plain lists then
    np = None

HAVE_NUMPY = np is not None


def _flatten(seq):
    out = []
    for item in seq:
        if isinstance(item, (list, tuple)):
            out.extend(item)
        else:
            out.append(item)
    return out


def _input(data, width, ctype, np_dtype, what):
    if data is None:
        return None, 0, None
    if HAVE_NUMPY:
        src = np.asarray(data)
        if np_dtype is np.int32 and src.size:
            # Index arrays: refuse what a cast would silently change (1.5 -> 1, 2**32 -> 0).
            if src.dtype.kind not in "iu":
                raise ValueError("%s: expected integer indices, got dtype %s" % (what, src.dtype))
            if src.min() < np.iinfo(np.int32).min or src.max() > np.iinfo(np.int32).max:
                raise ValueError("%s: index out of int32 range" % what)
        a = np.ascontiguousarray(src, dtype=np_dtype)
        if a.ndim == 1:
            if a.size % width:
                raise ValueError("%s: %d values is not a multiple of %d" % (what, a.size, width))
            a = a.reshape(-1, width)
        if a.ndim != 2 or a.shape[1] != width:
            raise ValueError("%s: expected shape (n, %d), got %s" % (what, width, a.shape))
        return a.ctypes.data_as(POINTER(ctype)), a.shape[0], a
    flat = _flatten(data)
    if len(flat) % width:
        raise ValueError("%s: %d values is not a multiple of %d" % (what, len(flat), width))
    buf = (ctype * len(flat))(*flat)
    return ctypes.cast(buf, POINTER(ctype)), len(flat) // width, buf


def floats3(data, what):
    """(n, 3) float32 input -> (pointer, n, keepalive)."""
    return _input(data, 3, c_float, np.float32 if HAVE_NUMPY else None, what)


def ints(data, width, what):
    """(n, width) int32 input -> (pointer, n, keepalive)."""
    return _input(data, width, c_int32, np.int32 if HAVE_NUMPY else None, what)


def index_list(nodes, what):
    """A single index or a sequence of them -> (pointer, count, keepalive)."""
    if isinstance(nodes, int):
        nodes = [nodes]
    return ints(nodes if not HAVE_NUMPY else np.asarray(nodes).reshape(-1, 1), 1, what)


class OutBuffer:
    """A host buffer of rows x width elements that C writes into."""

    def __init__(self, rows, width, ctype):
        self.rows, self.width, self.ctype = rows, width, ctype
        if HAVE_NUMPY:
            self.array = np.zeros((rows, width), dtype=np.float32 if ctype is c_float else np.int32)
            self.ptr = self.array.ctypes.data_as(POINTER(ctype))
        else:
            self.array = (ctype * max(rows * width, 1))()
            self.ptr = ctypes.cast(self.array, POINTER(ctype))

    def result(self):
        if HAVE_NUMPY:
            return self.array
        a, w = self.array, self.width
        return [tuple(a[i * w:(i + 1) * w]) for i in range(self.rows)]


def grid_result(out, cells_shape):
    """An OutBuffer holding one row per grid cell (x fastest) as a numpy array shaped
    cells_shape (+ (width,) when width > 1); without numpy, the flat C order (floats for
    width 1, tuples otherwise)."""
    if HAVE_NUMPY:
        return out.array.reshape(tuple(cells_shape) + ((out.width,) if out.width > 1 else ()))
    rows = out.result()
    return [r[0] for r in rows] if out.width == 1 else rows


def vec3(v, what="vector"):
    from ._types import vpVec3
    x, y, z = (float(c) for c in v)
    return vpVec3(x, y, z)


def quat(q):
    from ._types import vpQuat
    x, y, z, w = (float(c) for c in q)
    return vpQuat(x, y, z, w)
