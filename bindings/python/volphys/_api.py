"""Function prototypes for every call in volphys.h, the status check, and the import-time
check that these ctypes structs have the sizes the loaded library was built with."""
import ctypes
from ctypes import POINTER, c_char_p, c_float, c_int, c_int32, c_int64, c_size_t, c_uint32, c_void_p

from . import _types as T
from ._library import load_library
from .errors import error_for

lib = load_library()

_S = T.c_enum  # vpStatus
_P = POINTER

# name: (restype, argtypes). Status-returning calls are wrapped by check() at the call site.
_PROTOTYPES = {
    "vpGetVersion": (T.vpVersion, []),
    "vpGetLastError": (c_char_p, []),
    "vpStatusName": (c_char_p, [_S]),
    "vpCheckHeaderVersion": (_S, [c_uint32, c_uint32]),
    "vpSetAllocator": (_S, [T.vpAllocFn, T.vpFreeFn, c_void_p]),
    "vpSetLogCallback": (_S, [T.vpLogFn, c_void_p, T.c_enum]),
    "vpWorldIdIsNull": (c_int, [T.vpWorldId]),
    "vpColliderIdIsNull": (c_int, [T.vpColliderId]),
    "vpDeformableIdIsNull": (c_int, [T.vpDeformableId]),
    "vpFluidIdIsNull": (c_int, [T.vpFluidId]),
    "vpDefaultWorldDef": (T.vpWorldDef, []),
    "vpWorldCreate": (_S, [_P(T.vpWorldDef), _P(T.vpWorldId)]),
    "vpWorldDestroy": (_S, [T.vpWorldId]),
    "vpWorldIsValid": (_S, [T.vpWorldId]),
    "vpWorldSetGravity": (_S, [T.vpWorldId, T.vpVec3]),
    "vpWorldGetGravity": (_S, [T.vpWorldId, _P(T.vpVec3)]),
    "vpWorldSetFrameBudget": (_S, [T.vpWorldId, c_float]),
    "vpWorldStep": (_S, [T.vpWorldId, c_float]),
    "vpWorldLoadScene": (_S, [T.vpWorldId, c_char_p]),
    "vpDefaultStepStats": (T.vpStepStats, []),
    "vpDefaultActorStats": (T.vpActorStats, []),
    "vpWorldGetStepStats": (_S, [T.vpWorldId, _P(T.vpStepStats)]),
    "vpWorldGetActorStats": (_S, [T.vpWorldId, c_int32, _P(T.vpActorStats)]),
    "vpDefaultShapeDef": (T.vpShapeDef, []),
    "vpDefaultColliderDef": (T.vpColliderDef, []),
    "vpColliderCreate": (_S, [T.vpWorldId, _P(T.vpColliderDef), _P(T.vpColliderId)]),
    "vpColliderDestroy": (_S, [T.vpColliderId]),
    "vpColliderIsValid": (_S, [T.vpColliderId]),
    "vpColliderGetPose": (_S, [T.vpColliderId, _P(T.vpTransform)]),
    "vpColliderSetPose": (_S, [T.vpColliderId, _P(T.vpTransform)]),
    "vpColliderGetVelocity": (_S, [T.vpColliderId, _P(T.vpVec3), _P(T.vpVec3)]),
    "vpColliderSetVelocity": (_S, [T.vpColliderId, T.vpVec3, T.vpVec3]),
    "vpColliderSetKinematicTarget": (_S, [T.vpColliderId, _P(T.vpTransform)]),
    "vpColliderApplyForce": (_S, [T.vpColliderId, T.vpVec3, _P(T.vpVec3)]),
    "vpColliderApplyTorque": (_S, [T.vpColliderId, T.vpVec3]),
    "vpColliderApplyImpulse": (_S, [T.vpColliderId, T.vpVec3, _P(T.vpVec3)]),
    "vpColliderApplyAngularImpulse": (_S, [T.vpColliderId, T.vpVec3]),
    "vpColliderGetProperties": (_S, [T.vpColliderId, _P(T.vpBodyProperties)]),
    "vpColliderSetProperties": (_S, [T.vpColliderId, _P(T.vpBodyProperties)]),
    "vpColliderIsSleeping": (_S, [T.vpColliderId, _P(c_int32)]),
    "vpColliderSetSleeping": (_S, [T.vpColliderId, c_int32]),
    "vpColliderGetCollisionFilter": (_S, [T.vpColliderId, _P(T.vpCollisionFilter)]),
    "vpColliderSetCollisionFilter": (_S, [T.vpColliderId, T.vpCollisionFilter]),
    "vpDeformableGetCollisionFilter": (_S, [T.vpDeformableId, _P(T.vpCollisionFilter)]),
    "vpDeformableSetCollisionFilter": (_S, [T.vpDeformableId, T.vpCollisionFilter]),
    "vpFluidGetCollisionFilter": (_S, [T.vpFluidId, _P(T.vpCollisionFilter)]),
    "vpFluidSetCollisionFilter": (_S, [T.vpFluidId, T.vpCollisionFilter]),
    "vpColliderGetBodyType": (_S, [T.vpColliderId, _P(T.c_enum)]),
    "vpColliderGetUserData": (_S, [T.vpColliderId, _P(c_void_p)]),
    "vpWorldGetColliderCount": (_S, [T.vpWorldId, _P(c_int32)]),
    "vpWorldGetColliders": (_S, [T.vpWorldId, _P(T.vpColliderId), c_int32, _P(c_int32)]),
    "vpColliderGetShapeMeshSize": (_S, [T.vpColliderId, _P(c_int32), _P(c_int32)]),
    "vpColliderGetShapeMesh": (_S, [T.vpColliderId, _P(c_float), _P(c_float), c_int32, _P(c_int32), c_int32]),
    "vpWorldFindCollider": (_S, [T.vpWorldId, c_char_p, _P(T.vpColliderId)]),
    "vpDefaultDeformableDef": (T.vpDeformableDef, []),
    "vpDeformableCreate": (_S, [T.vpWorldId, _P(T.vpDeformableDef), _P(T.vpDeformableId)]),
    "vpDeformableDestroy": (_S, [T.vpDeformableId]),
    "vpDeformableIsValid": (_S, [T.vpDeformableId]),
    "vpDeformableGetNodeCount": (_S, [T.vpDeformableId, _P(c_int32)]),
    "vpDeformableGetPositions": (_S, [T.vpDeformableId, _P(c_float), c_int32]),
    "vpDeformableGetVelocities": (_S, [T.vpDeformableId, _P(c_float), c_int32]),
    "vpDeformableSetVelocities": (_S, [T.vpDeformableId, _P(c_float), c_int32]),
    "vpDeformableApplyForce": (_S, [T.vpDeformableId, c_int32, T.vpVec3]),
    "vpDeformableApplyImpulse": (_S, [T.vpDeformableId, c_int32, T.vpVec3]),
    "vpDeformablePin": (_S, [T.vpDeformableId, _P(c_int32), c_int32]),
    "vpDeformableUnpin": (_S, [T.vpDeformableId, _P(c_int32), c_int32]),
    "vpDeformableAttach": (_S, [T.vpDeformableId, _P(c_int32), c_int32, T.vpColliderId]),
    "vpDeformableGetRenderMeshSize": (_S, [T.vpDeformableId, _P(c_int32), _P(c_int32)]),
    "vpDeformableGetRenderMesh": (_S, [T.vpDeformableId, _P(c_float), _P(c_float), c_int32, _P(c_int32), c_int32]),
    "vpDeformableGetStats": (_S, [T.vpDeformableId, _P(T.vpActorStats)]),
    "vpDeformableGetMeshQuality": (_S, [T.vpDeformableId, _P(c_float), _P(c_float), _P(c_float), _P(c_float)]),
    "vpDeformableSolveStatic": (_S, [T.vpDeformableId, c_int32, c_float, _P(c_int32), _P(c_float)]),
    "vpColliderGetName": (_S, [T.vpColliderId, c_char_p, c_int32, _P(c_int32)]),
    "vpDeformableGetName": (_S, [T.vpDeformableId, c_char_p, c_int32, _P(c_int32)]),
    "vpFluidGetName": (_S, [T.vpFluidId, c_char_p, c_int32, _P(c_int32)]),
    "vpWorldFindDeformable": (_S, [T.vpWorldId, c_char_p, _P(T.vpDeformableId)]),
    "vpBoxTetMesh": (_S, [T.vpVec3, _P(c_int32), T.vpVec3, _P(c_float), c_int32, _P(c_int32), c_int32, _P(c_int32),
                          _P(c_int32)]),
    "vpWorldGetDeformableCount": (_S, [T.vpWorldId, _P(c_int32)]),
    "vpWorldGetDeformables": (_S, [T.vpWorldId, _P(T.vpDeformableId), c_int32, _P(c_int32)]),
    "vpDefaultFluidDef": (T.vpFluidDef, []),
    "vpFluidCreate": (_S, [T.vpWorldId, _P(T.vpFluidDef), _P(T.vpFluidId)]),
    "vpFluidDestroy": (_S, [T.vpFluidId]),
    "vpFluidIsValid": (_S, [T.vpFluidId]),
    "vpFluidGetResolution": (_S, [T.vpFluidId, _P(c_int32), _P(c_int32), _P(c_int32)]),
    "vpFluidGetKind": (_S, [T.vpFluidId, _P(T.c_enum)]),
    "vpFluidGetDomain": (_S, [T.vpFluidId, _P(T.vpVec3), _P(c_float)]),
    "vpFluidGetField": (_S, [T.vpFluidId, _S, _P(c_float), c_int64]),
    "vpFluidGetVelocityGrid": (_S, [T.vpFluidId, _P(c_float), c_int64]),
    "vpFluidSampleVelocity": (_S, [T.vpFluidId, _P(T.vpVec3), c_int32, _P(T.vpVec3)]),
    "vpFluidGetSurfaceMeshSize": (_S, [T.vpFluidId, _P(c_int32), _P(c_int32)]),
    "vpFluidGetSurfaceMesh": (_S, [T.vpFluidId, _P(c_float), _P(c_float), c_int32, _P(c_int32), c_int32]),
    "vpFluidGetAmount": (_S, [T.vpFluidId, _P(c_float)]),
    "vpFluidGetStats": (_S, [T.vpFluidId, _P(T.vpActorStats)]),
    "vpWorldGetFluidCount": (_S, [T.vpWorldId, _P(c_int32)]),
    "vpWorldGetFluids": (_S, [T.vpWorldId, _P(T.vpFluidId), c_int32, _P(c_int32)]),
    "vpWorldFindFluid": (_S, [T.vpWorldId, c_char_p, _P(T.vpFluidId)]),
    "vpGetBuildInfo": (_S, [_P(T.vpBuildInfo)]),
    "vpDefaultDeviceInfo": (T.vpDeviceInfo, []),
    "vpGetDeviceInfo": (_S, [c_int32, _P(T.vpDeviceInfo)]),
    "vpDefaultQueryFilter": (T.vpQueryFilter, []),
    "vpWorldGetContactEvents": (_S, [T.vpWorldId, _P(T.vpContactEvent), c_int32, _P(c_int32)]),
    "vpWorldSaveState": (_S, [T.vpWorldId, c_void_p, c_size_t, _P(c_size_t)]),
    "vpWorldRestoreState": (_S, [T.vpWorldId, c_void_p, c_size_t]),
    "vpDeformableSetPositions": (_S, [T.vpDeformableId, _P(c_float), c_int32, c_int32]),
    "vpDeformableGetMaterial": (_S, [T.vpDeformableId, _P(T.vpDeformableMaterial)]),
    "vpDeformableSetMaterial": (_S, [T.vpDeformableId, _P(T.vpDeformableMaterial)]),
    "vpFluidGetParameters": (_S, [T.vpFluidId, _P(T.vpFluidParameters)]),
    "vpFluidSetParameters": (_S, [T.vpFluidId, _P(T.vpFluidParameters)]),
    "vpFluidGetEmitterCount": (_S, [T.vpFluidId, _P(c_int32)]),
    "vpFluidSetEmitter": (_S, [T.vpFluidId, c_int32, c_int32, c_float, T.vpVec3, c_float]),
    "vpWorldRaycast": (_S, [T.vpWorldId, _P(T.vpRay), _P(T.vpQueryFilter), _P(T.vpQueryHit), _P(c_int32)]),
    "vpWorldRaycastAll": (_S, [T.vpWorldId, _P(T.vpRay), _P(T.vpQueryFilter), _P(T.vpQueryHit), c_int32,
                               _P(c_int32)]),
    "vpWorldRaycastBatch": (_S, [T.vpWorldId, _P(T.vpRay), c_int32, _P(T.vpQueryFilter), _P(T.vpQueryHit)]),
    "vpWorldOverlapSphere": (_S, [T.vpWorldId, T.vpVec3, c_float, _P(T.vpQueryFilter), _P(T.vpQueryHit), c_int32,
                                  _P(c_int32)]),
    "vpWorldOverlapBox": (_S, [T.vpWorldId, _P(T.vpTransform), T.vpVec3, _P(T.vpQueryFilter), _P(T.vpQueryHit),
                               c_int32, _P(c_int32)]),
}

