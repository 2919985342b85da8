"""ctypes mirrors of every struct, enum and callback type in volphys.h.

Field order and types must match the header exactly; volphys._api checks the sizes the
library reports (structSize defaults, vpCheckHeaderVersion) at import.
"""
import ctypes
import enum
from ctypes import c_float, c_int32, c_uint16, c_uint32, c_uint64, c_void_p, c_char_p, c_double, c_size_t, POINTER

VP_VERSION_MAJOR = 0
VP_VERSION_MINOR = 8
VP_VERSION_PATCH = 0
VP_HEADER_VERSION = (VP_VERSION_MAJOR << 16) | (VP_VERSION_MINOR << 8) | VP_VERSION_PATCH
VP_MAX_PHASES = 16

# C enums are ints with this compiler/ABI; ctypes sees them as c_int.
c_enum = ctypes.c_int


class _PrintsName:
    """Enum members print as Type.Name (IntEnum prints the bare number from Python 3.11 on);
    they still compare, compute and pass to C as the ints they are, and numeric format specs
    ("{:d}", "{:x}") still format the number."""

    def __str__(self):
        return "%s.%s" % (type(self).__name__, self.name)

    def __format__(self, spec):
        if spec and spec[-1] in "bcdeEfFgGnoxX%":
            return int.__format__(self, spec)
        return format(str(self), spec)


class NamedIntEnum(_PrintsName, enum.IntEnum):
    pass


class NamedIntFlag(_PrintsName, enum.IntFlag):
    pass


class Status(NamedIntEnum):
    Ok = 0
    InvalidArgument = 1
    InvalidId = 2
    OutOfMemory = 3
    Unsupported = 4
    IoError = 5
    ParseError = 6
    Busy = 7
    Diverged = 8
    VersionMismatch = 9
    Internal = 10
    PhaseFailed = 11
    NotConverged = 12


class LogLevel(NamedIntEnum):
    Debug = 0
    Info = 1
    Warning = 2
    Error = 3
    Off = 4


class Phase(NamedIntEnum):
    Rigid = 0
    Corotate = 1
    Assemble = 2
    Contacts = 3
    Solve = 4
    Embed = 5
    Advect = 6
    Forces = 7
    Fractions = 8
    Pressure = 9
    Surface = 10
    Viscosity = 11
    Coupling = 12


PHASE_COUNT = 13


class ActorKind(NamedIntEnum):
    Rigid = 0
    Deformable = 1
    Fluid = 2


class QueryKind(NamedIntFlag):
    Colliders = 1
    Deformables = 2
    Liquids = 4
    All = 7


class HitKind(NamedIntEnum):
    NoHit = 0
    Collider = 1
    Deformable = 2
    Liquid = 3


class BodyType(NamedIntEnum):
    Static = 0
    Kinematic = 1
    Dynamic = 2


class ShapeType(NamedIntEnum):
    Sphere = 0
    Box = 1
    Capsule = 2
    Cylinder = 3
    Plane = 4
    ConvexHull = 5
    TriangleMesh = 6


class SurfaceMesher(NamedIntEnum):
    Default = 0  # Stuffing
    Stuffing = 1
    Voxel = 2


class Device(NamedIntEnum):
    Auto = 0
    Cpu = 1
    Cuda = 2


class SelfCollision(NamedIntEnum):
    Auto = 0  # on for meshes with more than one layer of elements
    Off = 1
    On = 2


class FluidKind(NamedIntEnum):
    Smoke = 0
    Liquid = 1


class Advection(NamedIntEnum):
    SemiLagrangian = 0
    MacCormack = 1


class DomainSide(NamedIntEnum):
    Wall = 0
    Open = 1


class RegionType(NamedIntEnum):
    Box = 0
    Sphere = 1


class FluidField(NamedIntEnum):
    SmokeDensity = 0
    Temperature = 1
    LevelSet = 2
    Pressure = 3


class vpVersion(ctypes.Structure):
    _fields_ = [("major", c_int32), ("minor", c_int32), ("patch", c_int32)]


class vpVec3(ctypes.Structure):
    _fields_ = [("x", c_float), ("y", c_float), ("z", c_float)]


class vpQuat(ctypes.Structure):
    _fields_ = [("x", c_float), ("y", c_float), ("z", c_float), ("w", c_float)]


class vpTransform(ctypes.Structure):
    _fields_ = [("position", vpVec3), ("rotation", vpQuat)]


