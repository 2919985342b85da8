"""volphys: Python bindings (ctypes) over the VolPhys C ABI in libvolphys.so.

The library is found through $VOLPHYS_LIBRARY, a libvolphys.so* bundled beside the package,
the prefix CMake installed the package into, or the system library path (volphys/_library.py). Import fails with ImportError if the library's struct layouts differ
from these bindings. Every failing call raises a VolPhysError subclass carrying the status
and the library's message. Arrays come back as numpy arrays when numpy is importable.
"""
import ctypes

from . import _types as _T
from ._api import call as _call, lib as _lib
from ._arrays import HAVE_NUMPY
from ._types import (ActorKind, Advection, BodyType, ContactEventType, Device, DomainSide, FluidField, FluidKind, HitKind,
                     LogLevel, Phase, QueryKind, SelfCollision, ShapeType, Status, SurfaceMesher)
from .queries import Hit
from .box_mesh import box_tet_mesh
from .collider import BodyProperties, Collider, Transform
from ._handle import CollisionFilter
from .deformable import Deformable, Material, MeshQuality
from .fluid import Fluid, FluidParameters
from .fluid_sources import BoxRegion, Emitter, SphereRegion
from .log import set_log_callback
from .errors import (BusyError, DivergedError, InternalError, NotConvergedError, PhaseFailedError, InvalidArgumentError, InvalidIdError, IoError,
                     OutOfMemoryError, ParseError, UnsupportedError, VersionMismatchError, VolPhysError)
from .shapes import Box, Capsule, ConvexHull, Cylinder, Plane, Shape, Sphere, TriangleMesh
from .stats import ActorStats, PhaseStats, StepStats
from .world import ContactEvent, World

__version__ = "%d.%d.%d" % (_T.VP_VERSION_MAJOR, _T.VP_VERSION_MINOR, _T.VP_VERSION_PATCH)


def library_version():
    """(major, minor, patch) of the loaded library."""
    v = _lib.vpGetVersion()
    return (v.major, v.minor, v.patch)


def library_path():
    return _lib._name


def build_info():
    """dict with cuda_compiled, cuda_device_count, hardware_threads."""
    b = _T.vpBuildInfo()
    _call("vpGetBuildInfo", ctypes.byref(b))
    return {"cuda_compiled": bool(b.cudaCompiled), "cuda_device_count": b.cudaDeviceCount,
            "hardware_threads": b.hardwareThreads}


def device_info(device=0):
    """dict with name, total_memory_bytes, compute_capability (major, minor) and
    multiprocessors of CUDA device `device` (0 .. build_info()['cuda_device_count'] - 1)."""
    d = _lib.vpDefaultDeviceInfo()
    _call("vpGetDeviceInfo", int(device), ctypes.byref(d))
    return {"name": d.name.decode(), "total_memory_bytes": d.totalMemoryBytes,
            "compute_capability": (d.computeCapabilityMajor, d.computeCapabilityMinor),
            "multiprocessors": d.multiprocessorCount}


def status_name(status):
    return _lib.vpStatusName(int(status)).decode()


__all__ = [
    "World", "Collider", "Deformable", "Fluid", "BoxRegion", "SphereRegion", "Emitter", "Transform", "Shape",
    "Sphere", "Box", "Capsule", "Cylinder", "Plane", "ConvexHull", "TriangleMesh", "StepStats", "ActorStats",
    "PhaseStats", "Status", "BodyType", "ShapeType", "ActorKind", "Phase", "LogLevel", "FluidKind", "Advection",
    "SurfaceMesher", "Device", "DomainSide", "FluidField", "VolPhysError", "InvalidArgumentError", "InvalidIdError", "OutOfMemoryError",
    "UnsupportedError", "IoError", "ParseError", "BusyError", "DivergedError", "VersionMismatchError",
    "InternalError", "NotConvergedError", "PhaseFailedError", "library_version", "library_path", "build_info", "device_info", "status_name", "HAVE_NUMPY",
    "set_log_callback", "box_tet_mesh", "MeshQuality",
]
