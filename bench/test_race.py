#!/usr/bin/env python3
"""Tests bench/race.py: times to error inside, below and past a ladder, and the marks that the
ratios inherit from them (standard library only; the ctest bench.race runs it).

    python3 bench/test_race.py
"""
import os
import sys
import unittest

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import race  # noqa: E402

HALVING = {"seconds": [1, 2, 4], "relmse": [0.1, 0.05, 0.025]}  # relMSE = 0.1 / t


class TimeTo(unittest.TestCase):
    def test_inside_below_past_and_flat(self):
        t, mark = race.time_to(HALVING, 0.05)
        self.assertAlmostEqual(t, 2.0)
        self.assertEqual(mark, "")
        self.assertEqual(race.time_to(HALVING, 0.2), (1, "<="))
        t, mark = race.time_to(HALVING, 1e-3)
        self.assertAlmostEqual(t, 100.0)
        self.assertEqual(mark, "fit")
        flat = {"seconds": [1, 2, 4], "relmse": [0.1, 0.0999, 0.0998]}
        self.assertEqual(race.time_to(flat, 1e-3), (None, "fit: > 100 days"))
        rising = {"seconds": [1, 2, 4], "relmse": [0.1, 0.2, 0.4]}
        self.assertEqual(race.time_to(rising, 1e-3), (None, "not converging"))


class Ratio(unittest.TestCase):
    def test_marks(self):
        self.assertEqual(race.fmt_ratio(race.ratio((1.0, "<="), (4.0, ""))), "<= 0.25")
        self.assertEqual(race.fmt_ratio(race.ratio((1.0, ""), (4.0, "<="))), ">= 0.25")
        self.assertEqual(race.fmt_ratio(race.ratio((1.0, "fit"), (4.0, ""))), "0.25 (fit)")
        self.assertEqual(race.ratio((1.0, "<="), (4.0, "<="))[0], None)

    def test_goal(self):
        self.assertIs(race.meets(race.ratio((1.0, ""), (4.0, ""))), True)
        self.assertIs(race.meets(race.ratio((3.0, ""), (4.0, ""))), False)
        self.assertIs(race.meets(race.ratio((1.0, "<="), (4.0, ""))), True)    # at most 0.25
        self.assertIs(race.meets(race.ratio((3.0, ""), (4.0, "<="))), False)   # at least 0.75
        self.assertIsNone(race.meets(race.ratio((1.0, ""), (4.0, "<="))))     # at least 0.25
        self.assertIsNone(race.meets(race.ratio((3.0, "<="), (4.0, ""))))     # at most 0.75


if __name__ == "__main__":
    unittest.main()
