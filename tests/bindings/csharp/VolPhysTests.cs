// Tests of the C# binding against the real libvolphys.so, run by ctest under Mono. No test
// framework (Debian's mono has none by default): each public static method named Test* runs,
// failures are printed, and the exit code is the number of failures.
//   mono VolPhysTests.exe PATH/TO/vp_csharp_struct_layout
using System;
using System.Collections.Generic;
using System.Diagnostics;
using System.Reflection;
using System.Runtime.InteropServices;
using VolPhys;

static class VolPhysTests
{
    static string layoutProgram;

    static void Check(bool condition, string what)
    {
        if (!condition) throw new Exception("check failed: " + what);
    }

    // A 2x1x1 box of two unit cubes, six tets each, from the library's mesher.
    static void BoxMesh(out float[] vertices, out int[] tets)
    {
        Deformable.BoxTetMesh(new vpVec3(2, 1, 1), 2, 1, 1, new vpVec3(0, 0, 0), out vertices, out tets);
    }

    public static void TestStructLayoutsMatchTheCCompiler()
    {
        var psi = new ProcessStartInfo(layoutProgram) { RedirectStandardOutput = true, UseShellExecute = false };
        var expected = new Dictionary<string, int>();
        using (Process p = Process.Start(psi))
        {
            string line;
            while ((line = p.StandardOutput.ReadLine()) != null)
            {
                string[] parts = line.Split(' ');
                expected[parts[0]] = int.Parse(parts[1]);
            }
            p.WaitForExit();
            Check(p.ExitCode == 0, "layout program exit code");
        }
        int checkedFields = 0;
        Type[] types = { typeof(vpVersion), typeof(vpVec3), typeof(vpQuat), typeof(vpTransform), typeof(vpWorldId),
                         typeof(vpColliderId), typeof(vpDeformableId), typeof(vpWorldDef), typeof(vpPhaseStats),
                         typeof(vpActorStats), typeof(vpStepStats), typeof(vpShapeDef), typeof(vpColliderDef), typeof(vpBodyProperties), typeof(vpCollisionFilter),
                         typeof(vpQueryFilter), typeof(vpRay), typeof(vpQueryHit), typeof(vpDeformableMaterial),
                         typeof(vpFluidParameters), typeof(vpContactEvent),
                         typeof(vpDeformableDef), typeof(vpFluidId), typeof(vpFluidRegion), typeof(vpFluidEmitter),
                         typeof(vpFluidDef), typeof(vpBuildInfo), typeof(vpDeviceInfo) };
        foreach (Type t in types)
        {
            Check(expected.ContainsKey(t.Name), t.Name + " is printed by the layout program");
            int size = Marshal.SizeOf(t);
            Check(size == expected[t.Name], string.Format("sizeof({0}): C {1}, C# {2}", t.Name, expected[t.Name], size));
            foreach (FieldInfo f in t.GetFields(BindingFlags.Public | BindingFlags.Instance))
            {
                string key = t.Name + "." + f.Name;
                Check(expected.ContainsKey(key), key + " exists in C");
                int offset = (int)Marshal.OffsetOf(t, f.Name);
                Check(offset == expected[key], string.Format("offsetof({0}): C {1}, C# {2}", key, expected[key], offset));
                ++checkedFields;
            }
        }
        // Every C field has a C# twin: the C# side has no fewer fields than the C side.
        int cFields = 0;
        foreach (string k in expected.Keys) if (k.Contains(".")) ++cFields;
        Check(checkedFields == cFields, string.Format("{0} C# fields checked, {1} C fields", checkedFields, cFields));
        // The defaults' structSize is the library's own sizeof: the marshalled return agrees.
        Check(Native.vpDefaultWorldDef().structSize == Marshal.SizeOf(typeof(vpWorldDef)), "vpWorldDef.structSize");
        Check(Native.vpDefaultColliderDef().structSize == Marshal.SizeOf(typeof(vpColliderDef)), "vpColliderDef.structSize");
        Check(Native.vpDefaultDeformableDef().structSize == Marshal.SizeOf(typeof(vpDeformableDef)), "vpDeformableDef.structSize");
        Check(Native.vpDefaultStepStats().structSize == Marshal.SizeOf(typeof(vpStepStats)), "vpStepStats.structSize");
        Check(Native.vpDefaultActorStats().structSize == Marshal.SizeOf(typeof(vpActorStats)), "vpActorStats.structSize");
        Check(Native.vpDefaultFluidDef().structSize == Marshal.SizeOf(typeof(vpFluidDef)), "vpFluidDef.structSize");
    }

