// A deformable volume by id (a value: copying it does not copy the actor). Array getters
// allocate; the overloads taking an array fill a host buffer, as a game loop would.
namespace VolPhys
{
    public struct Deformable
    {
        public readonly vpDeformableId Id;
        public Deformable(vpDeformableId id) { Id = id; }

        public static vpDeformableDef DefaultDef() { return Native.vpDefaultDeformableDef(); }

        /// <summary>The library's box mesher (vpBoxTetMesh, the one scene files use for "box"
        /// deformables): the box [minCorner, minCorner + size] as cellsX x cellsY x cellsZ cubes of
        /// 6 positively oriented tets. vertices: xyz per vertex, x fastest; tets: 4 indices each.
        /// Bad arguments raise a VolPhysException naming them.</summary>
        public static void BoxTetMesh(vpVec3 size, int cellsX, int cellsY, int cellsZ, vpVec3 minCorner,
                                      out float[] vertices, out int[] tets)
        {
            int[] cells = { cellsX, cellsY, cellsZ };
            int nv, nt;
            VolPhysException.Check(Native.vpBoxTetMesh(size, cells, minCorner, null, 0, null, 0, out nv, out nt), "vpBoxTetMesh");
            vertices = new float[3 * nv];
            tets = new int[4 * nt];
            VolPhysException.Check(Native.vpBoxTetMesh(size, cells, minCorner, vertices, nv, tets, nt, out nv, out nt), "vpBoxTetMesh");
        }

        public bool IsValid { get { return Native.vpDeformableIsValid(Id) == Status.Ok; } }

        /// <summary>Which colliders it meets; a change takes effect from the next step.</summary>
        public vpCollisionFilter CollisionFilter
        {
            get { vpCollisionFilter f; VolPhysException.Check(Native.vpDeformableGetCollisionFilter(Id, out f), "vpDeformableGetCollisionFilter"); return f; }
            set { VolPhysException.Check(Native.vpDeformableSetCollisionFilter(Id, value), "vpDeformableSetCollisionFilter"); }
        }

        public int NodeCount
        {
            get { int n; VolPhysException.Check(Native.vpDeformableGetNodeCount(Id, out n), "vpDeformableGetNodeCount"); return n; }
        }

        /// <summary>Node positions, xyz per node.</summary>
        public float[] GetPositions() { float[] xyz = new float[3 * NodeCount]; GetPositions(xyz); return xyz; }
        public void GetPositions(float[] xyz)
        {
            VolPhysException.Check(Native.vpDeformableGetPositions(Id, xyz, xyz.Length / 3), "vpDeformableGetPositions");
        }

        public float[] GetVelocities()
        {
            float[] xyz = new float[3 * NodeCount];
            VolPhysException.Check(Native.vpDeformableGetVelocities(Id, xyz, xyz.Length / 3), "vpDeformableGetVelocities");
            return xyz;
        }

        public void Pin(int[] nodes) { VolPhysException.Check(Native.vpDeformablePin(Id, nodes, nodes.Length), "vpDeformablePin"); }

        public void ApplyImpulse(int node, vpVec3 impulse)
        {
            VolPhysException.Check(Native.vpDeformableApplyImpulse(Id, node, impulse), "vpDeformableApplyImpulse");
        }

        /// <summary>The embedded render mesh: positions and normals (xyz per vertex), triangles.</summary>
        public void GetRenderMesh(out float[] positions, out float[] normals, out int[] triangles)
        {
            int nv, nt;
            VolPhysException.Check(Native.vpDeformableGetRenderMeshSize(Id, out nv, out nt), "vpDeformableGetRenderMeshSize");
            positions = new float[3 * nv];
            normals = new float[3 * nv];
            triangles = new int[3 * nt];
            VolPhysException.Check(Native.vpDeformableGetRenderMesh(Id, positions, normals, nv, triangles, nt),
                                   "vpDeformableGetRenderMesh");
        }

        /// <summary>The name its scene file gave it ("" when none).</summary>
        public string Name
        {
            get { var id = Id; return ActorName.Read((byte[] b, int c, out int l) => Native.vpDeformableGetName(id, b, c, out l), "vpDeformableGetName"); }
        }

        /// <summary>The simulation mesh's dihedral angle range (degrees) and its tets' volume against
        /// the volume its render surface encloses (vpDeformableGetMeshQuality).</summary>
        public void GetMeshQuality(out float minDihedralDegrees, out float maxDihedralDegrees, out float tetVolume,
                                   out float surfaceVolume)
        {
            VolPhysException.Check(Native.vpDeformableGetMeshQuality(Id, out minDihedralDegrees, out maxDihedralDegrees,
                                                                     out tetVolume, out surfaceVolume),
                                   "vpDeformableGetMeshQuality");
        }

        /// <summary>Moves the body to its static equilibrium and leaves it at rest there
        /// (vpDeformableSolveStatic); a VolPhysException with Status.NotConverged leaves it unchanged.</summary>
        public void SolveStatic(int maxIterations, float tolerance, out int iterations, out float residual)
        {
            VolPhysException.Check(Native.vpDeformableSolveStatic(Id, maxIterations, tolerance, out iterations, out residual),
                                   "vpDeformableSolveStatic");
        }

        public vpActorStats Stats
        {
            get { vpActorStats s = Native.vpDefaultActorStats(); VolPhysException.Check(Native.vpDeformableGetStats(Id, ref s), "vpDeformableGetStats"); return s; }
        }

        /// <summary>Teleports every node (xyz per node); the render mesh follows.</summary>
        public void SetPositions(float[] xyz, bool resetVelocities)
        {
            VolPhysException.Check(Native.vpDeformableSetPositions(Id, xyz, xyz.Length / 3, resetVelocities ? 1 : 0), "vpDeformableSetPositions");
        }

        /// <summary>The material, validated on set (a failure changes nothing); acts from the next step.</summary>
        public vpDeformableMaterial Material
        {
            get
            {
                var m = new vpDeformableMaterial { structSize = (uint)System.Runtime.InteropServices.Marshal.SizeOf(typeof(vpDeformableMaterial)) };
                VolPhysException.Check(Native.vpDeformableGetMaterial(Id, ref m), "vpDeformableGetMaterial");
                return m;
            }
            set
            {
                value.structSize = (uint)System.Runtime.InteropServices.Marshal.SizeOf(typeof(vpDeformableMaterial));
                VolPhysException.Check(Native.vpDeformableSetMaterial(Id, ref value), "vpDeformableSetMaterial");
            }
        }

        public void Destroy() { VolPhysException.Check(Native.vpDeformableDestroy(Id), "vpDeformableDestroy"); }
    }
}
