"""volphys.box_tet_mesh (vpBoxTetMesh): the arrays, the box they fill, and refused arguments."""
import itertools
import os
import subprocess
import sys
import unittest

import numpy as np

import volphys


def signed_volumes(vertices, tets):
    p = vertices.astype(np.float64)[tets]
    return np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0])) / 6.0


class BoxTetMesh(unittest.TestCase):
    def test_lattice_vertices_and_positive_tets_filling_the_box(self):
        size, cells, corner = (1.5, 0.8, 0.6), (3, 2, 2), (-1.0, 2.0, 0.5)
        vertices, tets = volphys.box_tet_mesh(size, cells, min_corner=corner)
        self.assertEqual((vertices.dtype, vertices.shape), (np.float32, (4 * 3 * 3, 3)))
        self.assertEqual((tets.dtype, tets.shape), (np.int32, (6 * 3 * 2 * 2, 4)))
        # x fastest: vertex (i, j, k) at i + 4 (j + 3 k).
        lattice = np.array([(i, j, k) for k, j, i in itertools.product(range(3), range(3), range(4))], dtype=np.float64)
        expected = np.float32(corner) + np.float32(size) * lattice / np.array(cells)
        np.testing.assert_allclose(vertices, expected, rtol=0, atol=1e-6)
        volumes = signed_volumes(vertices, tets)
        box_volume = 1.5 * 0.8 * 0.6
        np.testing.assert_allclose(volumes, box_volume / tets.shape[0], rtol=1e-5)
        self.assertAlmostEqual(float(volumes.sum()), box_volume, delta=1e-6 * box_volume)

    def test_default_corner_is_the_origin_and_the_mesh_makes_a_deformable(self):
        vertices, tets = volphys.box_tet_mesh((1, 2, 3), (1, 1, 1))
        np.testing.assert_array_equal(vertices.min(axis=0), (0, 0, 0))
        np.testing.assert_array_equal(vertices.max(axis=0), (1, 2, 3))
        with volphys.World() as w:
            d = w.create_deformable(vertices=vertices, tets=tets)
            self.assertEqual(d.node_count, 8)

    def test_bad_arguments_name_the_field(self):
        for kwargs, message in (
                (dict(size=(1, 1, 1), cells=(2, 0, 2)), "cells[1] = 0: must be in [1, 512]"),
                (dict(size=(1, 1, 1), cells=(512, 512, 9)), "cells = (512, 512, 9): 2359296 cells, at most 2097152"),
                (dict(size=(1, -2, 1), cells=(1, 1, 1)), "size.y = -2"),
                (dict(size=(1, 1, 1), cells=(1, 1, 1), min_corner=(float("nan"), 0, 0)), "minCorner = (nan, 0, 0)")):
            with self.assertRaises(volphys.InvalidArgumentError, msg=message) as cm:
                volphys.box_tet_mesh(**kwargs)
            self.assertIn(message, cm.exception.message)
        # What ctypes would silently truncate or wrap is refused before the call.
        for cells, message in (((1.5, 1, 1), "cells[0] = 1.5: expected an integer"),
                               ((1, 2 ** 32, 1), "cells[1] = 4294967296: out of int32 range"),
                               ((1, 1), "cells: expected 3 integers")):
            with self.assertRaises(ValueError, msg=message) as cm:
                volphys.box_tet_mesh((1, 1, 1), cells)
            self.assertIn(message, str(cm.exception))
        self.assertEqual(volphys.box_tet_mesh((1, 1, 1), np.array([1, 1, 2]))[1].shape, (12, 4))

    def test_lists_of_tuples_without_numpy(self):
        code = ("import sys; sys.modules['numpy'] = None\n"
                "import volphys\n"
                "v, t = volphys.box_tet_mesh((2, 1, 1), (2, 1, 1))\n"
                "assert v[:3] == [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (2.0, 0.0, 0.0)], v\n"
                "assert len(v) == 12 and len(t) == 12 and all(len(x) == 4 for x in t), t\n"
                "print('ok')\n")
        r = subprocess.run([sys.executable, "-c", code], env=dict(os.environ), capture_output=True, text=True,
                           timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.strip(), "ok")


if __name__ == "__main__":
    unittest.main()