    public static void TestVersionAndDefaults()
    {
        vpVersion v = Native.vpGetVersion();
        Check(v.major == Constants.VersionMajor && v.minor >= Constants.VersionMinor, "version " + v.major + "." + v.minor);
        vpWorldDef def = World.DefaultDef();
        Check(Math.Abs(def.gravity.y + 9.81f) < 1e-5f, "default gravity");
        Check(def.workerCount == 1 && def.frameBudgetMs == 16.0f, "default workers and budget");
        Check(def.device == Device.Cpu, "default device");
        vpBuildInfo build;
        Check(Native.vpGetBuildInfo(out build) == Status.Ok, "build info");
        vpDeviceInfo device = new vpDeviceInfo();
        device.structSize = (uint)Marshal.SizeOf(typeof(vpDeviceInfo));
        for (int d = 0; d < build.cudaDeviceCount; ++d)
            Check(Native.vpGetDeviceInfo(d, ref device) == Status.Ok && device.name.Length > 0, "device " + d);
        Check(Native.vpGetDeviceInfo(build.cudaDeviceCount, ref device) == Status.InvalidArgument, "no device past the count");
    }

    // A static plane at y = 0 and a dynamic ball of radius 0.5 dropped from y = 2.
    static Collider GroundAndBall(World world)
    {
        vpColliderDef ground = Collider.DefaultDef();
        ground.shape.type = ShapeType.Plane;
        world.CreateCollider(ground);
        vpColliderDef ballDef = Collider.DefaultDef();
        ballDef.bodyType = BodyType.Dynamic;
        ballDef.shape.radius = 0.5f;
        ballDef.pose.position.y = 2.0f;
        return world.CreateCollider(ballDef);
    }

    public static void TestColliderAndDeformableFallAndRest()
    {
        vpWorldDef def = World.DefaultDef();
        def.frameBudgetMs = 0; // physics checks must not depend on machine speed
        using (var world = new World(def))
        {
            Collider ball = GroundAndBall(world);

            float[] vertices;
            int[] tets;
            BoxMesh(out vertices, out tets);
            vpDeformableDef jelly = Deformable.DefaultDef();
            jelly.pose.position = new vpVec3(3, 3, 0);
            jelly.youngsModulus = 2e5f;
            Deformable body = world.CreateDeformable(jelly, vertices, tets);
            Check(body.NodeCount == 12, "node count " + body.NodeCount);

            vpStepStats stats = default(vpStepStats);
            // The soft box may bounce: begins and ends alternate, and it ends up touching.
            int begins = 0, ends = 0;
            for (int i = 0; i < 120; ++i)
            {
                stats = world.Step(1.0f / 60.0f);
                foreach (vpContactEvent e in world.ContactEvents())
                {
                    if (e.deformable.index1 != body.Id.index1) continue;
                    if (e.type == ContactEventType.Begin) ++begins; else ++ends;
                    Check(begins - ends == 0 || begins - ends == 1, "begin and end alternate");
                }
            }
            Check(begins >= 1 && begins == ends + 1, string.Format("{0} begins, {1} ends", begins, ends));
            Check(stats.stepIndex == 120 && stats.colliderCount == 2 && stats.actorCount == 2,
                  string.Format("stats: step {0}, colliders {1}, actors {2}", stats.stepIndex, stats.colliderCount, stats.actorCount));
            Check(Math.Abs(ball.Pose.position.y - 0.5f) < 0.02f, "ball rests on the plane, y = " + ball.Pose.position.y);

            float[] x = body.GetPositions();
            float minY = float.MaxValue;
            for (int i = 0; i < body.NodeCount; ++i) minY = Math.Min(minY, x[3 * i + 1]);
            Check(minY > -0.05f && minY < 0.1f, "the box landed on the plane, lowest node y = " + minY);
            vpActorStats s = body.Stats;
            Check(s.kind == ActorKind.Deformable && s.Phase(Phase.Solve).iterations > 0, "solve stats through the fixed buffer");

            float[] p, n;
            int[] tris;
            body.GetRenderMesh(out p, out n, out tris);
            Check(p.Length == 36 && tris.Length == 3 * 20, "render mesh sizes");

            vpDeformableMaterial m = body.Material;
            Check(m.youngsModulus == 2e5f, "material read back");
            m.youngsModulus = 4e5f;
            body.Material = m;
            Check(body.Material.youngsModulus == 4e5f, "material set");
            for (int i = 0; i < body.NodeCount; ++i) x[3 * i] += 10.0f;
            body.SetPositions(x, true);
            Check(body.GetPositions()[0] == x[0], "teleported");
        }
    }

