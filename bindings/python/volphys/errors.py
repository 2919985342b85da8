"""Exceptions: one per vpStatus, all deriving from VolPhysError."""
from ._types import Status


class VolPhysError(Exception):
    """A VolPhys call returned a status other than Ok. `status` is the volphys.Status,
    `message` the library's vpGetLastError() text (it names the bad argument or field)."""

    def __init__(self, status, message, call=None):
        self.status = Status(status)
        self.message = message
        self.call = call
        where = "%s: " % call if call else ""
        super().__init__("%s%s (%s)" % (where, message, self.status.name))


class InvalidArgumentError(VolPhysError, ValueError):
    pass


class InvalidIdError(VolPhysError):
    pass


class OutOfMemoryError(VolPhysError, MemoryError):
    pass


class UnsupportedError(VolPhysError):
    pass


class IoError(VolPhysError, OSError):
    pass


class ParseError(VolPhysError):
    pass


class BusyError(VolPhysError):
    pass


class DivergedError(VolPhysError):
    pass


class VersionMismatchError(VolPhysError):
    pass


class InternalError(VolPhysError):
    pass


class PhaseFailedError(VolPhysError):
    """World.step: a phase of some actor failed; the rest of the step ran (actor_stats say which)."""


class NotConvergedError(VolPhysError):
    """An iterative request (Deformable.solve_static) stopped above its tolerance; nothing changed."""


_BY_STATUS = {
    Status.InvalidArgument: InvalidArgumentError,
    Status.InvalidId: InvalidIdError,
    Status.OutOfMemory: OutOfMemoryError,
    Status.Unsupported: UnsupportedError,
    Status.IoError: IoError,
    Status.ParseError: ParseError,
    Status.Busy: BusyError,
    Status.Diverged: DivergedError,
    Status.VersionMismatch: VersionMismatchError,
    Status.Internal: InternalError,
    Status.PhaseFailed: PhaseFailedError,
    Status.NotConverged: NotConvergedError,
}


def error_for(status, message, call=None):
    """The exception instance for a failing status (VolPhysError for unknown codes)."""
    try:
        st = Status(status)
    except ValueError:
        # A newer library may add statuses; keep the number rather than failing here.
        e = VolPhysError.__new__(VolPhysError)
        Exception.__init__(e, "%s: %s (status %d)" % (call, message, status))
        e.status, e.message, e.call = status, message, call
        return e
    return _BY_STATUS.get(st, VolPhysError)(st, message, call)
