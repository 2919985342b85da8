"""ActorHandle: what Collider, Deformable and Fluid share. It holds only the id: operations on a
destroyed object (or one of a destroyed world) raise InvalidIdError from the library, they
never crash."""
from collections import namedtuple
import ctypes

from . import _arrays
from . import _types as T
from ._api import call, lib

# vpCollisionFilter: two objects meet when each one's category shares a bit with the other's
# mask. Default CollisionFilter(1, 0xFFFFFFFF): everything meets everything.
CollisionFilter = namedtuple("CollisionFilter", "category mask")


def c_filter(value):
    """CollisionFilter or (category, mask) -> vpCollisionFilter."""
    category, mask = value
    return T.vpCollisionFilter(int(category), int(mask))


class ActorHandle:
    # Set by subclasses: the C functions that check and destroy this kind of id, and that get
    # and set its collision filter.
    _is_valid_function = None
    _destroy_function = None
    _name_function = None
    _get_filter_function = None
    _set_filter_function = None

    def __init__(self, world, handle_id):
        self.world = world
        self._id = handle_id

    def __repr__(self):
        return "%s(index1=%d, generation=%d)" % (type(self).__name__, self._id.index1, self._id.generation)

    def __eq__(self, other):
        return type(other) is type(self) and bytes(self._id) == bytes(other._id)

    def __hash__(self):
        return hash(bytes(self._id))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.destroy()

    @property
    def id(self):
        return self._id

    @property
    def is_valid(self):
        return getattr(lib, self._is_valid_function)(self._id) == 0

    def destroy(self):
        call(self._destroy_function, self._id)

    @property
    def name(self):
        """The name a scene file gave it ("" when none)."""
        length = ctypes.c_int32()
        call(self._name_function, self._id, None, 0, ctypes.byref(length))
        buffer = ctypes.create_string_buffer(length.value)
        call(self._name_function, self._id, buffer, length.value, ctypes.byref(length))
        return buffer.value.decode("utf-8", "replace")

    @property
    def collision_filter(self):
        """CollisionFilter(category, mask); set it with a CollisionFilter or a (category, mask)
        pair. A change takes effect from the next step."""
        f = T.vpCollisionFilter()
        call(self._get_filter_function, self._id, ctypes.byref(f))
        return CollisionFilter(f.categoryBits, f.maskBits)

    @collision_filter.setter
    def collision_filter(self, value):
        call(self._set_filter_function, self._id, c_filter(value))

    def _read_mesh(self, size_function, mesh_function):
        """A mesh through the ABI's size + fill pair: (positions (v,3) float32, normals (v,3)
        float32, triangles (t,3) int32)."""
        nv, nt = ctypes.c_int32(), ctypes.c_int32()
        call(size_function, self._id, ctypes.byref(nv), ctypes.byref(nt))
        pos = _arrays.OutBuffer(nv.value, 3, ctypes.c_float)
        nrm = _arrays.OutBuffer(nv.value, 3, ctypes.c_float)
        tri = _arrays.OutBuffer(nt.value, 3, ctypes.c_int32)
        call(mesh_function, self._id, pos.ptr, nrm.ptr, nv.value, tri.ptr, nt.value)
        return pos.result(), nrm.result(), tri.result()
