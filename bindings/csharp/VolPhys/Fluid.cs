// A fluid actor by id (a value: copying it does not copy the actor). Grids are flat arrays in
// the C order (x fastest: cell (i, j, k) at i + nx * (j + ny * k)); the overloads taking an
// array fill a host buffer, so a game loop can reuse one.
namespace VolPhys
{
    public struct Fluid
    {
        public readonly vpFluidId Id;
        public Fluid(vpFluidId id) { Id = id; }

        public static vpFluidDef DefaultDef() { return Native.vpDefaultFluidDef(); }

        public bool IsValid { get { return Native.vpFluidIsValid(Id) == Status.Ok; } }
        /// <summary>The name its scene file gave it ("" when none).</summary>
        public string Name
        {
            get { var id = Id; return ActorName.Read((byte[] b, int c, out int l) => Native.vpFluidGetName(id, b, c, out l), "vpFluidGetName"); }
        }

        /// <summary>Which colliders it meets; a change takes effect from the next step.</summary>
        public vpCollisionFilter CollisionFilter
        {
            get { vpCollisionFilter f; VolPhysException.Check(Native.vpFluidGetCollisionFilter(Id, out f), "vpFluidGetCollisionFilter"); return f; }
            set { VolPhysException.Check(Native.vpFluidSetCollisionFilter(Id, value), "vpFluidSetCollisionFilter"); }
        }

        public void GetResolution(out int nx, out int ny, out int nz)
        {
            VolPhysException.Check(Native.vpFluidGetResolution(Id, out nx, out ny, out nz), "vpFluidGetResolution");
        }

        public FluidKind Kind
        {
            get { FluidKind k; VolPhysException.Check(Native.vpFluidGetKind(Id, out k), "vpFluidGetKind"); return k; }
        }

        /// <summary>The domain's low corner and the cell size in metres.</summary>
        public void GetDomain(out vpVec3 origin, out float cellSize)
        {
            VolPhysException.Check(Native.vpFluidGetDomain(Id, out origin, out cellSize), "vpFluidGetDomain");
        }

        public int CellCount
        {
            get { int nx, ny, nz; GetResolution(out nx, out ny, out nz); return nx * ny * nz; }
        }

        /// <summary>A cell-centred field, one value per cell.</summary>
        public float[] GetField(FluidField field) { float[] values = new float[CellCount]; GetField(field, values); return values; }
        public void GetField(FluidField field, float[] values)
        {
            VolPhysException.Check(Native.vpFluidGetField(Id, field, values, values.Length), "vpFluidGetField");
        }

        /// <summary>The velocity at the cell centres, xyz per cell.</summary>
        public float[] GetVelocityGrid() { float[] xyz = new float[3 * CellCount]; GetVelocityGrid(xyz); return xyz; }
        public void GetVelocityGrid(float[] xyz)
        {
            VolPhysException.Check(Native.vpFluidGetVelocityGrid(Id, xyz, xyz.Length / 3), "vpFluidGetVelocityGrid");
        }

        public vpVec3[] SampleVelocity(vpVec3[] points)
        {
            var velocities = new vpVec3[points.Length];
            VolPhysException.Check(Native.vpFluidSampleVelocity(Id, points, points.Length, velocities), "vpFluidSampleVelocity");
            return velocities;
        }

        public void GetSurfaceMeshSize(out int vertexCount, out int triangleCount)
        {
            VolPhysException.Check(Native.vpFluidGetSurfaceMeshSize(Id, out vertexCount, out triangleCount),
                                   "vpFluidGetSurfaceMeshSize");
        }

        /// <summary>Liquid: the free surface in world space (xyz per vertex, normals out of the
        /// liquid, 3 indices per triangle). Smoke: empty.</summary>
        public void GetSurfaceMesh(out float[] positions, out float[] normals, out int[] triangles)
        {
            int nv, nt;
            GetSurfaceMeshSize(out nv, out nt);
            positions = new float[3 * nv];
            normals = new float[3 * nv];
            triangles = new int[3 * nt];
            VolPhysException.Check(Native.vpFluidGetSurfaceMesh(Id, positions, normals, nv, triangles, nt), "vpFluidGetSurfaceMesh");
        }

        /// <summary>Liquid: volume in m^3. Smoke: total smoke (density * m^3).</summary>
        public float Amount
        {
            get { float a; VolPhysException.Check(Native.vpFluidGetAmount(Id, out a), "vpFluidGetAmount"); return a; }
        }

        public vpActorStats Stats
        {
            get { vpActorStats s = Native.vpDefaultActorStats(); VolPhysException.Check(Native.vpFluidGetStats(Id, ref s), "vpFluidGetStats"); return s; }
        }

        /// <summary>Forces and viscosity as last set; a set acts from the next fluid step that begins.</summary>
        public vpFluidParameters Parameters
        {
            get
            {
                var p = new vpFluidParameters { structSize = (uint)System.Runtime.InteropServices.Marshal.SizeOf(typeof(vpFluidParameters)) };
                VolPhysException.Check(Native.vpFluidGetParameters(Id, ref p), "vpFluidGetParameters");
                return p;
            }
            set
            {
                value.structSize = (uint)System.Runtime.InteropServices.Marshal.SizeOf(typeof(vpFluidParameters));
                VolPhysException.Check(Native.vpFluidSetParameters(Id, ref value), "vpFluidSetParameters");
            }
        }

        public int EmitterCount
        {
            get { int n; VolPhysException.Check(Native.vpFluidGetEmitterCount(Id, out n), "vpFluidGetEmitterCount"); return n; }
        }

        public void SetEmitter(int index, bool enabled, float densityRate, vpVec3 velocity, float temperature)
        {
            VolPhysException.Check(Native.vpFluidSetEmitter(Id, index, enabled ? 1 : 0, densityRate, velocity, temperature), "vpFluidSetEmitter");
        }

        public void Destroy() { VolPhysException.Check(Native.vpFluidDestroy(Id), "vpFluidDestroy"); }
    }
}
