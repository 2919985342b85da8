"""Routing the library's log messages to a Python callable (vpSetLogCallback)."""
import sys

from . import _types as T
from ._api import call

# The ctypes thunk must outlive every call that may log: the library keeps the raw pointer.
_current_thunk = None


def set_log_callback(fn, min_level=T.LogLevel.Warning):
    """fn(level: LogLevel, message: str) receives messages at min_level and above; None
    restores the default (warnings and errors to stderr). Process-wide. The library may call
    it from its worker threads; ctypes takes the GIL for it. An exception inside fn is
    printed and swallowed: it cannot unwind through C."""
    global _current_thunk
    if fn is None:
        call("vpSetLogCallback", T.vpLogFn(), None, int(min_level))
        _current_thunk = None
        return

    def thunk(level, message, _context):
        try:
            fn(T.LogLevel(level), message.decode("utf-8", "replace") if message else "")
        except Exception as e:  # noqa: BLE001 - see the docstring
            print("volphys: log callback raised %r" % (e,), file=sys.stderr)

    new = T.vpLogFn(thunk)
    call("vpSetLogCallback", new, None, int(min_level))
    _current_thunk = new  # swapped only after the library stopped using the old one
