"""Self collision through the Python package: auto by default, off and on by name or enum, and
a value the enum does not have refused (in Python for a name, by the library naming the field
for a number that reaches it)."""
import unittest

import volphys


class SelfCollision(unittest.TestCase):
    def create(self, **keywords):
        with volphys.World() as w:
            vertices, tets = volphys.box_tet_mesh((1.0, 1.0, 1.0), (2, 2, 2))
            return w.create_deformable(vertices=vertices, tets=tets, **keywords).node_count

    def test_auto_off_and_on_are_accepted(self):
        for value in (None, "auto", "off", "on", volphys.SelfCollision.On):
            self.assertEqual(self.create(self_collision=value), 27)

    def test_an_unknown_name_is_refused(self):
        with self.assertRaises(ValueError):
            self.create(self_collision="sometimes")

    def test_the_enum_has_auto_off_and_on(self):
        self.assertEqual([int(m) for m in volphys.SelfCollision], [0, 1, 2])
        self.assertEqual(volphys.SelfCollision.Auto, 0)


if __name__ == "__main__":
    unittest.main()
