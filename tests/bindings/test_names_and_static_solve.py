"""Actor names from a scene file, the mesh quality report and the static solve, through the
Python package."""
import os
import tempfile
import unittest

import volphys

SCENE = """{"colliders": [{"name": "ground", "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}},
                          {"shape": {"type": "sphere", "radius": 0.2}, "position": [3, 1, 0]}],
            "deformables": [{"name": "jelly", "degree": 2, "box": {"cells": [2, 2, 2], "size": [0.4, 0.4, 0.4]},
                             "position": [0, 0.3, 0], "youngsModulus": 1e5}],
            "fluids": [{"name": "tank", "kind": "liquid", "origin": [5, 0, 0], "resolution": [4, 4, 4]}]}"""


class NamesAndStaticSolve(unittest.TestCase):
    def setUp(self):
        fd, self.path = tempfile.mkstemp(suffix=".json")
        with os.fdopen(fd, "w") as f:
            f.write(SCENE)

    def tearDown(self):
        os.unlink(self.path)

    def test_names_come_from_the_scene(self):
        with volphys.World() as w:
            w.load_scene(self.path)
            self.assertEqual([c.name for c in w.colliders()], ["ground", ""])
            self.assertEqual(w.find_deformable("jelly").name, "jelly")
            self.assertEqual(w.find_fluid("tank").name, "tank")

    def test_solve_static_lands_the_jelly_at_rest(self):
        with volphys.World(frame_budget_ms=0) as w:
            w.load_scene(self.path)
            jelly = w.find_deformable("jelly")
            iterations, residual = jelly.solve_static(max_iterations=200, tolerance=1e-4)
            self.assertGreater(iterations, 0)
            self.assertLessEqual(residual, 1e-4)
            lowest = min(p[1] for p in jelly.positions())
            self.assertGreaterEqual(lowest, -1e-5)
            self.assertLess(lowest, 0.01)
            self.assertTrue(all(v == 0 for p in jelly.velocities() for v in p))

    def test_mesh_quality_of_the_box_jelly(self):
        with volphys.World() as w:
            w.load_scene(self.path)
            q = w.find_deformable("jelly").mesh_quality()
            self.assertAlmostEqual(q.min_dihedral, 45.0, places=3)
            self.assertAlmostEqual(q.max_dihedral, 90.0, places=3)
            self.assertAlmostEqual(q.tet_volume, 0.064, places=5)
            self.assertAlmostEqual(q.surface_volume, 0.064, places=5)

    def test_not_converging_raises_and_changes_nothing(self):
        with volphys.World(frame_budget_ms=0) as w:
            w.load_scene(self.path)
            jelly = w.find_deformable("jelly")
            before = [tuple(p) for p in jelly.positions()]
            with self.assertRaises(volphys.NotConvergedError) as cm:
                jelly.solve_static(max_iterations=1, tolerance=1e-9)
            self.assertEqual(cm.exception.status, volphys.Status.NotConverged)
            self.assertIn("unchanged", cm.exception.message)
            self.assertEqual([tuple(p) for p in jelly.positions()], before)
            with self.assertRaises(volphys.InvalidArgumentError):
                jelly.solve_static(max_iterations=0)


if __name__ == "__main__":
    unittest.main()