    public static void TestBadDefRaisesWithTheFieldName()
    {
        using (var world = new World())
        {
            float[] vertices;
            int[] tets;
            BoxMesh(out vertices, out tets);
            vpDeformableDef bad = Deformable.DefaultDef();
            bad.youngsModulus = -5;
            try
            {
                world.CreateDeformable(bad, vertices, tets);
                Check(false, "a negative Young's modulus was accepted");
            }
            catch (VolPhysException e)
            {
                Check(e.Status == Status.InvalidArgument, "status " + e.Status);
                Check(e.Message.Contains("youngsModulus") && e.Message.Contains("-5"), "message names field and value: " + e.Message);
            }
            vpColliderDef ball = Collider.DefaultDef();
            ball.shape.radius = -1;
            try
            {
                world.CreateCollider(ball);
                Check(false, "a negative radius was accepted");
            }
            catch (VolPhysException e)
            {
                Check(e.Message.Contains("shape.radius"), "message names the field: " + e.Message);
            }
        }
    }

    public static void TestSelfCollisionDefaultsToAutoAndABadValueIsNamed()
    {
        using (var world = new World())
        {
            float[] vertices;
            int[] tets;
            BoxMesh(out vertices, out tets);
            vpDeformableDef def = Deformable.DefaultDef();
            Check(def.selfCollision == SelfCollision.Auto, "default selfCollision " + def.selfCollision);
            def.selfCollision = SelfCollision.Off;
            world.CreateDeformable(def, vertices, tets);
            def.selfCollision = (SelfCollision)7;
            try
            {
                world.CreateDeformable(def, vertices, tets);
                Check(false, "selfCollision = 7 was accepted");
            }
            catch (VolPhysException e)
            {
                Check(e.Status == Status.InvalidArgument, "status " + e.Status);
                Check(e.Message.Contains("selfCollision = 7"), "message names field and value: " + e.Message);
            }
        }
    }

