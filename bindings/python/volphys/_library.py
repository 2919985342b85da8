"""Finds and loads libvolphys.so.

Order: $VOLPHYS_LIBRARY (a path), a libvolphys.so next to this package, then the system
library path. The first that loads wins; if none does, the error lists every place tried so
a user can see which one they meant to hit.
"""
import ctypes
import ctypes.util
import os

ENV_VAR = "VOLPHYS_LIBRARY"


def _candidates():
    """Yields (description, path-or-name) in lookup order."""
    env = os.environ.get(ENV_VAR)
    if env:
        yield ("$%s" % ENV_VAR, env)
    here = os.path.dirname(os.path.abspath(__file__))
    for d in (here, os.path.dirname(here)):
        yield ("beside the package", os.path.join(d, "libvolphys.so"))
    found = ctypes.util.find_library("volphys")
    if found:
        yield ("ctypes.util.find_library('volphys')", found)
    yield ("system library path", "libvolphys.so.0")
    yield ("system library path", "libvolphys.so")


def load_library():
    tried = []
    env = os.environ.get(ENV_VAR)
    for where, path in _candidates():
        # A path that does not exist is skipped without trying, but still reported.
        if os.sep in path and not os.path.exists(path):
            tried.append("%s: %s (no such file)" % (where, path))
            # An explicit $VOLPHYS_LIBRARY that is wrong is a user error: do not silently
            # fall back to some other copy of the library.
            if where.startswith("$"):
                break
            continue
        try:
            return ctypes.CDLL(path)
        except OSError as e:
            tried.append("%s: %s (%s)" % (where, path, e))
            if where.startswith("$") and env:
                break
    raise ImportError("volphys: cannot load libvolphys.so; tried:\n  " + "\n  ".join(tried))