# Callback types. CFUNCTYPE(restype, *argtypes).
vpAllocFn = ctypes.CFUNCTYPE(c_void_p, c_size_t, c_size_t, c_void_p)
vpFreeFn = ctypes.CFUNCTYPE(None, c_void_p, c_void_p)
vpLogFn = ctypes.CFUNCTYPE(None, c_enum, c_char_p, c_void_p)
vpTaskFn = ctypes.CFUNCTYPE(None, c_int32, c_int32, c_uint32, c_void_p)
vpEnqueueTaskFn = ctypes.CFUNCTYPE(c_void_p, vpTaskFn, c_int32, c_int32, c_void_p, c_void_p)
vpFinishTaskFn = ctypes.CFUNCTYPE(None, c_void_p, c_void_p)
vpClockFn = ctypes.CFUNCTYPE(c_double, c_void_p)


class vpWorldId(ctypes.Structure):
    _fields_ = [("index1", c_uint16), ("generation", c_uint16)]


class vpColliderId(ctypes.Structure):
    _fields_ = [("index1", c_uint32), ("generation", c_uint32), ("world", vpWorldId)]


class vpDeformableId(ctypes.Structure):
    _fields_ = [("index1", c_uint32), ("generation", c_uint32), ("world", vpWorldId)]


class vpFluidId(ctypes.Structure):
    _fields_ = [("index1", c_uint32), ("generation", c_uint32), ("world", vpWorldId)]


class vpWorldDef(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("gravity", vpVec3),
        ("workerCount", c_int32),
        ("frameBudgetMs", c_float),
        ("rigidMaxSubstep", c_float),
        ("enqueueTask", vpEnqueueTaskFn),
        ("finishTask", vpFinishTaskFn),
        ("userTaskContext", c_void_p),
        ("clock", vpClockFn),
        ("clockContext", c_void_p),
        ("userData", c_void_p),
        ("device", c_int32),
    ]


class vpPhaseStats(ctypes.Structure):
    _fields_ = [("ms", c_float), ("iterations", c_int32), ("residual", c_float), ("budgetCut", c_int32)]


class vpActorStats(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("kind", c_enum),
        ("index1", c_uint32),
        ("totalMs", c_float),
        ("diverged", c_int32),
        ("phases", vpPhaseStats * VP_MAX_PHASES),
        ("simulatedDt", c_float),
        ("interval", c_int32),
        ("completedStep", c_int32),
        ("progress", c_float),
        ("slices", c_int32),
        ("residual", c_float),
        ("priority", c_int32),
        ("floorMissed", c_int32),
        ("failedPhases", c_uint32),
        ("device", c_int32),
    ]


class vpStepStats(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("stepIndex", c_uint64),
        ("dt", c_float),
        ("totalMs", c_float),
        ("budgetMs", c_float),
        ("budgetCut", c_int32),
        ("actorCount", c_int32),
        ("colliderCount", c_int32),
        ("rigidSubsteps", c_int32),
        ("fluidInterval", c_int32),
        ("overBudgetMs", c_float),
        ("budgetInfeasible", c_int32),
        ("maxSliceMs", c_float),
    ]


class vpCollisionFilter(ctypes.Structure):
    _fields_ = [("categoryBits", c_uint32), ("maskBits", c_uint32)]


class vpShapeDef(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("type", c_enum),
        ("radius", c_float),
        ("halfHeight", c_float),
        ("halfExtents", vpVec3),
        ("normal", vpVec3),
        ("offset", c_float),
        ("points", POINTER(c_float)),
        ("pointCount", c_int32),
        ("indices", POINTER(c_int32)),
        ("triangleCount", c_int32),
        ("meshFile", c_char_p),
        ("meshScale", vpVec3),
    ]


class vpColliderDef(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("bodyType", c_enum),
        ("shape", vpShapeDef),
        ("pose", vpTransform),
        ("linearVelocity", vpVec3),
        ("angularVelocity", vpVec3),
        ("mass", c_float),
        ("friction", c_float),
        ("restitution", c_float),
        ("linearDamping", c_float),
        ("angularDamping", c_float),
        ("userData", c_void_p),
        ("filter", vpCollisionFilter),
    ]


class vpBodyProperties(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("mass", c_float),
        ("friction", c_float),
        ("restitution", c_float),
        ("linearDamping", c_float),
        ("angularDamping", c_float),
    ]


class vpDeformableMaterial(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("youngsModulus", c_float),
        ("poissonRatio", c_float),
        ("density", c_float),
        ("massDamping", c_float),
        ("stiffnessDamping", c_float),
        ("friction", c_float),
    ]


class vpFluidParameters(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("ambientTemperature", c_float),
        ("densityBuoyancy", c_float),
        ("thermalBuoyancy", c_float),
        ("vorticityConfinement", c_float),
        ("densityDissipation", c_float),
        ("temperatureDissipation", c_float),
        ("kinematicViscosity", c_float),
        ("sides", c_enum * 6),  # DomainSide: -x, +x, -y, +y, -z, +z
    ]


