"""Versioned settings structs read and changed by name: vpBodyProperties, vpDeformableMaterial,
vpFluidParameters. Each maps to a namedtuple with snake_case fields in the struct's order."""
import ctypes
import re

from ._api import call


def snake(name):
    return re.sub(r"(?<!^)(?=[A-Z])", "_", name).lower()


def read(function, handle_id, ctype, tuple_type):
    s = ctype(structSize=ctypes.sizeof(ctype))
    call(function, handle_id, ctypes.byref(s))
    return tuple_type(*(_plain(getattr(s, name)) for name, _ in ctype._fields_[1:]))


def _plain(value):
    """A ctypes array field (a fluid's sides) as a tuple, not a view into the struct."""
    return tuple(value) if isinstance(value, ctypes.Array) else value


def change(get_function, set_function, handle_id, ctype, tuple_type, changes):
    """Reads the current values, replaces those named in `changes`, writes them back (the library
    validates them all; on failure nothing changes)."""
    current = read(get_function, handle_id, ctype, tuple_type)._asdict()
    unknown = set(changes) - set(current)
    if unknown:
        raise TypeError("unknown field(s) %s; known: %s" % (", ".join(sorted(unknown)), ", ".join(tuple_type._fields)))
    current.update(changes)
    s = ctype(ctypes.sizeof(ctype), *(current[snake(name)] for name, _ in ctype._fields_[1:]))
    call(set_function, handle_id, ctypes.byref(s))
