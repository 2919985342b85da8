// A VolPhys world owned by managed code: destroyed by Dispose (or, as a last resort, by the
// finalizer). Colliders, deformables and fluids are value handles over their ids; after the world is
// gone their calls throw VolPhysException(InvalidId) instead of touching freed memory.
using System;
using System.Runtime.InteropServices;

namespace VolPhys
{
    public sealed class World : IDisposable
    {
        public vpWorldId Id { get; private set; }

        static World()
        {
            // The header version these bindings mirror, and their vpWorldDef size, must match
            // the loaded library: a mismatch would corrupt every def passed across.
            VolPhysException.Check(Native.vpCheckHeaderVersion(Constants.HeaderVersion, (uint)Marshal.SizeOf(typeof(vpWorldDef))),
                                   "vpCheckHeaderVersion");
        }

        public static vpWorldDef DefaultDef() { return Native.vpDefaultWorldDef(); }

        public World() : this(DefaultDef()) { }

        public World(vpWorldDef def)
        {
            vpWorldId id;
            VolPhysException.Check(Native.vpWorldCreate(ref def, out id), "vpWorldCreate");
            Id = id;
        }

        public void LoadScene(string path) { VolPhysException.Check(Native.vpWorldLoadScene(Id, path), "vpWorldLoadScene"); }
        public void SetFrameBudget(float ms) { VolPhysException.Check(Native.vpWorldSetFrameBudget(Id, ms), "vpWorldSetFrameBudget"); }

        public vpVec3 Gravity
        {
            get { vpVec3 g; VolPhysException.Check(Native.vpWorldGetGravity(Id, out g), "vpWorldGetGravity"); return g; }
            set { VolPhysException.Check(Native.vpWorldSetGravity(Id, value), "vpWorldSetGravity"); }
        }

        /// <summary>Advances the world by dt seconds and returns the step's statistics.</summary>
        public vpStepStats Step(float dt)
        {
            VolPhysException.Check(Native.vpWorldStep(Id, dt), "vpWorldStep");
            vpStepStats stats = Native.vpDefaultStepStats();
            VolPhysException.Check(Native.vpWorldGetStepStats(Id, ref stats), "vpWorldGetStepStats");
            return stats;
        }

        public vpActorStats ActorStats(int actorIndex)
        {
            vpActorStats s = Native.vpDefaultActorStats();
            VolPhysException.Check(Native.vpWorldGetActorStats(Id, actorIndex, ref s), "vpWorldGetActorStats");
            return s;
        }

        /// <summary>Deformable-collider contacts that began or ended in the last step.</summary>
        public vpContactEvent[] ContactEvents()
        {
            int count;
            VolPhysException.Check(Native.vpWorldGetContactEvents(Id, null, 0, out count), "vpWorldGetContactEvents");
            var events = new vpContactEvent[count];
            VolPhysException.Check(Native.vpWorldGetContactEvents(Id, events, count, out count), "vpWorldGetContactEvents");
            return events;
        }

        int stateSize; // the last saved state's size: the next save's first guess

        /// <summary>Everything that evolves, as bytes (vpWorldSaveState: saving completes any
        /// fluid step in progress and rebuilds Bullet's caches; stepping after RestoreState is
        /// bitwise the stepping after this call). One save when the size is unchanged.</summary>
        public byte[] SaveState()
        {
            while (true)
            {
                var buffer = new byte[stateSize];
                UIntPtr size;
                Status status = Native.vpWorldSaveState(Id, stateSize > 0 ? buffer : null, (UIntPtr)stateSize, out size);
                bool fits = (ulong)size <= (ulong)stateSize;
                if (status == Status.Ok && fits && stateSize > 0)
                {
                    Array.Resize(ref buffer, (int)size);
                    return buffer;
                }
                if ((status != Status.Ok && status != Status.InvalidArgument) || (status != Status.Ok && fits))
                    VolPhysException.Check(status, "vpWorldSaveState");
                stateSize = checked((int)(ulong)size);
            }
        }

        /// <summary>Puts back a state from SaveState; a truncated, corrupted or foreign one
        /// throws (the world is unchanged).</summary>
        public void RestoreState(byte[] state)
        {
            VolPhysException.Check(Native.vpWorldRestoreState(Id, state, (UIntPtr)state.Length), "vpWorldRestoreState");
        }

        // Scene queries: filter from Native.vpDefaultQueryFilter() (every kind, every category).
        /// <summary>The nearest hit along the ray; false when nothing is hit.</summary>
        public bool Raycast(vpRay ray, vpQueryFilter filter, out vpQueryHit hit)
        {
            int count;
            VolPhysException.Check(Native.vpWorldRaycast(Id, ref ray, ref filter, out hit, out count), "vpWorldRaycast");
            return count == 1;
        }

        /// <summary>Every object the ray hits, nearest first.</summary>
        public vpQueryHit[] RaycastAll(vpRay ray, vpQueryFilter filter)
        {
            return Collect((hits, capacity) => { int n; VolPhysException.Check(Native.vpWorldRaycastAll(Id, ref ray, ref filter, hits, capacity, out n), "vpWorldRaycastAll"); return n; });
        }

        /// <summary>Each ray's nearest hit (kind HitKind.None for a miss).</summary>
        public vpQueryHit[] RaycastBatch(vpRay[] rays, vpQueryFilter filter)
        {
            var hits = new vpQueryHit[rays.Length];
            VolPhysException.Check(Native.vpWorldRaycastBatch(Id, rays, rays.Length, ref filter, hits), "vpWorldRaycastBatch");
            return hits;
        }