    public static void TestLiquidTankHasAVolumeAndASurface()
    {
        vpWorldDef worldDef = World.DefaultDef();
        worldDef.frameBudgetMs = 0; // a cut pressure solve would make the volume machine-dependent
        using (var world = new World(worldDef))
        {
            vpFluidDef def = Fluid.DefaultDef();
            def.kind = FluidKind.Liquid;
            def.SetResolution(16, 12, 8);
            def.cellSize = 1.0f / 16;
            Check(def.Resolution(1) == 12 && def.Side(3) == DomainSide.Wall, "fixed-buffer accessors");
            // Half of a 1 x 0.75 x 0.5 m tank: 0.1875 m^3.
            var tank = new[] { vpFluidRegion.Box(new vpVec3(0.5f, 0.1875f, 0.25f), new vpVec3(0.5f, 0.1875f, 0.25f)) };
            Fluid liquid = world.CreateFluid(def, tank);
            for (int i = 0; i < 5; ++i) world.Step(1.0f / 60.0f);
            int nx, ny, nz;
            liquid.GetResolution(out nx, out ny, out nz);
            Check(nx == 16 && ny == 12 && nz == 8, string.Format("resolution {0} {1} {2}", nx, ny, nz));
            Check(Math.Abs(liquid.Amount - 0.1875f) < 0.01f, "liquid volume " + liquid.Amount);
            vpFluidParameters fp = liquid.Parameters;
            fp.kinematicViscosity = 1e-3f;
            liquid.Parameters = fp;
            Check(liquid.Parameters.kinematicViscosity == 1e-3f && liquid.EmitterCount == 0, "parameters and emitters");
            int vertices, triangles;
            liquid.GetSurfaceMeshSize(out vertices, out triangles);
            Check(vertices > 0 && triangles > 0, string.Format("surface of {0} vertices, {1} triangles", vertices, triangles));
            float[] positions, normals;
            int[] indices;
            liquid.GetSurfaceMesh(out positions, out normals, out indices);
            Check(positions.Length == 3 * vertices && indices.Length == 3 * triangles, "surface array lengths");
            float[] levelSet = liquid.GetField(FluidField.LevelSet);
            Check(levelSet.Length == nx * ny * nz && levelSet[nx * 1 + 3] < 0, "level set negative near the floor");
            vpVec3[] sampled = liquid.SampleVelocity(new[] { new vpVec3(0.5f, 0.1f, 0.25f), new vpVec3(0.2f, 0.6f, 0.1f) });
            Check(sampled.Length == 2 && !float.IsNaN(sampled[0].y) && Math.Abs(sampled[0].y) < 5, "sampled velocity " + sampled[0]);
            float[] velocity = liquid.GetVelocityGrid();
            Check(velocity.Length == 3 * nx * ny * nz, "velocity grid length " + velocity.Length);
            Check(liquid.Kind == FluidKind.Liquid, "kind " + liquid.Kind);
            vpVec3 origin;
            float cellSize;
            liquid.GetDomain(out origin, out cellSize);
            Check(origin.x == 0 && cellSize == 1.0f / 16, "domain " + origin + " " + cellSize);
            Check(liquid.Stats.kind == ActorKind.Fluid, "stats kind " + liquid.Stats.kind);
            Fluid[] all = world.GetFluids();
            Check(all.Length == 1 && all[0].Id.index1 == liquid.Id.index1, "world lists the fluid");

            vpFluidDef bad = Fluid.DefaultDef();
            bad.cellSize = -1;
            try
            {
                world.CreateFluid(bad);
                Check(false, "a negative cell size was accepted");
            }
            catch (VolPhysException e)
            {
                Check(e.Status == Status.InvalidArgument && e.Message.Contains("cellSize"), "message names the field: " + e.Message);
            }
            liquid.Destroy();
            Check(!liquid.IsValid, "destroyed fluid is invalid");
        }
    }

    static void ExpectInvalidArgument(Action create, params string[] messageParts)
    {
        string expected = string.Join("', '", messageParts);
        try
        {
            create();
            Check(false, "accepted, expected: '" + expected + "'");
        }
        catch (VolPhysException e)
        {
            bool named = e.Status == Status.InvalidArgument;
            foreach (string part in messageParts) named = named && e.Message.Contains(part);
            Check(named, "expected '" + expected + "' in: " + e.Message);
        }
    }

