// Blittable mirrors of the structs and enums in volphys.h, in the same order with the same
// field names, so that [StructLayout(LayoutKind.Sequential)] gives the C layout on every
// 64-bit platform a game engine runs on. Pointers and callbacks are IntPtr; C flags are int.
// tests/bindings/csharp checks every size and field offset against the C compiler's.
using System;
using System.Runtime.InteropServices;

namespace VolPhys
{
    public enum Status : int
    {
        Ok = 0, InvalidArgument = 1, InvalidId = 2, OutOfMemory = 3, Unsupported = 4, IoError = 5,
        ParseError = 6, Busy = 7, Diverged = 8, VersionMismatch = 9, Internal = 10, PhaseFailed = 11,
        NotConverged = 12
    }

    public enum LogLevel : int { Debug = 0, Info = 1, Warning = 2, Error = 3, Off = 4 }

    public enum Phase : int
    {
        Rigid = 0, Corotate = 1, Assemble = 2, Contacts = 3, Solve = 4, Embed = 5, Advect = 6, Forces = 7,
        Fractions = 8, Pressure = 9, Surface = 10, Viscosity = 11, Coupling = 12
    }

    public enum ActorKind : int { Rigid = 0, Deformable = 1, Fluid = 2 }
    public enum BodyType : int { Static = 0, Kinematic = 1, Dynamic = 2 }
    public enum ShapeType : int { Sphere = 0, Box = 1, Capsule = 2, Cylinder = 3, Plane = 4, ConvexHull = 5, TriangleMesh = 6 }

    public enum SurfaceMesher : int { Default = 0, Stuffing = 1, Voxel = 2 }
    /// <summary>Contact of a deformable with itself; Auto: on for meshes with more than one layer of elements.</summary>
    public enum SelfCollision : int { Auto = 0, Off = 1, On = 2 }
    public enum Device : int { Auto = 0, Cpu = 1, Cuda = 2 }
    public enum FluidKind : int { Smoke = 0, Liquid = 1 }
    public enum Advection : int { SemiLagrangian = 0, MacCormack = 1 }
    public enum DomainSide : int { Wall = 0, Open = 1 }
    public enum RegionType : int { Box = 0, Sphere = 1 }
    public enum FluidField : int { SmokeDensity = 0, Temperature = 1, LevelSet = 2, Pressure = 3 }
    [Flags] public enum QueryKind : int { Colliders = 1, Deformables = 2, Liquids = 4, All = 7 }
    public enum HitKind : int { None = 0, Collider = 1, Deformable = 2, Liquid = 3 }
    public enum ContactEventType : int { Begin = 0, End = 1 }

    public static class Constants
    {
        public const int VersionMajor = 0, VersionMinor = 8, VersionPatch = 0;
        public const uint HeaderVersion = (VersionMajor << 16) | (VersionMinor << 8) | VersionPatch;
        public const int MaxPhases = 16;
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpVersion { public int major, minor, patch; }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpVec3
    {
        public float x, y, z;
        public vpVec3(float x, float y, float z) { this.x = x; this.y = y; this.z = z; }
        public override string ToString() { return string.Format("({0}, {1}, {2})", x, y, z); }
    }

