#!/usr/bin/env python3
"""Tests bench/tools/race.py: times to error inside, below and past a ladder, and the marks that the
ratios inherit from them (standard library only; the ctest bench.race runs it).

    python3 bench/tools/test_race.py
"""
import math
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

    def test_inside_interpolates_between_the_rungs_around_the_target(self):
        # A fixed 1 s per render on top of 1 s per sample: relMSE = 0.1 / spp.
        spp = [1, 2, 4, 8, 16]
        ladder = {"seconds": [1.0 + n for n in spp], "relmse": [0.1 / n for n in spp]}
        t, mark = race.time_to(ladder, 0.1 / 3)  # between the rungs of 2 and 4 spp (3 s, 5 s)
        self.assertEqual(mark, "")
        w = math.log(3 / 2) / math.log(2)  # where 1/3 lies between 1/2 and 1/4, in log
        self.assertAlmostEqual(t, math.exp(math.log(3) + w * math.log(5 / 3)))
        self.assertEqual(race.time_to(ladder, 0.1 / 16), (17.0, ""))  # exactly at the last rung

    def test_past_the_ladder_only_the_top_rungs_are_fitted(self):
        # The first rungs fall as spp^-2 (and are cheap), the last four as spp^-1.
        seconds = [1, 2, 4, 8, 16, 32, 64]
        relmse = [1.0, 0.25, 0.0625, 0.03125, 0.015625, 0.0078125, 0.00390625]
        t, mark = race.time_to({"seconds": seconds, "relmse": relmse}, 0.00390625 / 10)
        self.assertEqual(mark, "fit")
        self.assertAlmostEqual(t, 640.0)  # the tail's slope of -1, not the whole ladder's
        self.assertEqual(race.TAIL_RUNGS, 4)


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
