"""Tests of the Python bindings against the real libvolphys.so (found via $VOLPHYS_LIBRARY).

Run: VOLPHYS_LIBRARY=build/release/plugin_api/libvolphys.so PYTHONPATH=bindings/python \
     /usr/bin/python3 -m unittest discover -s tests/bindings -v
"""
import ctypes
import os
import subprocess
import sys
import tempfile
import unittest

import volphys
from volphys import _types as T

try:
    import numpy as np
except ImportError:
    np = None

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DEFAULT_SCENE = os.path.join(REPO, "sample_host", "scenes", "default.json")
DT = 1.0 / 60.0


def centred_cube(n, size):
    """An n^3-cell cube of edge `size` centred at the origin, from the library's mesher."""
    return volphys.box_tet_mesh((size, size, size), (n, n, n), (-size / 2, -size / 2, -size / 2))


class WorldLifecycle(unittest.TestCase):
    def test_create_step_destroy(self):
        w = volphys.World(gravity=(0, -9.81, 0), workers=2, frame_budget_ms=0)
        self.assertTrue(w.is_valid)
        self.assertEqual(w.gravity, (0.0, -9.8100004196167, 0.0))
        s = w.step(DT)
        self.assertEqual(s.step_index, 1)
        self.assertAlmostEqual(s.dt, DT, places=6)
        self.assertEqual(s.budget_ms, 0.0)
        w.step(DT)
        self.assertEqual(w.stats().step_index, 2)
        w.destroy()
        self.assertFalse(w.is_valid)
        w.destroy()  # idempotent, like file.close()

    def test_context_manager_destroys_world_and_its_objects(self):
        with volphys.World() as w:
            c = w.create_collider(volphys.Sphere(0.5), position=(0, 1, 0))
            self.assertTrue(c.is_valid)
        self.assertFalse(w.is_valid)
        self.assertFalse(c.is_valid)
        with self.assertRaises(volphys.InvalidIdError):
            c.pose

    def test_collider_context_manager(self):
        with volphys.World() as w:
            with w.create_collider(volphys.Box((0.5, 0.5, 0.5)), body_type="static") as c:
                self.assertEqual(len(w.colliders()), 1)
            self.assertFalse(c.is_valid)
            self.assertEqual(w.colliders(), [])

    def test_version_and_build_info(self):
        self.assertEqual(volphys.library_version()[0], T.VP_VERSION_MAJOR)
        info = volphys.build_info()
        self.assertGreaterEqual(info["hardware_threads"], 1)

    def test_device_info_for_each_counted_device(self):
        count = volphys.build_info()["cuda_device_count"]
        for d in range(count):
            self.assertTrue(volphys.device_info(d)["name"])
        with self.assertRaisesRegex(volphys.InvalidArgumentError, "device = %d" % count):
            volphys.device_info(count)

    def test_device_choice_and_where_a_deformable_was_solved(self):
        has_device = volphys.build_info()["cuda_device_count"] > 0
        verts, tets = centred_cube(1, 1.0)
        for device in (None, volphys.Device.Auto, volphys.Device.Cuda):
            if device == volphys.Device.Cuda and not has_device:
                with self.assertRaisesRegex(volphys.UnsupportedError, "device = 2"):
                    volphys.World(device=device)
                continue
            with volphys.World(device=device) as w:
                w.create_deformable(vertices=verts, tets=tets)
                w.step(DT)
                solved = w.actor_stats()[1].device
                self.assertEqual(solved, volphys.Device.Cuda if device is not None and has_device else volphys.Device.Cpu)


class Logging(unittest.TestCase):
    def test_log_callback_receives_world_created(self):
        got = []
        volphys.set_log_callback(lambda level, msg: got.append((level, msg)), volphys.LogLevel.Info)
        try:
            volphys.World(workers=1).destroy()
        finally:
            volphys.set_log_callback(None)
        self.assertTrue(any(level == volphys.LogLevel.Info and "world created" in msg for level, msg in got), got)
        got.clear()
        volphys.World().destroy()
        self.assertEqual(got, [], "None must restore the default logger")