    public static void TestAccuracyFloorAndPrioritiesReachTheStats()
    {
        Check(Deformable.DefaultDef().targetResidual == 1e-2f, "default targetResidual " + Deformable.DefaultDef().targetResidual);
        Check(Deformable.DefaultDef().priority == 0 && Fluid.DefaultDef().priority == 0, "default priorities");
        vpWorldDef worldDef = World.DefaultDef();
        worldDef.frameBudgetMs = 0; // unlimited: nothing is over budget, every actor steps every frame
        using (var world = new World(worldDef))
        {
            float[] vertices;
            int[] tets;
            BoxMesh(out vertices, out tets);
            vpDeformableDef jellyDef = Deformable.DefaultDef();
            jellyDef.targetResidual = 0.05f;
            jellyDef.priority = 6;
            Deformable jelly = world.CreateDeformable(jellyDef, vertices, tets);
            vpFluidDef smokeDef = Fluid.DefaultDef();
            smokeDef.SetResolution(8, 8, 8);
            smokeDef.cellSize = 0.125f;
            smokeDef.origin = new vpVec3(4, 0, 0);
            smokeDef.priority = -2;
            Fluid smoke = world.CreateFluid(smokeDef);
            vpStepStats step = world.Step(1.0f / 60.0f);
            Check(step.overBudgetMs == 0 && step.budgetInfeasible == 0, "unlimited: over budget " + step.overBudgetMs);
            Check(step.maxSliceMs >= 0 && step.maxSliceMs <= step.totalMs, "longest slice " + step.maxSliceMs);
            Check(step.fluidInterval == 1 && step.actorCount == 3, "fluid interval, actor count " + step.actorCount);
            Check(world.ActorStats(0).priority == 0 && world.ActorStats(0).interval == 1, "rigid pseudo-actor");
            Check(world.ActorStats(1).priority == 6 && jelly.Stats.priority == 6, "deformable priority " + jelly.Stats.priority);
            Check(world.ActorStats(2).priority == -2 && smoke.Stats.priority == -2, "fluid priority " + smoke.Stats.priority);
            Check(jelly.Stats.interval == 1 && smoke.Stats.interval == 1, "intervals");
            vpActorStats s = smoke.Stats;
            Check(s.progress >= 0 && s.progress <= 1 && s.slices >= 0 && s.residual >= 0, "progress " + s.progress);
            Check((s.completedStep == 0 || s.completedStep == 1) && (s.floorMissed == 0 || s.floorMissed == 1), "flags");

            vpDeformableDef bad = jellyDef;
            bad.targetResidual = float.NaN;
            // C#'s NaN has its sign bit set: the library prints it as -nan.
            ExpectInvalidArgument(() => world.CreateDeformable(bad, vertices, tets), "targetResidual = ", "nan: must be finite");
            bad.targetResidual = 5e-4f;
            ExpectInvalidArgument(() => world.CreateDeformable(bad, vertices, tets),
                                  "targetResidual = 0.0005: must be >= solverTolerance = 0.001");
            bad.targetResidual = 1.5f;
            ExpectInvalidArgument(() => world.CreateDeformable(bad, vertices, tets), "targetResidual = 1.5");
            bad = jellyDef;
            bad.priority = 1000001;
            ExpectInvalidArgument(() => world.CreateDeformable(bad, vertices, tets), "priority = 1000001");
            vpFluidDef badFluid = smokeDef;
            badFluid.priority = -1000001;
            ExpectInvalidArgument(() => world.CreateFluid(badFluid), "priority = -1000001");
            int deformables;
            VolPhysException.Check(Native.vpWorldGetDeformableCount(world.Id, out deformables), "vpWorldGetDeformableCount");
            Check(deformables == 1 && world.GetFluids().Length == 1, "nothing was created: " + deformables + " deformables");
        }
    }