class vpDeformableDef(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("degree", c_int32),
        ("vertices", POINTER(c_float)),
        ("vertexCount", c_int32),
        ("tets", POINTER(c_int32)),
        ("tetCount", c_int32),
        ("tetFile", c_char_p),
        ("surfaceFile", c_char_p),
        ("voxelResolution", c_int32),
        ("renderVertices", POINTER(c_float)),
        ("renderVertexCount", c_int32),
        ("renderTriangles", POINTER(c_int32)),
        ("renderTriangleCount", c_int32),
        ("pose", vpTransform),
        ("linearVelocity", vpVec3),
        ("youngsModulus", c_float),
        ("poissonRatio", c_float),
        ("density", c_float),
        ("massDamping", c_float),
        ("stiffnessDamping", c_float),
        ("friction", c_float),
        ("solverTolerance", c_float),
        ("solverMaxIterations", c_int32),
        ("userData", c_void_p),
        ("targetResidual", c_float),
        ("priority", c_int32),
        ("filter", vpCollisionFilter),
        ("surfaceMesher", c_int32),  # SurfaceMesher
        ("selfCollision", c_int32),  # SelfCollision
        ("meshGrading", c_int32),  # levels of coarsening inside (stuffing), 0: uniform
    ]


class vpFluidRegion(ctypes.Structure):
    _fields_ = [("type", c_enum), ("centre", vpVec3), ("halfExtents", vpVec3), ("radius", c_float)]


class vpFluidEmitter(ctypes.Structure):
    _fields_ = [("region", vpFluidRegion), ("velocity", vpVec3), ("densityRate", c_float), ("temperature", c_float)]


class vpFluidDef(ctypes.Structure):
    _fields_ = [
        ("structSize", c_uint32),
        ("kind", c_enum),
        ("origin", vpVec3),
        ("resolution", c_int32 * 3),
        ("cellSize", c_float),
        ("sides", c_enum * 6),
        ("density", c_float),
        ("advection", c_enum),
        ("cflNumber", c_float),
        ("maxSubsteps", c_int32),
        ("pressureTolerance", c_float),
        ("pressureMaxIterations", c_int32),
        ("ambientTemperature", c_float),
        ("densityBuoyancy", c_float),
        ("thermalBuoyancy", c_float),
        ("vorticityConfinement", c_float),
        ("densityDissipation", c_float),
        ("temperatureDissipation", c_float),
        ("initialLiquid", POINTER(vpFluidRegion)),
        ("initialLiquidCount", c_int32),
        ("emitters", POINTER(vpFluidEmitter)),
        ("emitterCount", c_int32),
        ("drains", POINTER(vpFluidRegion)),
        ("drainCount", c_int32),
        ("twoWayCoupling", c_int32),
        ("userData", c_void_p),
        ("kinematicViscosity", c_float),
        ("priority", c_int32),
        ("filter", vpCollisionFilter),
    ]


class vpBuildInfo(ctypes.Structure):
    _fields_ = [("cudaCompiled", c_int32), ("cudaDeviceCount", c_int32), ("hardwareThreads", c_int32)]


class vpDeviceInfo(ctypes.Structure):
    _fields_ = [("structSize", c_uint32), ("name", ctypes.c_char * 256), ("totalMemoryBytes", ctypes.c_uint64),
                ("computeCapabilityMajor", c_int32), ("computeCapabilityMinor", c_int32),
                ("multiprocessorCount", c_int32)]


class vpQueryFilter(ctypes.Structure):
    _fields_ = [("kinds", c_int32), ("filter", vpCollisionFilter)]


class vpRay(ctypes.Structure):
    _fields_ = [("origin", vpVec3), ("direction", vpVec3), ("maxDistance", c_float)]


class vpQueryHit(ctypes.Structure):
    _fields_ = [
        ("kind", c_enum),
        ("collider", vpColliderId),
        ("deformable", vpDeformableId),
        ("fluid", vpFluidId),
        ("distance", c_float),
        ("point", vpVec3),
        ("normal", vpVec3),
        ("triangle", c_int32),
        ("barycentric", vpVec3),
        ("nearestNode", c_int32),
    ]


class ContactEventType(NamedIntEnum):
    Begin = 0
    End = 1


class vpContactEvent(ctypes.Structure):
    _fields_ = [
        ("type", c_enum),
        ("deformable", vpDeformableId),
        ("collider", vpColliderId),
        ("nodeCount", c_int32),
        ("point", vpVec3),
        ("normal", vpVec3),
    ]