class Rigid(unittest.TestCase):
    def test_ball_dropped_on_plane_rests_at_its_radius(self):
        with volphys.World() as w:
            w.create_collider(volphys.Plane((0, 1, 0), 0.0), body_type=volphys.BodyType.Static)
            ball = w.create_collider(volphys.Sphere(radius=0.3), position=(0, 2, 0), mass=1.0)
            self.assertEqual(ball.body_type, volphys.BodyType.Dynamic)
            for _ in range(180):
                w.step(DT)
            (x, y, z), rot = ball.pose
            self.assertAlmostEqual(y, 0.3, delta=0.02)
            lin, _ = ball.velocity
            self.assertLess(max(abs(v) for v in lin), 0.05)

    def test_velocity_and_kinematic_target(self):
        with volphys.World(gravity=(0, 0, 0)) as w:
            body = w.create_collider(volphys.Sphere(0.2), linear_velocity=(1, 0, 0))
            self.assertAlmostEqual(body.velocity[0][0], 1.0, places=5)
            body.set_velocity((0, 2, 0))
            self.assertAlmostEqual(body.velocity[0][1], 2.0, places=5)
            kin = w.create_collider(volphys.Box((0.5, 0.1, 0.5)), body_type="kinematic")
            kin.set_kinematic_target((0.5, 0.25, 0))
            w.step(DT)
            px, py, pz = kin.position
            self.assertAlmostEqual(px, 0.5, places=4)
            self.assertAlmostEqual(py, 0.25, places=4)
            kin.pose = ((1, 1, 1), (0, 0, 0, 1))
            self.assertAlmostEqual(kin.position[2], 1.0, places=5)


    def test_push_a_body_change_its_mass_and_put_it_to_sleep(self):
        with volphys.World(gravity=(0, 0, 0), frame_budget_ms=0) as w:
            ball = w.create_collider(volphys.Sphere(0.5), mass=2.0, angular_damping=0.0)
            self.assertAlmostEqual(ball.properties.mass, 2.0)
            ball.set_properties(mass=4.0, friction=0.8)
            self.assertAlmostEqual(ball.properties.friction, 0.8, places=6)
            # J at r = (0.5, 0, 0): dv = J / m, dw = (r x J) / (2/5 m r^2).
            ball.apply_impulse((0, 0, 1), point=(0.5, 0, 0))
            lin, ang = ball.velocity
            self.assertAlmostEqual(lin[2], 0.25, places=5)
            self.assertAlmostEqual(ang[1], -0.5 / (0.4 * 4.0 * 0.25), places=4)
            ball.apply_force((8, 0, 0))
            w.step(0.5)
            self.assertAlmostEqual(ball.velocity[0][0], 1.0, places=4)
            ball.sleeping = True
            self.assertTrue(ball.sleeping)
            with self.assertRaises(volphys.InvalidArgumentError) as e:
                ball.set_properties(restitution=2)
            self.assertIn("restitution = 2", str(e.exception))
            self.assertAlmostEqual(ball.properties.mass, 4.0)
            with self.assertRaises(TypeError):
                ball.set_properties(bounciness=1)
            floor = w.create_collider(volphys.Plane(), body_type="static")
            with self.assertRaises(volphys.InvalidArgumentError) as e:
                floor.apply_force((1, 0, 0))
            self.assertIn("static", str(e.exception))


    def test_collision_filter_lets_a_ball_through_the_ground_until_changed(self):
        with volphys.World(frame_budget_ms=0) as w:
            ground = w.create_collider(volphys.Plane(), body_type="static", collision_filter=(2, 0xFFFFFFFF))
            ball = w.create_collider(volphys.Sphere(0.5), position=(0, 3, 0), collision_filter=(1, ~2 & 0xFFFFFFFF))
            self.assertEqual(ball.collision_filter, volphys.CollisionFilter(1, 0xFFFFFFFD))
            for _ in range(10):
                w.step(DT)
            ball.collision_filter = volphys.CollisionFilter(1, 0xFFFFFFFF)
            for _ in range(120):
                w.step(DT)
            self.assertAlmostEqual(ball.position[1], 0.5, delta=0.01)
            self.assertEqual(ground.collision_filter.category, 2)
            fluid = w.create_fluid(resolution=(4, 4, 4), collision_filter=(4, 4))
            self.assertEqual(fluid.collision_filter, (4, 4))
            fluid.collision_filter = (8, 1)
            self.assertEqual(fluid.collision_filter.mask, 1)


    def test_rays_and_overlaps_find_colliders(self):
        with volphys.World(frame_budget_ms=0) as w:
            ball = w.create_collider(volphys.Sphere(1.0), body_type="static")
            far = w.create_collider(volphys.Sphere(1.0), body_type="static", position=(10, 0, 0))
            hit = w.raycast((-5, 0.5, 0), (2, 0, 0))  # any length: normalized
            self.assertEqual(hit.kind, volphys.HitKind.Collider)
            self.assertEqual(hit.obj, ball)
            self.assertAlmostEqual(hit.distance, 5 - 0.75 ** 0.5, places=4)
            self.assertAlmostEqual(hit.normal[1], 0.5, places=4)
            self.assertEqual([h.obj for h in w.raycast_all((-5, 0, 0), (1, 0, 0))], [ball, far])
            self.assertIsNone(w.raycast((-5, 0, 0), (1, 0, 0), kinds=volphys.QueryKind.Deformables))
            self.assertIsNone(w.raycast((-5, 3, 0), (1, 0, 0)))
            batch = w.raycast_batch([(-5, 0, 0), (-5, 3, 0)], [(1, 0, 0), (1, 0, 0)])
            self.assertEqual(batch[0].obj, ball)
            self.assertIsNone(batch[1])
            self.assertEqual([h.obj for h in w.overlap_sphere((1.5, 0, 0), 0.6)], [ball])
            self.assertEqual(w.overlap_box((1.4, 0, 0), (0.3, 0.3, 0.3)), [])
            with self.assertRaises(volphys.InvalidArgumentError) as e:
                w.raycast((0, 0, 0), (0, 0, 0))
            self.assertIn("ray.direction", str(e.exception))


