// The C ABI as P/Invoke declarations, one per function in volphys.h. "volphys" resolves to
// libvolphys.so / volphys.dll / libvolphys.dylib the way Unity and Mono look up plugins.
// Strings the library owns (vpGetLastError, vpStatusName) come back as IntPtr: a `string`
// return would make the marshaller free memory it does not own.
using System;
using System.Runtime.InteropServices;

namespace VolPhys
{
    public static class Native
    {
        public const string Library = "volphys";

        [DllImport(Library)] public static extern vpVersion vpGetVersion();
        [DllImport(Library)] public static extern IntPtr vpGetLastError();
        [DllImport(Library)] public static extern IntPtr vpStatusName(Status status);
        [DllImport(Library)] public static extern Status vpCheckHeaderVersion(uint headerVersion, uint worldDefSize);
        [DllImport(Library)] public static extern Status vpSetLogCallback(IntPtr logFn, IntPtr userContext, LogLevel minLevel);
        [DllImport(Library)] public static extern Status vpGetBuildInfo(out vpBuildInfo info);
        [DllImport(Library)] public static extern Status vpGetDeviceInfo(int device, ref vpDeviceInfo info);

        [DllImport(Library)] public static extern int vpWorldIdIsNull(vpWorldId id);
        [DllImport(Library)] public static extern int vpColliderIdIsNull(vpColliderId id);
        [DllImport(Library)] public static extern int vpDeformableIdIsNull(vpDeformableId id);
        [DllImport(Library)] public static extern int vpFluidIdIsNull(vpFluidId id);

        [DllImport(Library)] public static extern vpWorldDef vpDefaultWorldDef();
        [DllImport(Library)] public static extern Status vpWorldCreate(ref vpWorldDef def, out vpWorldId world);
        [DllImport(Library)] public static extern Status vpWorldDestroy(vpWorldId world);
        [DllImport(Library)] public static extern Status vpWorldIsValid(vpWorldId world);
        [DllImport(Library)] public static extern Status vpWorldSetGravity(vpWorldId world, vpVec3 gravity);
        [DllImport(Library)] public static extern Status vpWorldGetGravity(vpWorldId world, out vpVec3 gravity);
        [DllImport(Library)] public static extern Status vpWorldSetFrameBudget(vpWorldId world, float frameBudgetMs);
        [DllImport(Library)] public static extern Status vpWorldStep(vpWorldId world, float dt);
        [DllImport(Library)] public static extern Status vpWorldLoadScene(vpWorldId world, [MarshalAs(UnmanagedType.LPStr)] string path);

        [DllImport(Library)] public static extern vpStepStats vpDefaultStepStats();
        [DllImport(Library)] public static extern vpActorStats vpDefaultActorStats();
        [DllImport(Library)] public static extern Status vpWorldGetStepStats(vpWorldId world, ref vpStepStats stats);
        [DllImport(Library)] public static extern Status vpWorldGetActorStats(vpWorldId world, int actorIndex, ref vpActorStats stats);

