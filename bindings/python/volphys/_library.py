"""Finds and loads libvolphys.so.

Order: $VOLPHYS_LIBRARY (a path); a libvolphys.so* bundled in the package's folder (or beside
it); the library that CMake's install put beside the package (the install writes its path,
relative to the package, into _installed_library.py); then the system loader's path. The first that loads wins; if none does, the error lists every
place tried so a user can see which one they meant to hit.
"""
import ctypes
import ctypes.util
import glob
import os

ENV_VAR = "VOLPHYS_LIBRARY"


def _bundled(directory):
    # The unversioned name first, then the soname, then any fuller version.
    names = sorted(glob.glob(os.path.join(directory, "libvolphys.so*")), key=lambda p: (len(p), p))
    return names or [os.path.join(directory, "libvolphys.so")]


def _installed_library(package_dir):
    # Only a package installed by cmake --install has this module.
    try:
        from . import _installed_library
    except ImportError:
        return []
    return [os.path.normpath(os.path.join(package_dir, _installed_library.PATH))]


def _candidates():
    """Yields (description, path-or-name) in lookup order."""
    env = os.environ.get(ENV_VAR)
    if env:
        yield ("$%s" % ENV_VAR, env)
    here = os.path.dirname(os.path.abspath(__file__))
    for d in (here, os.path.dirname(here)):
        for path in _bundled(d):
            yield ("beside the package", path)
    for path in _installed_library(here):
        yield ("installed with the package", path)
    found = ctypes.util.find_library("volphys")
    if found:
        yield ("ctypes.util.find_library('volphys')", found)
    yield ("system library path", "libvolphys.so.0")
    yield ("system library path", "libvolphys.so")


def load_library():
    tried = []
    for where, path in _candidates():
        explicit = where.startswith("$")
        # A path that does not exist is skipped without trying, but still reported.
        if os.sep in path and not os.path.exists(path):
            tried.append("%s: %s (no such file)" % (where, path))
            # An explicit $VOLPHYS_LIBRARY that is wrong is a user error: do not silently
            # fall back to some other copy of the library.
            if explicit:
                break
            continue
        try:
            return ctypes.CDLL(path)
        except OSError as e:
            tried.append("%s: %s (%s)" % (where, path, e))
            if explicit:
                break
    raise ImportError("volphys: cannot load libvolphys.so; tried:\n  " + "\n  ".join(tried))