@unittest.skipIf(np is None, "numpy is not importable")
class SavedStates(unittest.TestCase):
    def test_round_trip_and_refusals(self):
        with volphys.World() as w:
            w.load_scene(DEFAULT_SCENE)
            w.set_frame_budget(0)  # the scene's budget would make the steps depend on the clock
            for _ in range(5):
                w.step(DT)
            saved = w.save_state()
            self.assertEqual(saved[:7], b"VPSTATE")
            crate = w.find_collider("crate")
            trajectory = []
            for _ in range(5):
                w.step(DT)
                trajectory.append(crate.pose)
            w.restore_state(saved)
            again = []
            for _ in range(5):
                w.step(DT)
                again.append(crate.pose)
            self.assertEqual(again, trajectory)
            with self.assertRaises(volphys.ParseError) as e:
                w.restore_state(saved[:-1])
            self.assertIn("truncated", str(e.exception))
            corrupted = bytearray(saved)
            corrupted[len(saved) // 2] ^= 1
            with self.assertRaises(volphys.ParseError) as e:
                w.restore_state(corrupted)
            self.assertIn("checksum", str(e.exception))
        with volphys.World() as other:
            with self.assertRaises(volphys.InvalidArgumentError) as e:
                other.restore_state(saved)
            self.assertIn("collider count", str(e.exception))


class Deformables(unittest.TestCase):
    def make(self, w, **kw):
        verts, tets = centred_cube(2, 0.4)
        return w.create_deformable(vertices=verts, tets=tets, position=(0, 2, 0), **kw), verts

    def test_material_and_teleport(self):
        with volphys.World(frame_budget_ms=0) as w:
            d, verts = self.make(w)
            d.set_material(youngs_modulus=2e6, density=500)
            m = d.material
            self.assertEqual((m.youngs_modulus, m.density), (2e6, 500))
            with self.assertRaises(volphys.InvalidArgumentError) as e:
                d.set_material(poisson_ratio=0.5)
            self.assertIn("poissonRatio = 0.5", str(e.exception))
            self.assertAlmostEqual(d.material.poisson_ratio, 0.3, places=6)
            x = d.positions() + np.array([3.0, 0.0, 0.0], dtype=np.float32)
            d.set_positions(x, reset_velocities=True)
            np.testing.assert_allclose(d.positions(), x)
            self.assertGreater(float(d.render_mesh()[0][:, 0].min()), 2.0)

    def test_landing_on_the_floor_is_one_begin_event(self):
        with volphys.World(frame_budget_ms=0) as w:
            floor = w.create_collider(volphys.Plane(), body_type="static")
            d, verts = self.make(w)
            events = []
            for _ in range(90):
                w.step(DT)
                events += w.contact_events()
            self.assertEqual(len(events), 1)
            self.assertEqual(events[0].type, volphys.ContactEventType.Begin)
            self.assertEqual((events[0].deformable, events[0].collider), (d, floor))
            self.assertAlmostEqual(events[0].normal[1], 1.0, places=3)

    def test_ray_hits_the_deformable_surface(self):
        with volphys.World(frame_budget_ms=0) as w:
            d, verts = self.make(w)
            top = 2 + float(np.max(verts[:, 1]))
            hit = w.raycast((0.2, 10, 0.2), (0, -1, 0))
            self.assertEqual(hit.kind, volphys.HitKind.Deformable)
            self.assertEqual(hit.obj, d)
            self.assertAlmostEqual(hit.point[1], top, places=5)
            self.assertGreaterEqual(hit.triangle, 0)
            self.assertAlmostEqual(sum(hit.barycentric), 1.0, places=5)
            self.assertTrue(0 <= hit.nearest_node < d.node_count)
            self.assertEqual([h.obj for h in w.overlap_sphere((0.2, 2.2, 0.2), 0.05)], [d])

    def test_box_from_numpy_falls(self):
        with volphys.World(frame_budget_ms=0) as w:
            d, verts = self.make(w)
            self.assertEqual(d.node_count, len(verts))
            p0 = d.positions()
            self.assertEqual(p0.dtype, np.float32)
            self.assertEqual(p0.shape, (len(verts), 3))
            self.assertAlmostEqual(float(p0[:, 1].mean()), 2.0, places=4)
            n = 30
            for _ in range(n):
                w.step(DT)
            drop = 2.0 - float(d.positions()[:, 1].mean())
            # Backward Euler free fall: sum_{k=1..n} k g dt^2 = g dt^2 n(n+1)/2 (1.27 m).
            expected = 9.81 * DT * DT * n * (n + 1) / 2
            self.assertAlmostEqual(drop, expected, delta=0.05 * expected)
            self.assertLess(float(d.velocities()[:, 1].mean()), -4.0)
            st = d.stats()
            self.assertEqual(st.kind, volphys.ActorKind.Deformable)
            self.assertGreater(st.phases[volphys.Phase.Solve].iterations, 0)
            kinds = [a.kind for a in w.actor_stats()]
            self.assertEqual(kinds[0], volphys.ActorKind.Rigid)
            self.assertIn(volphys.ActorKind.Deformable, kinds)

    def test_pin_keeps_nodes_fixed_and_unpin_releases_them(self):
        with volphys.World() as w:
            d, _ = self.make(w)
            p0 = d.positions()
            top = np.nonzero(p0[:, 1] > p0[:, 1].max() - 1e-4)[0].astype(np.int32)
            self.assertEqual(len(top), 9)
            d.pin(top)
            for _ in range(20):
                w.step(DT)
            p1 = d.positions()
            np.testing.assert_allclose(p1[top], p0[top], atol=1e-6)
            bottom = p0[:, 1] < p0[:, 1].min() + 1e-4
            # The free end hangs from the pinned one: it must have sagged (so the step ran).
            self.assertLess(float((p1[bottom, 1] - p0[bottom, 1]).max()), -1e-4)
            d.unpin(top)
            for _ in range(10):
                w.step(DT)
            self.assertLess(float(d.positions()[top, 1].max()), float(p0[top, 1].max()) - 0.01)

    def test_impulse_set_velocities_and_render_mesh(self):
        with volphys.World(gravity=(0, 0, 0)) as w:
            d, verts = self.make(w)
            d.apply_impulse(0, (0.0, 0.0, 1.0))
            v = d.velocities()
            self.assertGreater(v[0, 2], 0.0)
            self.assertEqual(float(np.abs(v[1:]).max()), 0.0)
            d.set_velocities(np.zeros_like(verts))
            self.assertEqual(float(np.abs(d.velocities()).max()), 0.0)
            pos, nrm, tri = d.render_mesh()
            self.assertEqual(pos.shape, nrm.shape)
            self.assertEqual(tri.dtype, np.int32)
            self.assertEqual(tri.shape[1], 3)
            # Boundary of a 2x2x2-cell cube: 6 faces x 4 squares x 2 triangles.
            self.assertEqual(len(tri), 48)
            self.assertLess(int(tri.max()), len(pos))
            np.testing.assert_allclose(np.linalg.norm(nrm, axis=1), 1.0, atol=1e-4)

    def test_attach_to_kinematic_collider_follows_it(self):
        with volphys.World(gravity=(0, 0, 0)) as w:
            d, _ = self.make(w)
            paddle = w.create_collider(volphys.Box((0.1, 0.1, 0.1)), body_type="kinematic", position=(0, 2, 0))
            d.attach([0, 1, 2], paddle)
            before = d.positions()[[0, 1, 2]].copy()
            paddle.set_kinematic_target((0.0, 2.5, 0.0))
            w.step(DT)
            after = d.positions()[[0, 1, 2]]
            np.testing.assert_allclose(after - before, [[0, 0.5, 0]] * 3, atol=1e-3)

    def test_bad_node_index_raises_and_names_it(self):
        with volphys.World() as w:
            d, verts = self.make(w)
            with self.assertRaises(volphys.InvalidArgumentError) as cm:
                d.pin([0, len(verts)])
            self.assertIn(str(len(verts)), cm.exception.message)
            with self.assertRaises(ValueError):
                d.set_velocities(np.zeros((len(verts), 2)))
            with self.assertRaises(ValueError):
                d.pin(np.array([0.5]))
            with self.assertRaises(ValueError):
                d.pin(np.array([2 ** 32], dtype=np.int64))


@unittest.skipIf(np is None, "numpy is needed for the fluid grid checks")
class Fluids(unittest.TestCase):
    def setUp(self):
        self.world = volphys.World(gravity=(0, -9.81, 0), frame_budget_ms=0)

    def tearDown(self):
        self.world.destroy()

    def test_parameters_and_emitters_change_at_run_time(self):
        emitter = volphys.Emitter(volphys.SphereRegion((0.5, 0.2, 0.5), 0.15), velocity=(0, 1, 0))
        fluid = self.world.create_fluid("smoke", resolution=(8, 8, 8), cell_size=0.125, emitters=[emitter])
        self.assertEqual(fluid.emitter_count, 1)
        fluid.set_emitter(0, enabled=False)
        self.world.step(DT)
        self.assertEqual(fluid.amount, 0.0)
        fluid.set_emitter(0, enabled=True, density_rate=2.0, velocity=(0, 1, 0))
        self.world.step(DT)
        self.assertGreater(fluid.amount, 0.0)
        fluid.set_parameters(kinematic_viscosity=1e-3)
        self.assertAlmostEqual(fluid.parameters.kinematic_viscosity, 1e-3)
        self.world.step(DT)
        self.assertGreater(fluid.stats().phases[volphys.Phase.Viscosity].iterations, 0)
        with self.assertRaises(volphys.InvalidArgumentError) as e:
            fluid.set_parameters(vorticity_confinement=-1)
        self.assertIn("vorticityConfinement = -1", str(e.exception))
        self.assertEqual(fluid.parameters.sides, (volphys.DomainSide.Wall,) * 6)
        fluid.set_parameters(sides=(0, 0, 0, volphys.DomainSide.Open, 0, 0))
        self.assertEqual(fluid.parameters.sides[3], volphys.DomainSide.Open)
        with self.assertRaises(volphys.InvalidArgumentError) as e:
            fluid.set_parameters(sides=(0, 0, 0, 0, 5, 0))
        self.assertIn("sides[4] = 5", str(e.exception))

    def test_smoke_from_an_emitter_fills_fields_shaped_z_y_x(self):
        # A box that is not a cube, so a transposed layout would change the shapes; the
        # emitter sits at low x and low y, so smoke there tells that [k, j, i] is (z, y, x).
        nx, ny, nz = 12, 16, 10
        h = 1.0 / 16
        emitter = volphys.Emitter(volphys.SphereRegion((2.5 * h, 3.5 * h, 5 * h), 2 * h), velocity=(0, 0.5, 0),
                                  density_rate=2.0, temperature=2.0)
        fluid = self.world.create_fluid("smoke", origin=(0, 0, 0), resolution=(nx, ny, nz), cell_size=h,
                                        density=1.2, sides={"+y": "open"}, emitters=[emitter])
        self.assertIsInstance(fluid, volphys.Fluid)
        self.assertEqual(fluid.resolution, (nx, ny, nz))
        self.assertEqual(fluid.kind, volphys.FluidKind.Smoke)
        self.assertEqual(fluid.domain, ((0.0, 0.0, 0.0), h))
        for _ in range(8):
            self.world.step(DT)
        density = fluid.smoke_density()
        self.assertEqual(density.shape, (nz, ny, nx))
        self.assertEqual(density.dtype, np.float32)
        self.assertGreater(density.max(), 0.0)
        self.assertGreater(density[:, :, :nx // 2].sum(), 10 * density[:, :, nx // 2:].sum())
        self.assertGreater(density[:, :ny // 2, :].sum(), density[:, ny // 2:, :].sum())
        self.assertEqual(fluid.temperature().shape, (nz, ny, nx))
        self.assertEqual(fluid.field("pressure").shape, (nz, ny, nx))
        np.testing.assert_array_equal(fluid.field(volphys.FluidField.SmokeDensity), density)
        # The smoke total is density * cell volume summed over the cells.
        self.assertAlmostEqual(fluid.amount, float(density.sum()) * h ** 3, delta=1e-4 * fluid.amount)

        velocity = fluid.velocity_grid()
        self.assertEqual(velocity.shape, (nz, ny, nx, 3))
        self.assertGreater(velocity[..., 1].max(), 0.1)  # the emitter pushes up
        probes = np.array([[2.5 * h, 6 * h, 5 * h], [0.5, 0.5, 0.3]], dtype=np.float32)
        sampled = fluid.sample_velocity(probes)
        self.assertEqual(sampled.shape, (2, 3))
        self.assertGreater(sampled[0, 1], 0.0)

        stats = fluid.stats()
        self.assertEqual(stats.kind, volphys.ActorKind.Fluid)
        self.assertGreater(stats.phases[volphys.Phase.Pressure].iterations, 0)
        positions, normals, triangles = fluid.surface_mesh()
        self.assertEqual(len(positions), 0)  # smoke has no surface
        self.assertEqual(self.world.fluids(), [fluid])

    def test_liquid_tank_has_a_free_surface_mesh(self):
        n, h = 16, 1.0 / 16
        fluid = self.world.create_fluid(
            "liquid", origin=(0, 0, 0), resolution=(n, n, n), cell_size=h,
            initial_liquid=[volphys.BoxRegion((0.5, 0.25, 0.5), (0.5, 0.25, 0.5))])
        for _ in range(5):
            self.world.step(DT)
        self.assertEqual(fluid.kind, volphys.FluidKind.Liquid)
        self.assertAlmostEqual(fluid.amount, 0.5, delta=0.02)
        level_set = fluid.level_set()
        self.assertEqual(level_set.shape, (n, n, n))
        self.assertLess(level_set[:, 1, :].max(), 0.0)   # inside the liquid near the floor
        self.assertGreater(level_set[:, -2, :].min(), 0.0)  # air near the top
        positions, normals, triangles = fluid.surface_mesh()
        self.assertGreater(len(triangles), 0)
        self.assertEqual(positions.shape, normals.shape)
        self.assertEqual(triangles.shape[1], 3)
        self.assertTrue(0 <= triangles.min() and triangles.max() < len(positions))
        # The free surface of a half-full tank at rest: flat at y = 0.5, normals up.
        top = positions[:, 1] > 0.3
        self.assertGreater(top.sum(), 0)
        np.testing.assert_allclose(positions[top, 1], 0.5, atol=1.5 * h)
        self.assertGreater(normals[top, 1].mean(), 0.9)

    def test_viscous_liquid_reports_its_viscosity_solve(self):
        fluid = self.world.create_fluid(
            "liquid", resolution=(8, 8, 8), cell_size=0.125, kinematic_viscosity=0.05,
            initial_liquid=[volphys.BoxRegion((0.25, 0.5, 0.5), (0.25, 0.5, 0.5))])
        for _ in range(3):  # the column starts at rest, with nothing to diffuse
            self.world.step(DT)
        self.assertGreater(fluid.stats().phases[volphys.Phase.Viscosity].iterations, 0)

    def test_bad_definitions_raise_naming_the_field_and_create_nothing(self):
        with self.assertRaises(volphys.InvalidArgumentError) as cm:
            self.world.create_fluid("smoke", resolution=(0, 16, 16))
        self.assertIn("resolution", cm.exception.message)
        with self.assertRaises(volphys.InvalidArgumentError) as cm:
            self.world.create_fluid("liquid", initial_liquid=[volphys.SphereRegion((0.5, 0.5, 0.5), -1.0)])
        self.assertIn("initialLiquid[0]", cm.exception.message)
        with self.assertRaises(volphys.InvalidArgumentError) as cm:
            self.world.create_fluid("smoke", pressure_tolerance=0.0)
        self.assertIn("pressureTolerance", cm.exception.message)
        with self.assertRaises(volphys.InvalidArgumentError) as cm:
            self.world.create_fluid("liquid", kinematic_viscosity=-0.5)
        self.assertIn("kinematicViscosity = -0.5", cm.exception.message)
        with self.assertRaises(ValueError):
            self.world.create_fluid("lava")
        with self.assertRaises(ValueError):
            self.world.create_fluid("smoke", sides={"up": "open"})
        with self.assertRaises(TypeError):
            self.world.create_fluid("smoke", viscosity=1.0)
        self.assertEqual(self.world.fluids(), [])
        with self.assertRaises(volphys.InvalidArgumentError):
            self.world.find_fluid("none")

    def test_scene_fluids_are_listed_and_found_by_name(self):
        self.world.load_scene(os.path.join(REPO, "tests", "data", "scenes", "fluid_tank.json"))
        smoke, tank = self.world.fluids()
        self.assertEqual((smoke.kind, tank.kind), (volphys.FluidKind.Smoke, volphys.FluidKind.Liquid))
        self.assertEqual(self.world.find_fluid("tank"), tank)
        self.assertEqual(tank.domain, ((0.0, 0.0, 0.0), 0.0625))
        self.assertEqual(tank.resolution, (16, 12, 16))

    def test_destroyed_fluid_raises_invalid_id(self):
        fluid = self.world.create_fluid("smoke", resolution=(4, 4, 4), cell_size=0.25)
        with fluid:
            self.assertTrue(fluid.is_valid)
        self.assertFalse(fluid.is_valid)
        with self.assertRaises(volphys.InvalidIdError):
            fluid.smoke_density()


class Errors(unittest.TestCase):
    def test_negative_radius_names_the_field(self):
        with volphys.World() as w:
            with self.assertRaises(volphys.InvalidArgumentError) as cm:
                w.create_collider(volphys.Sphere(-1.0))
            e = cm.exception
            self.assertIsInstance(e, volphys.VolPhysError)
            self.assertEqual(e.status, volphys.Status.InvalidArgument)
            self.assertIn("shape.radius", e.message)
            self.assertIn("shape.radius", str(e))
            self.assertEqual(w.colliders(), [], "a failing call changes nothing")

    def test_bad_step_and_unknown_keyword(self):
        with volphys.World() as w:
            with self.assertRaises(volphys.InvalidArgumentError) as cm:
                w.step(-1.0)
            self.assertIn("dt", cm.exception.message)
            with self.assertRaises(TypeError):
                w.create_collider(volphys.Sphere(1.0), bounciness=2)

    def test_stale_ids_raise_invalid_id(self):
        w = volphys.World()
        c = w.create_collider(volphys.Sphere(0.5))
        c.destroy()
        with self.assertRaises(volphys.InvalidIdError):
            c.pose
        with self.assertRaises(volphys.InvalidIdError):
            c.destroy()
        w.destroy()
        with self.assertRaises(volphys.InvalidIdError) as cm:
            w.step(DT)
        self.assertEqual(cm.exception.status, volphys.Status.InvalidId)
        with self.assertRaises(volphys.InvalidIdError):
            w.create_collider(volphys.Sphere(0.5))

    def test_missing_scene_is_io_error(self):
        with volphys.World() as w:
            with self.assertRaises(volphys.IoError) as cm:
                w.load_scene("/nonexistent/scene.json")
            self.assertIn("/nonexistent/scene.json", cm.exception.message)

    def test_malformed_scene_is_parse_error(self):
        import tempfile
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
            f.write('{"version": 1, "colliders": [{"shape": {"type": "sphere", "radius": "big"}}]}')
        try:
            with volphys.World() as w:
                with self.assertRaises(volphys.ParseError) as cm:
                    w.load_scene(f.name)
                self.assertIn("radius", cm.exception.message)
        finally:
            os.unlink(f.name)


class Scenes(unittest.TestCase):
    def test_default_scene_loads_and_runs(self):
        with volphys.World() as w:
            w.load_scene(DEFAULT_SCENE)
            names = ["ground", "tank_west", "tank_east", "tank_north", "tank_south", "paddle", "buoy",
                     "chimney_ball", "chimney_blade", "crate", "pill", "can", "gem"]
            self.assertEqual(len(w.colliders()), len(names))
            ball = w.find_collider("crate")
            self.assertIn(ball, w.colliders())
            y0 = ball.position[1]
            jelly = w.find_deformable("jelly")
            self.assertGreater(jelly.node_count, 0)
            for _ in range(10):
                s = w.step(DT)
            self.assertEqual(s.collider_count, len(names))
            self.assertGreaterEqual(s.actor_count, 2)
            self.assertLess(ball.position[1], y0)
            with self.assertRaises(volphys.InvalidArgumentError):
                w.find_collider("no-such-collider")
            self.assertEqual(w.deformables(), [jelly, w.find_deformable("cubic_jelly"), w.find_deformable("hanging_bar")])
            positions, normals, triangles = w.find_collider("crate").shape_mesh()
            self.assertEqual(len(positions), len(normals))
            self.assertEqual(len(triangles), 12)  # a box: two triangles per face


class Example(unittest.TestCase):
    def test_run_scene_example_prints_every_frame(self):
        script = os.path.join(REPO, "bindings", "python", "examples", "run_scene.py")
        r = subprocess.run([sys.executable, script, DEFAULT_SCENE, "--frames", "3", "--budget-ms", "0"],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = [line.split() for line in r.stdout.splitlines() if line[:5].strip().isdigit()]
        self.assertEqual([int(row[0]) for row in rows], [1, 2, 3])
        self.assertTrue(all(float(row[2]) == 0.0 for row in rows), "--budget-ms 0 must reach the world")
        self.assertIn("summary: 3 frames", r.stdout)

    def test_run_scene_example_plots_frame_times_headless(self):
        # Debian's matplotlib is installed by scripts/setup.sh: its absence is a failure here.
        import matplotlib  # noqa: F401
        script = os.path.join(REPO, "bindings", "python", "examples", "run_scene.py")
        with tempfile.TemporaryDirectory() as tmp:
            png = os.path.join(tmp, "frame_times.png")
            env = dict(os.environ, MPLBACKEND="Agg")
            env.pop("DISPLAY", None)  # headless, as in CI
            r = subprocess.run([sys.executable, script, DEFAULT_SCENE, "--frames", "5", "--plot", png],
                               capture_output=True, text=True, timeout=300, env=env)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("plot: " + png, r.stdout)
            with open(png, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
            from PIL import Image
            with Image.open(png) as img:
                self.assertGreater(len(set(img.convert("RGB").getdata())), 20, "a drawn plot, not a blank page")

    def test_run_scene_example_reports_a_missing_scene(self):
        script = os.path.join(REPO, "bindings", "python", "examples", "run_scene.py")
        r = subprocess.run([sys.executable, script, "/nonexistent.json", "--frames", "1"],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 1)
        self.assertIn("IoError", r.stderr)


class FramePlanFields(unittest.TestCase):
    """The accuracy floor and priorities of the defs, and the frame plan's statistics."""

    def setUp(self):
        self.world = volphys.World(frame_budget_ms=0)
        self.verts, self.tets = centred_cube(1, 0.4)

    def tearDown(self):
        self.world.destroy()

    def test_defaults(self):
        d = volphys._lib.vpDefaultDeformableDef()
        self.assertEqual(d.targetResidual, ctypes.c_float(1e-2).value)
        self.assertEqual(d.priority, 0)
        self.assertEqual(volphys._lib.vpDefaultFluidDef().priority, 0)
        self.assertEqual((T.VP_VERSION_MAJOR, T.VP_VERSION_MINOR), (0, 8))

    def test_priorities_and_floor_reach_the_stats(self):
        jelly = self.world.create_deformable(vertices=self.verts, tets=self.tets, target_residual=0.05, priority=5)
        smoke = self.world.create_fluid("smoke", origin=(2, 0, 0), resolution=(8, 8, 8), cell_size=0.125,
                                        priority=-4)
        step = self.world.step(DT)
        self.assertEqual(step.over_budget_ms, 0.0)  # unlimited
        self.assertFalse(step.budget_infeasible)
        self.assertGreaterEqual(step.max_slice_ms, 0.0)
        self.assertLessEqual(step.max_slice_ms, step.total_ms)
        self.assertEqual(step.fluid_interval, 1)
        rigid, by_world_jelly, by_world_smoke = self.world.actor_stats()
        self.assertEqual((rigid.priority, rigid.interval), (0, 1))
        for stats, priority in ((jelly.stats(), 5), (by_world_jelly, 5), (smoke.stats(), -4), (by_world_smoke, -4)):
            self.assertEqual(stats.priority, priority)
            self.assertEqual(stats.interval, 1)  # unbudgeted: every actor steps every frame
            self.assertIsInstance(stats.completed_step, bool)
            self.assertIsInstance(stats.floor_missed, bool)
            self.assertTrue(0.0 <= stats.progress <= 1.0, stats.progress)
            self.assertGreaterEqual(stats.slices, 0)
            self.assertGreaterEqual(stats.residual, 0.0)

    def test_actor_stats_struct_is_the_size_the_library_writes(self):
        # The library fills exactly the structSize bytes of the ctypes mirror, no more (a short
        # mirror) and no fewer (a long one).
        self.world.create_deformable(vertices=self.verts, tets=self.tets, priority=-9)
        self.world.step(DT)
        size = ctypes.sizeof(T.vpActorStats)
        buffer = (ctypes.c_uint8 * (size + 16))(*([0xAB] * (size + 16)))
        ctypes.c_uint32.from_buffer(buffer).value = size
        volphys._call("vpWorldGetActorStats", self.world.id, 1, ctypes.cast(buffer, ctypes.POINTER(T.vpActorStats)))
        self.assertEqual(list(buffer[size:]), [0xAB] * 16)
        # Every field is 4 bytes wide, so there is no padding: every word was written.
        words = [bytes(buffer[i:i + 4]) for i in range(0, size, 4)]
        self.assertNotIn(b"\xab\xab\xab\xab", words)
        stats = T.vpActorStats.from_buffer_copy(bytes(buffer[:size]))
        self.assertEqual((stats.kind, stats.priority), (int(volphys.ActorKind.Deformable), -9))

    def test_bad_values_raise_naming_the_field_and_create_nothing(self):
        cases = (
            (dict(target_residual=float("nan")), "targetResidual = nan: must be finite"),
            (dict(target_residual=0.0), "targetResidual = 0: must be >= solverTolerance = 0.001"),
            (dict(target_residual=5e-4), "targetResidual = 0.0005: must be >= solverTolerance = 0.001"),
            (dict(target_residual=2.0), "targetResidual = 2: must be finite and in [solverTolerance, 1]"),
            (dict(priority=1000001), "priority = 1000001: must be in [-1000000, 1000000]"),
        )
        for kwargs, message in cases:
            with self.assertRaises(volphys.InvalidArgumentError, msg=str(kwargs)) as cm:
                self.world.create_deformable(vertices=self.verts, tets=self.tets, **kwargs)
            self.assertIn(message, cm.exception.message)
        with self.assertRaises(volphys.InvalidArgumentError) as cm:
            self.world.create_fluid("smoke", resolution=(8, 8, 8), priority=-1000001)
        self.assertIn("priority = -1000001: must be in [-1000000, 1000000]", cm.exception.message)
        self.assertEqual(self.world.deformables(), [])
        self.assertEqual(self.world.fluids(), [])


class ImportChecks(unittest.TestCase):
    def test_struct_sizes_match_library(self):
        lib = volphys._lib
        for fn, st in (("vpDefaultWorldDef", T.vpWorldDef), ("vpDefaultStepStats", T.vpStepStats),
                       ("vpDefaultShapeDef", T.vpShapeDef), ("vpDefaultColliderDef", T.vpColliderDef),
                       ("vpDefaultDeformableDef", T.vpDeformableDef), ("vpDefaultFluidDef", T.vpFluidDef)):
            self.assertEqual(getattr(lib, fn)().structSize, ctypes.sizeof(st), st.__name__)

    def test_layout_mismatch_is_an_import_error(self):
        # The import-time check must be able to fail: give it a ShapeDef with an extra field.
        from volphys import _api
        real = T.vpShapeDef

        class Grown(ctypes.Structure):
            _fields_ = real._fields_ + [("extra", ctypes.c_int64)]

        T.vpShapeDef = Grown
        try:
            with self.assertRaises(ImportError) as cm:
                _api._check_struct_sizes()
            self.assertIn("Grown", str(cm.exception))
        finally:
            T.vpShapeDef = real
        _api._check_struct_sizes()

    def _python(self, code, env_extra):
        env = dict(os.environ, **env_extra)
        return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)

    def test_bad_library_path_names_every_place_tried(self):
        r = self._python("import volphys", {"VOLPHYS_LIBRARY": "/nonexistent/libvolphys.so"})
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("ImportError", r.stderr)
        self.assertIn("/nonexistent/libvolphys.so", r.stderr)
        self.assertIn("VOLPHYS_LIBRARY", r.stderr)

    def test_works_without_numpy(self):
        # Block numpy in a child interpreter: outputs must come back as lists of tuples.
        code = (
            "import sys; sys.modules['numpy'] = None\n"
            "import volphys\n"
            "assert not volphys.HAVE_NUMPY\n"
            "w = volphys.World(gravity=(0, -10, 0))\n"
            "v = [(0,0,0), (1,0,0), (0,1,0), (0,0,1)]\n"
            "d = w.create_deformable(vertices=v, tets=[(0,1,2,3)], position=(0, 1, 0))\n"
            "d.pin([0])\n"
            "w.step(1/60)\n"
            "p = d.positions()\n"
            "assert isinstance(p, list) and len(p) == 4 and len(p[0]) == 3, p\n"
            "assert p[0] == (0.0, 1.0, 0.0), p[0]\n"
            "assert p[3][1] < 1.0, p\n"
            "pos, nrm, tri = d.render_mesh()\n"
            "assert len(tri) == 4 and len(tri[0]) == 3, tri\n"
            "f = w.create_fluid('smoke', resolution=(3, 4, 5), cell_size=0.25)\n"
            "rho = f.smoke_density()\n"
            "assert isinstance(rho, list) and len(rho) == 60 and isinstance(rho[0], float), rho\n"
            "vel = f.velocity_grid()\n"
            "assert len(vel) == 60 and len(vel[0]) == 3, vel\n"
            "w.destroy()\n"
            "print('ok')\n")
        r = self._python(code, {})
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.strip(), "ok")


if __name__ == "__main__":
    unittest.main()