        [DllImport(Library)] public static extern vpShapeDef vpDefaultShapeDef();
        [DllImport(Library)] public static extern vpColliderDef vpDefaultColliderDef();
        [DllImport(Library)] public static extern Status vpColliderCreate(vpWorldId world, ref vpColliderDef def, out vpColliderId collider);
        [DllImport(Library)] public static extern Status vpColliderDestroy(vpColliderId collider);
        [DllImport(Library)] public static extern Status vpColliderIsValid(vpColliderId collider);
        [DllImport(Library)] public static extern Status vpColliderGetPose(vpColliderId collider, out vpTransform pose);
        [DllImport(Library)] public static extern Status vpColliderSetPose(vpColliderId collider, ref vpTransform pose);
        [DllImport(Library)] public static extern Status vpColliderGetVelocity(vpColliderId collider, out vpVec3 linear, out vpVec3 angular);
        [DllImport(Library)] public static extern Status vpColliderSetVelocity(vpColliderId collider, vpVec3 linear, vpVec3 angular);
        [DllImport(Library)] public static extern Status vpColliderSetKinematicTarget(vpColliderId collider, ref vpTransform target);
        // point: a vpVec3 by ref, or IntPtr.Zero for the centre of mass (the two overloads).
        [DllImport(Library)] public static extern Status vpColliderApplyForce(vpColliderId collider, vpVec3 force, ref vpVec3 point);
        [DllImport(Library)] public static extern Status vpColliderApplyForce(vpColliderId collider, vpVec3 force, IntPtr point);
        [DllImport(Library)] public static extern Status vpColliderApplyTorque(vpColliderId collider, vpVec3 torque);
        [DllImport(Library)] public static extern Status vpColliderApplyImpulse(vpColliderId collider, vpVec3 impulse, ref vpVec3 point);
        [DllImport(Library)] public static extern Status vpColliderApplyImpulse(vpColliderId collider, vpVec3 impulse, IntPtr point);
        [DllImport(Library)] public static extern Status vpColliderApplyAngularImpulse(vpColliderId collider, vpVec3 angularImpulse);
        [DllImport(Library)] public static extern Status vpColliderGetProperties(vpColliderId collider, ref vpBodyProperties properties);
        [DllImport(Library)] public static extern Status vpColliderSetProperties(vpColliderId collider, ref vpBodyProperties properties);
        [DllImport(Library)] public static extern Status vpColliderIsSleeping(vpColliderId collider, out int sleeping);
        [DllImport(Library)] public static extern Status vpColliderSetSleeping(vpColliderId collider, int sleeping);
        [DllImport(Library)] public static extern Status vpColliderGetCollisionFilter(vpColliderId collider, out vpCollisionFilter filter);
        [DllImport(Library)] public static extern Status vpColliderSetCollisionFilter(vpColliderId collider, vpCollisionFilter filter);
        [DllImport(Library)] public static extern Status vpDeformableGetCollisionFilter(vpDeformableId deformable, out vpCollisionFilter filter);
        [DllImport(Library)] public static extern Status vpDeformableSetCollisionFilter(vpDeformableId deformable, vpCollisionFilter filter);
        [DllImport(Library)] public static extern Status vpFluidGetCollisionFilter(vpFluidId fluid, out vpCollisionFilter filter);
        [DllImport(Library)] public static extern Status vpFluidSetCollisionFilter(vpFluidId fluid, vpCollisionFilter filter);
        [DllImport(Library)] public static extern Status vpColliderGetBodyType(vpColliderId collider, out BodyType type);
        [DllImport(Library)] public static extern Status vpColliderGetUserData(vpColliderId collider, out IntPtr userData);
        [DllImport(Library)] public static extern Status vpColliderGetShapeMeshSize(vpColliderId collider, out int vertexCount, out int triangleCount);
        [DllImport(Library)] public static extern Status vpColliderGetShapeMesh(vpColliderId collider, float[] positions, float[] normals,
                                                                               int vertexCapacity, int[] triangles, int triangleCapacity);
        [DllImport(Library)] public static extern Status vpWorldGetColliderCount(vpWorldId world, out int count);
        [DllImport(Library)] public static extern Status vpWorldGetColliders(vpWorldId world, [Out] vpColliderId[] ids, int capacity, out int count);
        [DllImport(Library)] public static extern Status vpWorldFindCollider(vpWorldId world, [MarshalAs(UnmanagedType.LPStr)] string name, out vpColliderId collider);

