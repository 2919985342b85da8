"""The surface mesher choice through the Python package: isosurface stuffing by default, the
voxel mesher on request, a name the enum does not have refused in Python, and mesh_grading
(levels of coarsening inside, for stuffing) passed through and checked by the library."""
import os
import tempfile
import unittest

import volphys

# The box [0, 1] x [0, 1] x [0, 0.5] as an OBJ surface, counter-clockwise seen from outside.
BOX_OBJ = ("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 0.5\nv 1 0 0.5\nv 1 1 0.5\nv 0 1 0.5\n"
           "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\n"
           "f 2 3 7\nf 2 7 6\n")


class SurfaceMesher(unittest.TestCase):
    def setUp(self):
        fd, self.path = tempfile.mkstemp(suffix=".obj")
        with os.fdopen(fd, "w") as f:
            f.write(BOX_OBJ)

    def tearDown(self):
        os.unlink(self.path)

    def quality(self, **keywords):
        with volphys.World() as w:
            return w.create_deformable(surface_file=self.path, voxel_resolution=6, **keywords).mesh_quality()

    def test_stuffing_is_the_default_and_keeps_the_volume(self):
        by_default = self.quality()
        stuffed = self.quality(surface_mesher="stuffing")
        self.assertEqual(by_default, stuffed)
        self.assertAlmostEqual(stuffed.tet_volume, 0.5, places=5)
        self.assertAlmostEqual(stuffed.surface_volume, 0.5, places=5)
        self.assertGreater(stuffed.min_dihedral, 10.7)

    def test_voxel_on_request(self):
        voxel = self.quality(surface_mesher=volphys.SurfaceMesher.Voxel)
        self.assertAlmostEqual(voxel.min_dihedral, 45.0, places=3)
        self.assertAlmostEqual(voxel.max_dihedral, 90.0, places=3)
        self.assertGreaterEqual(voxel.tet_volume, 0.5 - 1e-6)

    def test_an_unknown_mesher_is_refused(self):
        with self.assertRaises(ValueError):
            self.quality(surface_mesher="octree")

    def test_mesh_grading_keeps_the_volume_and_is_checked(self):
        with volphys.World() as w:
            graded = w.create_deformable(surface_file=self.path, voxel_resolution=24, mesh_grading=2).mesh_quality()
        self.assertAlmostEqual(graded.tet_volume, 0.5, places=5)
        self.assertGreater(graded.min_dihedral, 10.7)
        with self.assertRaises(volphys.InvalidArgumentError) as raised:
            self.quality(mesh_grading=9)
        self.assertIn("meshGrading = 9", str(raised.exception))


if __name__ == "__main__":
    unittest.main()
