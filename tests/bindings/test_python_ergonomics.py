"""Defaults and printing of the Python API: body types chosen from the shape and mass, and
enums that print their names while passing as ints."""
import ctypes
import unittest

import volphys
from volphys import _types as T


class DefaultBodyTypes(unittest.TestCase):
    def test_a_plane_is_static_without_saying_so(self):
        with volphys.World() as w:
            ground = w.create_collider(volphys.Plane())
            self.assertEqual(ground.body_type, volphys.BodyType.Static)
            ball = w.create_collider(volphys.Sphere(0.25), position=(0, 1, 0))
            self.assertEqual(ball.body_type, volphys.BodyType.Dynamic)
            for _ in range(120):
                w.step(1 / 60)
            self.assertAlmostEqual(ball.position[1], 0.25, delta=0.02)
            self.assertEqual(ground.position, (0.0, 0.0, 0.0))

    def test_mass_zero_is_a_static_body(self):
        with volphys.World() as w:
            box = w.create_collider(volphys.Box((0.5, 0.5, 0.5)), position=(0, 3, 0), mass=0)
            self.assertEqual(box.body_type, volphys.BodyType.Static)
            self.assertEqual(box.properties.mass, 0.0)
            w.step(1 / 60)
            self.assertEqual(box.position, (0.0, 3.0, 0.0))
            self.assertEqual(w.create_collider(volphys.Sphere(0.1), mass=2).body_type, volphys.BodyType.Dynamic)

    def test_an_explicit_body_type_wins_and_contradictions_are_refused(self):
        with volphys.World() as w:
            self.assertEqual(w.create_collider(volphys.Plane(), body_type="kinematic").body_type,
                             volphys.BodyType.Kinematic)
            with self.assertRaises(volphys.InvalidArgumentError) as cm:
                w.create_collider(volphys.Plane(), body_type="dynamic")
            self.assertIn("a plane cannot be a dynamic body", cm.exception.message)
            with self.assertRaises(volphys.InvalidArgumentError) as cm:
                w.create_collider(volphys.Sphere(0.1), body_type="dynamic", mass=0)
            self.assertIn("mass = 0", cm.exception.message)
            self.assertEqual(len(w.colliders()), 1)


class EnumsPrintTheirNames(unittest.TestCase):
    def test_str_and_format_show_the_name(self):
        self.assertEqual(str(volphys.Status.InvalidArgument), "Status.InvalidArgument")
        self.assertEqual("%s" % volphys.BodyType.Static, "BodyType.Static")
        self.assertEqual(f"{volphys.Phase.Solve}", "Phase.Solve")
        self.assertEqual(f"{volphys.FluidKind.Liquid:>20}", "    FluidKind.Liquid")
        self.assertEqual(str(volphys.QueryKind.Colliders | volphys.QueryKind.Liquids), "QueryKind.Colliders|Liquids")

    def test_every_enum_prints_its_name(self):
        enums = [getattr(T, name) for name in dir(T)]
        enums = [e for e in enums if isinstance(e, type) and issubclass(e, (T.NamedIntEnum, T.NamedIntFlag))
                 and e not in (T.NamedIntEnum, T.NamedIntFlag)]
        self.assertGreaterEqual(len(enums), 14)
        for e in enums:
            for member in e:
                self.assertEqual(str(member), "%s.%s" % (e.__name__, member.name))

    def test_they_still_pass_as_ints(self):
        s = volphys.Status.Busy
        self.assertEqual(s, 7)
        self.assertEqual("%d" % s, "7")
        self.assertEqual(f"{s:d} {s:x}", "7 7")
        self.assertEqual(s + 1, 8)
        self.assertEqual(ctypes.c_int(s).value, 7)
        self.assertEqual(volphys.status_name(s), "Busy")
        self.assertEqual(repr(s), "<Status.Busy: 7>")


if __name__ == "__main__":
    unittest.main()