for _name, (_res, _args) in _PROTOTYPES.items():
    try:
        _fn = getattr(lib, _name)
    except AttributeError:
        raise ImportError("volphys: %s does not export %s (library from another version?)" % (lib._name, _name))
    _fn.restype = _res
    _fn.argtypes = _args


def last_error():
    msg = lib.vpGetLastError()
    return msg.decode("utf-8", "replace") if msg else ""


def check(status, call):
    """Raises the VolPhysError subclass for `status` unless it is Ok. The message must be
    read right away: it is only valid until the next VolPhys call on this thread."""
    if status != 0:
        raise error_for(status, last_error(), call)


def call(name, *args):
    check(getattr(lib, name)(*args), name)


def encode_path(s):
    """str / bytes / os.PathLike -> bytes for const char* arguments."""
    import os
    return os.fsencode(s)


def _check_struct_sizes():
    # The header version and sizeof(vpWorldDef) go through the library's own check.
    st = lib.vpCheckHeaderVersion(T.VP_HEADER_VERSION, ctypes.sizeof(T.vpWorldDef))
    if st != 0:
        raise ImportError("volphys: the loaded library %s does not match these bindings: %s"
                          % (lib._name, last_error()))
    # Every struct with a structSize default tells us the library's sizeof.
    mismatches = []
    for fn, struct in (("vpDefaultWorldDef", T.vpWorldDef), ("vpDefaultStepStats", T.vpStepStats),
                       ("vpDefaultActorStats", T.vpActorStats),
                       ("vpDefaultShapeDef", T.vpShapeDef), ("vpDefaultColliderDef", T.vpColliderDef),
                       ("vpDefaultDeformableDef", T.vpDeformableDef), ("vpDefaultFluidDef", T.vpFluidDef)):
        lib_size = getattr(lib, fn)().structSize
        if lib_size != ctypes.sizeof(struct):
            mismatches.append("%s: library %d bytes, ctypes %d bytes" % (struct.__name__, lib_size, ctypes.sizeof(struct)))
    if mismatches:
        raise ImportError("volphys: struct layout mismatch with %s (bindings out of date?): %s"
                          % (lib._name, "; ".join(mismatches)))


_check_struct_sizes()