        [DllImport(Library)] public static extern vpDeformableDef vpDefaultDeformableDef();
        [DllImport(Library)] public static extern Status vpDeformableCreate(vpWorldId world, ref vpDeformableDef def, out vpDeformableId deformable);
        [DllImport(Library)] public static extern Status vpDeformableDestroy(vpDeformableId deformable);
        [DllImport(Library)] public static extern Status vpDeformableIsValid(vpDeformableId deformable);
        [DllImport(Library)] public static extern Status vpDeformableGetNodeCount(vpDeformableId deformable, out int count);
        [DllImport(Library)] public static extern Status vpDeformableGetPositions(vpDeformableId deformable, [Out] float[] xyz, int capacity);
        [DllImport(Library)] public static extern Status vpDeformableGetVelocities(vpDeformableId deformable, [Out] float[] xyz, int capacity);
        // cells: 3 ints; null arrays (with capacity 0) ask only for the counts.
        [DllImport(Library)] public static extern Status vpBoxTetMesh(vpVec3 size, int[] cells, vpVec3 minCorner, [Out] float[] outVertices,
                                                                      int vertexCapacity, [Out] int[] outTets, int tetCapacity,
                                                                      out int outVertexCount, out int outTetCount);
        [DllImport(Library)] public static extern Status vpDeformableSetVelocities(vpDeformableId deformable, float[] xyz, int nodeCount);
        [DllImport(Library)] public static extern Status vpDeformableApplyForce(vpDeformableId deformable, int node, vpVec3 force);
        [DllImport(Library)] public static extern Status vpDeformableApplyImpulse(vpDeformableId deformable, int node, vpVec3 impulse);
        [DllImport(Library)] public static extern Status vpDeformablePin(vpDeformableId deformable, int[] nodes, int count);
        [DllImport(Library)] public static extern Status vpDeformableUnpin(vpDeformableId deformable, int[] nodes, int count);
        [DllImport(Library)] public static extern Status vpDeformableAttach(vpDeformableId deformable, int[] nodes, int count, vpColliderId collider);
        [DllImport(Library)] public static extern Status vpDeformableGetRenderMeshSize(vpDeformableId deformable, out int vertexCount, out int triangleCount);
        [DllImport(Library)] public static extern Status vpDeformableGetRenderMesh(vpDeformableId deformable, [Out] float[] positions, [Out] float[] normals,
                                                                                  int vertexCapacity, [Out] int[] triangles, int triangleCapacity);
        [DllImport(Library)] public static extern Status vpDeformableGetStats(vpDeformableId deformable, ref vpActorStats stats);
        [DllImport(Library)] public static extern Status vpDeformableGetMeshQuality(vpDeformableId deformable,
                                                                                   out float minDihedralDegrees,
                                                                                   out float maxDihedralDegrees,
                                                                                   out float tetVolume, out float surfaceVolume);
        [DllImport(Library)] public static extern Status vpDeformableSolveStatic(vpDeformableId deformable, int maxIterations,
                                                                                float tolerance, out int outIterations,
                                                                                out float outResidual);
        // A NULL buffer with capacity 0 asks the length (with its terminator) only.
        [DllImport(Library)] public static extern Status vpColliderGetName(vpColliderId collider, [Out] byte[] buffer,
                                                                          int capacity, out int outLength);
        [DllImport(Library)] public static extern Status vpDeformableGetName(vpDeformableId deformable, [Out] byte[] buffer,
                                                                            int capacity, out int outLength);
        [DllImport(Library)] public static extern Status vpFluidGetName(vpFluidId fluid, [Out] byte[] buffer, int capacity,
                                                                       out int outLength);
        [DllImport(Library)] public static extern Status vpWorldGetDeformableCount(vpWorldId world, out int count);
        [DllImport(Library)] public static extern Status vpWorldGetDeformables(vpWorldId world, [Out] vpDeformableId[] ids, int capacity, out int count);
        [DllImport(Library)] public static extern Status vpWorldFindDeformable(vpWorldId world, [MarshalAs(UnmanagedType.LPStr)] string name, out vpDeformableId deformable);

