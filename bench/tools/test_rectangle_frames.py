#!/usr/bin/env python3
"""Tests bench/tools/rectangle_frames.py: `glint convert`'s mirrored rectangle matrices become
right-handed with the same corners and the same normal; right-handed ones stay as they are
(standard library only; the ctest bench.rectangle_frames runs it).

    python3 bench/tools/test_rectangle_frames.py
"""
import os
import sys
import unittest

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import rectangle_frames as rf  # noqa: E402


def apply(m, p):
    return tuple(sum(m[r][c] * (list(p) + [1.0])[c] for c in range(4)) for r in range(3))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normal(m):
    """Mitsuba's rectangle normal: the inverse transpose of the 3x3 block applied to (0, 0, 1),
    which is (x cross y) / det for the columns x, y."""
    x = [m[r][0] for r in range(3)]
    y = [m[r][1] for r in range(3)]
    det = rf.determinant3(m)
    return tuple(v / det for v in cross(x, y))


def corners(m):
    return sorted(apply(m, (u, v, 0.0)) for u in (-1.0, 1.0) for v in (-1.0, 1.0))


# The floor of bench/scenes/caustics.glint as `glint convert` writes it: corners (-4, 0, -4),
# (-4, 0, 4), (4, 0, -4), (4, 0, 4); x = (p2 - p0) / 2, y = (p1 - p0) / 2, z = up.
FLOOR = [[4, 0, 0, 0], [0, 0, 1, 0], [0, 4, 0, 0], [0, 0, 0, 1]]


class RightHanded(unittest.TestCase):
    def test_a_mirrored_rectangle_keeps_its_corners_and_normal(self):
        self.assertLess(rf.determinant3(FLOOR), 0)
        fixed = rf.right_handed(FLOOR)
        self.assertGreater(rf.determinant3(fixed), 0)
        self.assertEqual(corners(fixed), corners(FLOOR))
        self.assertEqual(normal(fixed), normal(FLOOR))
        self.assertEqual(normal(fixed), (0.0, 1.0, 0.0))  # the floor's front faces up
        self.assertEqual(fixed[3], [0.0, 0.0, 0.0, 1.0])

    def test_a_translated_wall_keeps_its_corners_and_normal(self):
        wall = [[4, 0, 0, 0], [0, 2, 0, 2], [0, 0, -1, -1.2], [0, 0, 0, 1]]  # caustics.glint's wall
        fixed = rf.right_handed(wall)
        self.assertGreater(rf.determinant3(fixed), 0)
        self.assertEqual(corners(fixed), corners(wall))
        self.assertEqual(normal(fixed), normal(wall))

    def test_a_right_handed_matrix_is_left_alone(self):
        m = [[0, 0, 2, 1], [3, 0, 0, 2], [0, 1, 0, 3], [0, 0, 0, 1]]
        self.assertGreater(rf.determinant3(m), 0)
        self.assertEqual(rf.right_handed(m), [[float(v) for v in row] for row in m])


if __name__ == "__main__":
    unittest.main()