    /// <summary>Unit quaternion, w last.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct vpQuat
    {
        public float x, y, z, w;
        public static readonly vpQuat Identity = new vpQuat { w = 1 };
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpTransform { public vpVec3 position; public vpQuat rotation; }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpWorldId
    {
        public ushort index1, generation;
        public bool IsNull { get { return index1 == 0; } }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpColliderId
    {
        public uint index1, generation;
        public vpWorldId world;
        public bool IsNull { get { return index1 == 0; } }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpDeformableId
    {
        public uint index1, generation;
        public vpWorldId world;
        public bool IsNull { get { return index1 == 0; } }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpFluidId
    {
        public uint index1, generation;
        public vpWorldId world;
        public bool IsNull { get { return index1 == 0; } }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpWorldDef
    {
        public uint structSize;
        public vpVec3 gravity;
        public int workerCount;
        public float frameBudgetMs;
        public float rigidMaxSubstep;
        public IntPtr enqueueTask;
        public IntPtr finishTask;
        public IntPtr userTaskContext;
        public IntPtr clock;
        public IntPtr clockContext;
        public IntPtr userData;
        /// <summary>Where the deformables' solves run (default Cpu).</summary>
        public Device device;
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpPhaseStats
    {
        public float ms;
        public int iterations;
        public float residual;
        public int budgetCut;
    }

    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct vpActorStats
    {
        public uint structSize;
        public ActorKind kind;
        public uint index1;
        public float totalMs;
        public int diverged;
        // vpPhaseStats[VP_MAX_PHASES] as raw storage: C# fixed buffers hold only primitives.
        public fixed int phases[Constants.MaxPhases * 4];
        public float simulatedDt;
        /// <summary>Frames per step (a fluid: the frames its last completed step spanned).</summary>
        public int interval;
        public int completedStep;
        /// <summary>Fluid: fraction of its current step done at the end of the frame, 1 when it completed.</summary>
        public float progress;
        public int slices;
        /// <summary>Final relative residual of the actor's iterative solve in the frame.</summary>
        public float residual;
        public int priority;
        /// <summary>Deformable: its solve ended the frame above its targetResidual.</summary>
        public int floorMissed;
        public uint failedPhases;
        /// <summary>Where its solve ran in this frame (Cpu, or Cuda).</summary>
        public Device device;

        public vpPhaseStats Phase(Phase phase)
        {
            int i = (int)phase;
            if (i < 0 || i >= Constants.MaxPhases) throw new ArgumentOutOfRangeException("phase");
            fixed (int* p = phases) { return ((vpPhaseStats*)p)[i]; }
        }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpStepStats
    {
        public uint structSize;
        public ulong stepIndex;
        public float dt;
        public float totalMs;
        public float budgetMs;
        public int budgetCut;
        public int actorCount;
        public int colliderCount;
        public int rigidSubsteps;
        public int fluidInterval;
        /// <summary>How far totalMs went past budgetMs; 0 when within it or unlimited.</summary>
        public float overBudgetMs;
        /// <summary>The accuracy floors and minimum rates did not fit the budget: some actor ran at
        /// its interval cap.</summary>
        public int budgetInfeasible;
        public float maxSliceMs;
    }

    /// <summary>Two objects meet when each one's categoryBits share a bit with the other's maskBits.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct vpCollisionFilter
    {
        public uint categoryBits;
        public uint maskBits;
        public vpCollisionFilter(uint categoryBits, uint maskBits) { this.categoryBits = categoryBits; this.maskBits = maskBits; }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpDeformableMaterial
    {
        public uint structSize;
        public float youngsModulus;
        public float poissonRatio;
        public float density;
        public float massDamping;
        public float stiffnessDamping;
        public float friction;
    }

    // The six DomainSide entries of vpFluidDef and vpFluidParameters (fixed int buffers).
    static unsafe class DomainSides
    {
        public static void Set(int* sides, int side, DomainSide value)
        {
            if (side < 0 || side > 5) throw new ArgumentOutOfRangeException("side");
            sides[side] = (int)value;
        }

        public static DomainSide Get(int* sides, int side)
        {
            if (side < 0 || side > 5) throw new ArgumentOutOfRangeException("side");
            return (DomainSide)sides[side];
        }
    }

    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct vpFluidParameters
    {
        public uint structSize;
        public float ambientTemperature;
        public float densityBuoyancy;
        public float thermalBuoyancy;
        public float vorticityConfinement;
        public float densityDissipation;
        public float temperatureDissipation;
        public float kinematicViscosity;
        // DomainSide per side (-x, +x, -y, +y, -z, +z), as in vpFluidDef.
        public fixed int sides[6];

        /// <summary>side: 0..5 for -x, +x, -y, +y, -z, +z.</summary>
        public void SetSide(int side, DomainSide value)
        {
            fixed (int* s = sides) { DomainSides.Set(s, side, value); }
        }

        public DomainSide Side(int side)
        {
            fixed (int* s = sides) { return DomainSides.Get(s, side); }
        }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpContactEvent
    {
        public ContactEventType type;
        public vpDeformableId deformable;
        public vpColliderId collider;
        public int nodeCount;
        public vpVec3 point;
        public vpVec3 normal;
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpQueryFilter
    {
        public QueryKind kinds;
        public vpCollisionFilter filter;
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpRay
    {
        public vpVec3 origin;
        public vpVec3 direction;
        public float maxDistance;
        public vpRay(vpVec3 origin, vpVec3 direction, float maxDistance) { this.origin = origin; this.direction = direction; this.maxDistance = maxDistance; }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpQueryHit
    {
        public HitKind kind;
        public vpColliderId collider;
        public vpDeformableId deformable;
        public vpFluidId fluid;
        public float distance;
        public vpVec3 point;
        public vpVec3 normal;
        public int triangle;
        public vpVec3 barycentric;
        public int nearestNode;
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpShapeDef
    {
        public uint structSize;
        public ShapeType type;
        public float radius;
        public float halfHeight;
        public vpVec3 halfExtents;
        public vpVec3 normal;
        public float offset;
        public IntPtr points;
        public int pointCount;
        public IntPtr indices;
        public int triangleCount;
        public IntPtr meshFile;
        public vpVec3 meshScale;
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpColliderDef
    {
        public uint structSize;
        public BodyType bodyType;
        public vpShapeDef shape;
        public vpTransform pose;
        public vpVec3 linearVelocity;
        public vpVec3 angularVelocity;
        public float mass;
        public float friction;
        public float restitution;
        public float linearDamping;
        public float angularDamping;
        public IntPtr userData;
        public vpCollisionFilter filter;
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpBodyProperties
    {
        public uint structSize;
        public float mass;
        public float friction;
        public float restitution;
        public float linearDamping;
        public float angularDamping;
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpDeformableDef
    {
        public uint structSize;
        public int degree;
        public IntPtr vertices;
        public int vertexCount;
        public IntPtr tets;
        public int tetCount;
        public IntPtr tetFile;
        public IntPtr surfaceFile;
        public int voxelResolution;
        public IntPtr renderVertices;
        public int renderVertexCount;
        public IntPtr renderTriangles;
        public int renderTriangleCount;
        public vpTransform pose;
        public vpVec3 linearVelocity;
        public float youngsModulus;
        public float poissonRatio;
        public float density;
        public float massDamping;
        public float stiffnessDamping;
        public float friction;
        public float solverTolerance;
        public int solverMaxIterations;
        public IntPtr userData;
        /// <summary>The accuracy floor of the implicit solve, in [solverTolerance, 1].</summary>
        public float targetResidual;
        /// <summary>Higher is served first when the frame budget is short.</summary>
        public int priority;
        /// <summary>The colliders it contacts.</summary>
        public vpCollisionFilter filter;
        /// <summary>How surfaceFile becomes tets (isosurface stuffing by default, or voxels).</summary>
        public SurfaceMesher surfaceMesher;
        /// <summary>Contact with itself (Auto: on for meshes with more than one layer of elements).</summary>
        public SelfCollision selfCollision;
        /// <summary>Levels of coarsening inside the body for the stuffing mesher, 0..8 (0: a uniform lattice).</summary>
        public int meshGrading;
    }

    /// <summary>A region in world coordinates: a box (centre, halfExtents) or a sphere (centre, radius).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct vpFluidRegion
    {
        public RegionType type;
        public vpVec3 centre;
        public vpVec3 halfExtents;
        public float radius;

        public static vpFluidRegion Box(vpVec3 centre, vpVec3 halfExtents)
        {
            return new vpFluidRegion { type = RegionType.Box, centre = centre, halfExtents = halfExtents };
        }

        public static vpFluidRegion Sphere(vpVec3 centre, float radius)
        {
            return new vpFluidRegion { type = RegionType.Sphere, centre = centre, radius = radius };
        }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpFluidEmitter
    {
        public vpFluidRegion region;
        public vpVec3 velocity;
        public float densityRate;
        public float temperature;
    }

    [StructLayout(LayoutKind.Sequential)]
    public unsafe struct vpFluidDef
    {
        public uint structSize;
        public FluidKind kind;
        public vpVec3 origin;
        public fixed int resolution[3];
        public float cellSize;
        // DomainSide per side (-x, +x, -y, +y, -z, +z): fixed buffers hold only primitives.
        public fixed int sides[6];
        public float density;
        public Advection advection;
        public float cflNumber;
        public int maxSubsteps;
        public float pressureTolerance;
        public int pressureMaxIterations;
        public float ambientTemperature;
        public float densityBuoyancy;
        public float thermalBuoyancy;
        public float vorticityConfinement;
        public float densityDissipation;
        public float temperatureDissipation;
        public IntPtr initialLiquid;
        public int initialLiquidCount;
        public IntPtr emitters;
        public int emitterCount;
        public IntPtr drains;
        public int drainCount;
        public int twoWayCoupling;
        public IntPtr userData;
        public float kinematicViscosity;
        /// <summary>Higher is served first when the frame budget is short.</summary>
        public int priority;
        /// <summary>The colliders that bound it.</summary>
        public vpCollisionFilter filter;

        public void SetResolution(int nx, int ny, int nz)
        {
            fixed (int* r = resolution) { r[0] = nx; r[1] = ny; r[2] = nz; }
        }

        public int Resolution(int axis)
        {
            if (axis < 0 || axis > 2) throw new ArgumentOutOfRangeException("axis");
            fixed (int* r = resolution) { return r[axis]; }
        }

        /// <summary>side: 0..5 for -x, +x, -y, +y, -z, +z.</summary>
        public void SetSide(int side, DomainSide value)
        {
            fixed (int* s = sides) { DomainSides.Set(s, side, value); }
        }

        public DomainSide Side(int side)
        {
            fixed (int* s = sides) { return DomainSides.Get(s, side); }
        }
    }

    [StructLayout(LayoutKind.Sequential)]
    public struct vpBuildInfo
    {
        public int cudaCompiled;
        public int cudaDeviceCount;
        public int hardwareThreads;
    }

    /// <summary>Set structSize to Marshal.SizeOf(typeof(vpDeviceInfo)) before vpGetDeviceInfo.</summary>
    [StructLayout(LayoutKind.Sequential, CharSet = CharSet.Ansi)]
    public struct vpDeviceInfo
    {
        public uint structSize;
        [MarshalAs(UnmanagedType.ByValTStr, SizeConst = 256)] public string name;
        public ulong totalMemoryBytes;
        public int computeCapabilityMajor;
        public int computeCapabilityMinor;
        public int multiprocessorCount;
    }
}