        [DllImport(Library)] public static extern vpFluidDef vpDefaultFluidDef();
        [DllImport(Library)] public static extern Status vpFluidCreate(vpWorldId world, ref vpFluidDef def, out vpFluidId fluid);
        [DllImport(Library)] public static extern Status vpFluidDestroy(vpFluidId fluid);
        [DllImport(Library)] public static extern Status vpFluidIsValid(vpFluidId fluid);
        [DllImport(Library)] public static extern Status vpFluidGetResolution(vpFluidId fluid, out int nx, out int ny, out int nz);
        [DllImport(Library)] public static extern Status vpFluidGetKind(vpFluidId fluid, out FluidKind kind);
        [DllImport(Library)] public static extern Status vpFluidGetDomain(vpFluidId fluid, out vpVec3 origin, out float cellSize);
        [DllImport(Library)] public static extern Status vpFluidGetField(vpFluidId fluid, FluidField field, [Out] float[] values, long capacity);
        [DllImport(Library)] public static extern Status vpFluidGetVelocityGrid(vpFluidId fluid, [Out] float[] xyz, long capacity);
        [DllImport(Library)] public static extern Status vpFluidSampleVelocity(vpFluidId fluid, vpVec3[] points, int count, [Out] vpVec3[] velocities);
        [DllImport(Library)] public static extern Status vpFluidGetSurfaceMeshSize(vpFluidId fluid, out int vertexCount, out int triangleCount);
        [DllImport(Library)] public static extern Status vpFluidGetSurfaceMesh(vpFluidId fluid, [Out] float[] positions, [Out] float[] normals,
                                                                              int vertexCapacity, [Out] int[] triangles, int triangleCapacity);
        [DllImport(Library)] public static extern Status vpFluidGetAmount(vpFluidId fluid, out float amount);
        [DllImport(Library)] public static extern Status vpFluidGetStats(vpFluidId fluid, ref vpActorStats stats);
        [DllImport(Library)] public static extern Status vpWorldGetFluidCount(vpWorldId world, out int count);
        [DllImport(Library)] public static extern Status vpWorldGetFluids(vpWorldId world, [Out] vpFluidId[] ids, int capacity, out int count);
        [DllImport(Library)] public static extern Status vpWorldFindFluid(vpWorldId world, [MarshalAs(UnmanagedType.LPStr)] string name, out vpFluidId fluid);

        [DllImport(Library)] public static extern Status vpDeformableSetPositions(vpDeformableId deformable, float[] xyz, int nodeCount, int resetVelocities);
        [DllImport(Library)] public static extern Status vpDeformableGetMaterial(vpDeformableId deformable, ref vpDeformableMaterial material);
        [DllImport(Library)] public static extern Status vpDeformableSetMaterial(vpDeformableId deformable, ref vpDeformableMaterial material);
        [DllImport(Library)] public static extern Status vpFluidGetParameters(vpFluidId fluid, ref vpFluidParameters parameters);
        [DllImport(Library)] public static extern Status vpFluidSetParameters(vpFluidId fluid, ref vpFluidParameters parameters);
        [DllImport(Library)] public static extern Status vpFluidGetEmitterCount(vpFluidId fluid, out int count);
        [DllImport(Library)] public static extern Status vpFluidSetEmitter(vpFluidId fluid, int index, int enabled, float densityRate, vpVec3 velocity, float temperature);
        [DllImport(Library)] public static extern Status vpWorldSaveState(vpWorldId world, [Out] byte[] buffer, UIntPtr capacity, out UIntPtr size);
        [DllImport(Library)] public static extern Status vpWorldRestoreState(vpWorldId world, byte[] buffer, UIntPtr size);
        [DllImport(Library)] public static extern Status vpWorldGetContactEvents(vpWorldId world, [Out] vpContactEvent[] events, int capacity, out int count);
        [DllImport(Library)] public static extern vpQueryFilter vpDefaultQueryFilter();
        [DllImport(Library)] public static extern Status vpWorldRaycast(vpWorldId world, ref vpRay ray, ref vpQueryFilter filter, out vpQueryHit hit, out int hitCount);
        [DllImport(Library)] public static extern Status vpWorldRaycastAll(vpWorldId world, ref vpRay ray, ref vpQueryFilter filter, [Out] vpQueryHit[] hits, int capacity, out int count);
        [DllImport(Library)] public static extern Status vpWorldRaycastBatch(vpWorldId world, vpRay[] rays, int count, ref vpQueryFilter filter, [Out] vpQueryHit[] hits);
        [DllImport(Library)] public static extern Status vpWorldOverlapSphere(vpWorldId world, vpVec3 centre, float radius, ref vpQueryFilter filter, [Out] vpQueryHit[] hits, int capacity, out int count);
        [DllImport(Library)] public static extern Status vpWorldOverlapBox(vpWorldId world, ref vpTransform pose, vpVec3 halfExtents, ref vpQueryFilter filter, [Out] vpQueryHit[] hits, int capacity, out int count);

        public static string LastError() { return Marshal.PtrToStringAnsi(vpGetLastError()) ?? ""; }
    }
}