    public static void TestImpulsesPropertiesAndSleepOnADynamicBody()
    {
        vpWorldDef def = World.DefaultDef();
        def.frameBudgetMs = 0;
        def.gravity = new vpVec3(0, 0, 0);
        using (var world = new World(def))
        {
            vpColliderDef ballDef = Collider.DefaultDef();
            ballDef.bodyType = BodyType.Dynamic;
            ballDef.mass = 2.0f;
            ballDef.angularDamping = 0.0f;
            Collider ball = world.CreateCollider(ballDef);
            vpBodyProperties p = ball.Properties;
            Check(p.mass == 2.0f, "mass read back " + p.mass);
            p.mass = 4.0f;
            ball.Properties = p;
            // J at r = (r, 0, 0) from the centre: dv = J / m, dw = (r x J) / (2/5 m r^2).
            float r = ballDef.shape.radius;
            ball.ApplyImpulse(new vpVec3(0, 0, 1), new vpVec3(r, 0, 0));
            vpVec3 v, w;
            ball.GetVelocity(out v, out w);
            Check(Math.Abs(v.z - 0.25f) < 1e-5f, "dv = J / m: " + v);
            Check(Math.Abs(w.y + r / (0.4f * 4.0f * r * r)) < 1e-4f, "dw = I^-1 (r x J): " + w);
            ball.ApplyForce(new vpVec3(8, 0, 0));
            world.Step(0.5f);
            ball.GetVelocity(out v, out w);
            Check(Math.Abs(v.x - 1.0f) < 1e-4f, "dv = F dt / m: " + v);
            ball.Sleeping = true;
            Check(ball.Sleeping, "put to sleep");
            Check(ball.CollisionFilter.categoryBits == 1 && ball.CollisionFilter.maskBits == 0xFFFFFFFF, "default filter");
            ball.CollisionFilter = new vpCollisionFilter(2, 5);
            Check(ball.CollisionFilter.categoryBits == 2 && ball.CollisionFilter.maskBits == 5, "filter set");
            try
            {
                p.friction = -1.0f;
                ball.Properties = p;
                Check(false, "negative friction accepted");
            }
            catch (VolPhysException e)
            {
                Check(e.Status == Status.InvalidArgument && e.Message.Contains("friction = -1"), e.Message);
            }
        }
    }

    public static void TestRaysAndOverlapsFindTheSphere()
    {
        using (var world = new World())
        {
            Collider sphere = world.CreateCollider(Collider.DefaultDef());  // static, radius 0.5
            vpQueryFilter all = Native.vpDefaultQueryFilter();
            vpQueryHit hit;
            Check(world.Raycast(new vpRay(new vpVec3(-5, 0, 0), new vpVec3(1, 0, 0), 10), all, out hit), "ray hits");
            Check(hit.kind == HitKind.Collider && hit.collider.index1 == sphere.Id.index1, "the sphere");
            Check(Math.Abs(hit.distance - 4.5f) < 1e-4f, "distance " + hit.distance);
            Check(world.RaycastAll(new vpRay(new vpVec3(-5, 2, 0), new vpVec3(1, 0, 0), 10), all).Length == 0, "miss");
            vpQueryHit[] batch = world.RaycastBatch(new[] { new vpRay(new vpVec3(0, 5, 0), new vpVec3(0, -1, 0), 10) }, all);
            Check(batch[0].kind == HitKind.Collider && Math.Abs(batch[0].distance - 4.5f) < 1e-4f, "batch");
            Check(world.OverlapSphere(new vpVec3(0.8f, 0, 0), 0.4f, all).Length == 1, "overlap sphere");
            vpTransform pose = new vpTransform { position = new vpVec3(2, 0, 0), rotation = vpQuat.Identity };
            Check(world.OverlapBox(pose, new vpVec3(1, 1, 1), all).Length == 0, "overlap box");
            all.kinds = QueryKind.Deformables;
            Check(!world.Raycast(new vpRay(new vpVec3(-5, 0, 0), new vpVec3(1, 0, 0), 10), all, out hit), "filtered");
        }
    }

