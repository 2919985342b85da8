"""box_tet_mesh: the library's box mesher (vpBoxTetMesh), the one scene files use for their
"box" deformables, for building a deformable from arrays."""
import ctypes
from ctypes import c_float, c_int32
import operator

from . import _arrays
from ._api import call

_INT32_MIN, _INT32_MAX = -2 ** 31, 2 ** 31 - 1


def _cells(cells):
    # Integers only: a silent int(1.5) or a ctypes wrap-around of 2**32 would mesh another box.
    values = list(cells)
    if len(values) != 3:
        raise ValueError("cells: expected 3 integers (cx, cy, cz), got %d values" % len(values))
    out = (c_int32 * 3)()
    for k, value in enumerate(values):
        try:
            n = operator.index(value)
        except TypeError:
            raise ValueError("cells[%d] = %r: expected an integer" % (k, value)) from None
        if not _INT32_MIN <= n <= _INT32_MAX:
            raise ValueError("cells[%d] = %d: out of int32 range" % (k, n))
        out[k] = n
    return out


def box_tet_mesh(size, cells, min_corner=(0.0, 0.0, 0.0)):
    """A tet mesh of the box [min_corner, min_corner + size]: cells (cx, cy, cz) cubes, each
    split into 6 positively oriented tets. Returns (vertices, tets): (n, 3) float32 in lattice
    order (x fastest) and (6 cx cy cz, 4) int32 numpy arrays (lists of tuples without numpy),
    ready for World.create_deformable(vertices=..., tets=...). Each count in [1, 512], at most
    2**21 cells; a value out of range raises InvalidArgumentError naming it, cells that are not
    int32 integers ValueError."""
    c, extent, corner = _cells(cells), _arrays.vec3(size), _arrays.vec3(min_corner)
    vertex_count, tet_count = c_int32(), c_int32()
    call("vpBoxTetMesh", extent, c, corner, None, 0, None, 0, ctypes.byref(vertex_count), ctypes.byref(tet_count))
    vertices = _arrays.OutBuffer(vertex_count.value, 3, c_float)
    tets = _arrays.OutBuffer(tet_count.value, 4, c_int32)
    call("vpBoxTetMesh", extent, c, corner, vertices.ptr, vertex_count.value, tets.ptr, tet_count.value, None, None)
    return vertices.result(), tets.result()