        public vpQueryHit[] OverlapSphere(vpVec3 centre, float radius, vpQueryFilter filter)
        {
            return Collect((hits, capacity) => { int n; VolPhysException.Check(Native.vpWorldOverlapSphere(Id, centre, radius, ref filter, hits, capacity, out n), "vpWorldOverlapSphere"); return n; });
        }

        public vpQueryHit[] OverlapBox(vpTransform pose, vpVec3 halfExtents, vpQueryFilter filter)
        {
            return Collect((hits, capacity) => { int n; VolPhysException.Check(Native.vpWorldOverlapBox(Id, ref pose, halfExtents, ref filter, hits, capacity, out n), "vpWorldOverlapBox"); return n; });
        }

        // Fills a buffer, growing it until every hit fits.
        static vpQueryHit[] Collect(Func<vpQueryHit[], int, int> fill)
        {
            var hits = new vpQueryHit[8];
            int count = fill(hits, hits.Length);
            if (count > hits.Length)
            {
                hits = new vpQueryHit[count];
                count = fill(hits, hits.Length);
            }
            Array.Resize(ref hits, Math.Min(count, hits.Length));
            return hits;
        }

        public Collider CreateCollider(vpColliderDef def)
        {
            vpColliderId id;
            VolPhysException.Check(Native.vpColliderCreate(Id, ref def, out id), "vpColliderCreate");
            return new Collider(id);
        }

        /// <summary>A deformable from a tet mesh: xyz per vertex, 4 vertex indices per tet.
        /// The arrays are pinned for the call only (the library copies them).</summary>
        public Deformable CreateDeformable(vpDeformableDef def, float[] vertices, int[] tets)
        {
            if (vertices == null || tets == null) throw new ArgumentNullException(vertices == null ? "vertices" : "tets");
            GCHandle v = GCHandle.Alloc(vertices, GCHandleType.Pinned), t = GCHandle.Alloc(tets, GCHandleType.Pinned);
            try
            {
                def.vertices = v.AddrOfPinnedObject();
                def.vertexCount = vertices.Length / 3;
                def.tets = t.AddrOfPinnedObject();
                def.tetCount = tets.Length / 4;
                return CreateDeformable(def);
            }
            finally
            {
                v.Free();
                t.Free();
            }
        }

        /// <summary>A deformable from a def whose pointers the caller keeps valid during the call.</summary>
        public Deformable CreateDeformable(vpDeformableDef def)
        {
            vpDeformableId id;
            VolPhysException.Check(Native.vpDeformableCreate(Id, ref def, out id), "vpDeformableCreate");
            return new Deformable(id);
        }

        /// <summary>A fluid with its sources: the arrays are pinned for the call only (the library
        /// copies them); null means none.</summary>
        public Fluid CreateFluid(vpFluidDef def, vpFluidRegion[] initialLiquid = null, vpFluidEmitter[] emitters = null,
                                 vpFluidRegion[] drains = null)
        {
            var pins = new GCHandle[3];
            try
            {
                def.initialLiquid = Pin(initialLiquid, ref pins[0]);
                def.initialLiquidCount = initialLiquid == null ? 0 : initialLiquid.Length;
                def.emitters = Pin(emitters, ref pins[1]);
                def.emitterCount = emitters == null ? 0 : emitters.Length;
                def.drains = Pin(drains, ref pins[2]);
                def.drainCount = drains == null ? 0 : drains.Length;
                return CreateFluid(def);
            }
            finally
            {
                foreach (GCHandle h in pins) if (h.IsAllocated) h.Free();
            }
        }

        static IntPtr Pin(object array, ref GCHandle handle)
        {
            if (array == null) return IntPtr.Zero;
            handle = GCHandle.Alloc(array, GCHandleType.Pinned);
            return handle.AddrOfPinnedObject();
        }

        /// <summary>A fluid from a def whose pointers the caller keeps valid during the call.</summary>
        public Fluid CreateFluid(vpFluidDef def)
        {
            vpFluidId id;
            VolPhysException.Check(Native.vpFluidCreate(Id, ref def, out id), "vpFluidCreate");
            return new Fluid(id);
        }

        public Fluid FindFluid(string name)
        {
            vpFluidId id;
            VolPhysException.Check(Native.vpWorldFindFluid(Id, name, out id), "vpWorldFindFluid");
            return new Fluid(id);
        }

        /// <summary>The world's fluids in slot order.</summary>
        public Fluid[] GetFluids()
        {
            int count;
            VolPhysException.Check(Native.vpWorldGetFluidCount(Id, out count), "vpWorldGetFluidCount");
            var ids = new vpFluidId[count];
            VolPhysException.Check(Native.vpWorldGetFluids(Id, ids, count, out count), "vpWorldGetFluids");
            var fluids = new Fluid[count];
            for (int i = 0; i < count; ++i) fluids[i] = new Fluid(ids[i]);
            return fluids;
        }

        public Collider FindCollider(string name)
        {
            vpColliderId id;
            VolPhysException.Check(Native.vpWorldFindCollider(Id, name, out id), "vpWorldFindCollider");
            return new Collider(id);
        }

        public Deformable FindDeformable(string name)
        {
            vpDeformableId id;
            VolPhysException.Check(Native.vpWorldFindDeformable(Id, name, out id), "vpWorldFindDeformable");
            return new Deformable(id);
        }

        public void Dispose()
        {
            if (!Id.IsNull) Native.vpWorldDestroy(Id);
            Id = default(vpWorldId);
            GC.SuppressFinalize(this);
        }

        ~World()
        {
            // Worlds are not bound to a thread, so destroying one from the finalizer is allowed.
            if (!Id.IsNull) Native.vpWorldDestroy(Id);
        }
    }
}