    public static void TestSavedStateRoundTripAndRefusal()
    {
        vpWorldDef def = World.DefaultDef();
        def.frameBudgetMs = 0;
        using (var world = new World(def))
        {
            Collider ball = GroundAndBall(world);
            for (int i = 0; i < 10; ++i) world.Step(1.0f / 60.0f);
            byte[] saved = world.SaveState();
            Check(saved.Length > 40 && saved[0] == (byte)'V', "state of " + saved.Length + " bytes");
            for (int i = 0; i < 30; ++i) world.Step(1.0f / 60.0f);
            float first = ball.Pose.position.y;
            world.RestoreState(saved);
            for (int i = 0; i < 30; ++i) world.Step(1.0f / 60.0f);
            Check(ball.Pose.position.y == first, "the same fall after the restore: " + ball.Pose.position.y + " vs " + first);
            saved[saved.Length / 2] ^= 1;
            try
            {
                world.RestoreState(saved);
                Check(false, "a corrupted state was accepted");
            }
            catch (VolPhysException e)
            {
                Check(e.Status == Status.ParseError && e.Message.Contains("checksum"), e.Message);
            }
        }
    }

    public static void TestBoxTetMeshFillsTheBoxAndNamesBadCells()
    {
        float[] v;
        int[] t;
        Deformable.BoxTetMesh(new vpVec3(1.5f, 0.8f, 0.6f), 3, 2, 2, new vpVec3(-1, 2, 0.5f), out v, out t);
        Check(v.Length == 3 * 4 * 3 * 3 && t.Length == 4 * 6 * 3 * 2 * 2, string.Format("sizes {0} {1}", v.Length, t.Length));
        // Vertex (i, j, k) at i + 4 (j + 3 k): the last one is the far corner.
        Check(v[0] == -1 && v[1] == 2 && v[2] == 0.5f, "first vertex is minCorner");
        int last = v.Length - 3;
        Check(Math.Abs(v[last] - 0.5f) < 1e-6f && Math.Abs(v[last + 1] - 2.8f) < 1e-6f && Math.Abs(v[last + 2] - 1.1f) < 1e-6f,
              string.Format("last vertex ({0}, {1}, {2})", v[last], v[last + 1], v[last + 2]));
        double total = 0;
        for (int i = 0; i < t.Length; i += 4)
        {
            double[] e = new double[9];
            for (int a = 0; a < 3; ++a)
                for (int k = 0; k < 3; ++k) e[3 * a + k] = (double)v[3 * t[i + a + 1] + k] - v[3 * t[i] + k];
            double volume = (e[0] * (e[4] * e[8] - e[5] * e[7]) - e[1] * (e[3] * e[8] - e[5] * e[6]) +
                             e[2] * (e[3] * e[7] - e[4] * e[6])) / 6;
            Check(volume > 0, "tet " + i / 4 + " positively oriented");
            total += volume;
        }
        double box = 1.5 * 0.8 * 0.6;
        Check(Math.Abs(total - box) < 1e-6 * box, "volumes sum to the box's: " + total);
        try
        {
            Deformable.BoxTetMesh(new vpVec3(1, 1, 1), 2, 0, 2, new vpVec3(0, 0, 0), out v, out t);
            Check(false, "cells[1] = 0 was accepted");
        }
        catch (VolPhysException e)
        {
            Check(e.Status == Status.InvalidArgument && e.Message.Contains("cells[1] = 0"), "message names the cell count: " + e.Message);
        }
    }

    public static void TestNamesFromASceneAndTheStaticSolve()
    {
        string path = System.IO.Path.GetTempFileName();
        System.IO.File.WriteAllText(path,
            "{\"colliders\": [{\"name\": \"ground\", \"shape\": {\"type\": \"plane\", \"normal\": [0, 1, 0], \"offset\": 0}}]," +
            " \"deformables\": [{\"name\": \"jelly\", \"degree\": 2, \"box\": {\"cells\": [2, 2, 2], \"size\": [0.4, 0.4, 0.4]}," +
            " \"position\": [0, 0.3, 0], \"youngsModulus\": 1e5}]," +
            " \"fluids\": [{\"name\": \"tank\", \"kind\": \"liquid\", \"origin\": [5, 0, 0], \"resolution\": [4, 4, 4]}]}");
        try
        {
            vpWorldDef def = World.DefaultDef();
            def.frameBudgetMs = 0;
            using (var world = new World(def))
            {
                world.LoadScene(path);
                Check(world.FindCollider("ground").Name == "ground", "collider name");
                Check(world.FindFluid("tank").Name == "tank", "fluid name");
                Deformable jelly = world.FindDeformable("jelly");
                Check(jelly.Name == "jelly", "deformable name");
                float minAngle, maxAngle, tetVolume, surfaceVolume;
                jelly.GetMeshQuality(out minAngle, out maxAngle, out tetVolume, out surfaceVolume);
                Check(Math.Abs(minAngle - 45) < 1e-3f && Math.Abs(maxAngle - 90) < 1e-3f, "dihedral angles 45-90");
                Check(Math.Abs(tetVolume - 0.064f) < 1e-5f && Math.Abs(surfaceVolume - 0.064f) < 1e-5f, "volumes");
                int iterations;
                float residual;
                try
                {
                    jelly.SolveStatic(1, 1e-9f, out iterations, out residual);
                    Check(false, "one iteration to 1e-9 must not converge");
                }
                catch (VolPhysException e)
                {
                    Check(e.Status == Status.NotConverged, "NotConverged, got " + e.Status);
                }
                jelly.SolveStatic(200, 1e-4f, out iterations, out residual);
                Check(iterations > 0 && residual <= 1e-4f, string.Format("{0} iterations, residual {1}", iterations, residual));
                float[] x = jelly.GetPositions();
                float lowest = float.MaxValue;
                for (int i = 1; i < x.Length; i += 3) lowest = Math.Min(lowest, x[i]);
                Check(lowest >= -1e-5f && lowest < 0.01f, "the jelly rests on the ground, lowest node y = " + lowest);
            }
        }
        finally
        {
            System.IO.File.Delete(path);
        }
    }

    public static void TestIdsAfterDestroyRaiseInvalidId()
    {
        var world = new World();
        Collider c = world.CreateCollider(Collider.DefaultDef());
        Check(c.IsValid, "fresh collider is valid");
        world.Dispose();
        Check(!c.IsValid, "collider of a destroyed world is invalid");
        try
        {
            var pose = c.Pose;
            Check(false, "pose of a destroyed collider: " + pose.position);
        }
        catch (VolPhysException e)
        {
            Check(e.Status == Status.InvalidId, "status " + e.Status);
        }
        try
        {
            world.Step(1.0f / 60.0f);
            Check(false, "stepping a disposed world");
        }
        catch (VolPhysException e)
        {
            Check(e.Status == Status.InvalidId, "status " + e.Status);
        }
    }

    static int Main(string[] args)
    {
        if (args.Length != 1)
        {
            Console.Error.WriteLine("usage: VolPhysTests.exe PATH/TO/vp_csharp_struct_layout");
            return 2;
        }
        layoutProgram = args[0];
        int failures = 0, count = 0;
        foreach (MethodInfo m in typeof(VolPhysTests).GetMethods(BindingFlags.Public | BindingFlags.Static))
        {
            if (!m.Name.StartsWith("Test")) continue;
            ++count;
            try
            {
                m.Invoke(null, null);
                Console.WriteLine("PASS " + m.Name);
            }
            catch (TargetInvocationException e)
            {
                ++failures;
                Console.WriteLine("FAIL " + m.Name + ": " + e.InnerException);
            }
        }
        Console.WriteLine("{0} tests, {1} failures", count, failures);
        return failures;
    }
}
