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


def ladder(seconds_per_spp, error_at_one_spp):
    """A ladder of 1 to 64 spp whose relMSE falls as 1/spp."""
    spp = [1, 2, 4, 8, 16, 32, 64]
    return {"spp": spp, "seconds": [n * seconds_per_spp for n in spp],
            "relmse": [error_at_one_spp / n for n in spp]}


def scene(ptracer_vs_path, ptracer_seconds_per_spp=0.001):
    """One scene's results as run.py and caustic_race.py hold them: Glint reaches relMSE 1e-2 in
    1 s and 1e-3 in 10 s; path (independent) in 4 s and 40 s, path (orthogonal) in 8 s and 80 s;
    ptracer at `ptracer_seconds_per_spp` (its 1 spp error 0.1, as path's)."""
    return {"summary": ladder(0.1, 0.1),
            "mitsuba": {"exported": True, "summary": ladder(0.4, 0.1)},
            "mitsuba_ld": {"orthogonal": {"summary": ladder(0.8, 0.1)}},
            "mitsuba_ptracer": {"exported": True, "summary": ladder(ptracer_seconds_per_spp, 0.1),
                                "vs_path": ptracer_vs_path}}


def versus(difference, floor):
    return {"difference": difference, "floor": floor, "relmse": difference * 1.5,
            "floor_relmse": floor * 1.5, "mean_bias": -0.05}


AGREES = versus(2e-4, 1e-4)        # valid at 1e-2 and 1e-3
BLACK_GLASS = versus(0.08, 1e-4)   # ptracer's black glass: valid at neither
NOISY_PATH = versus(0.02, 0.015)   # path's own images disagree by 0.015


class Contenders(unittest.TestCase):
    def test_valid_at(self):
        self.assertTrue(race.valid_at(None, 1e-3))  # path itself
        self.assertTrue(race.valid_at(AGREES, 1e-3))
        self.assertFalse(race.valid_at(BLACK_GLASS, 1e-2))
        # The difference beyond the floor (0.005) is below 1e-2, but the floor is not: path's
        # converged image cannot tell at that precision.
        self.assertFalse(race.valid_at(NOISY_PATH, 1e-2))
        self.assertTrue(race.valid_at(NOISY_PATH, 0.1))
        self.assertFalse(race.valid_at({"difference": float("nan"), "floor": 0.0}, 1.0))
        self.assertFalse(race.valid_at({"difference": 0.0}, 1.0))  # no floor: not shown

    def test_best_is_the_fastest_valid_contender_with_a_time(self):
        times = {"independent": (4.0, ""), "orthogonal": (3.0, "fit"), "ptracer": (1.0, ""),
                 "other": (None, "not converging")}
        valid = {"independent": True, "orthogonal": True, "ptracer": False, "other": True}
        self.assertEqual(race.best(times, valid), "orthogonal")
        self.assertEqual(race.best(times, dict(valid, ptracer=True)), "ptracer")
        self.assertIsNone(race.best({"ptracer": (1.0, "")}, {"ptracer": False}))

    def test_verdict_over_the_valid_contenders(self):
        self.assertEqual(race.verdict([(0.25, ""), (0.4, "")]), "yes")
        self.assertEqual(race.verdict([(0.25, ""), (0.6, "")]), "no")
        self.assertEqual(race.verdict([(0.25, ""), (0.6, "fit")]), "no (fit)")
        self.assertEqual(race.verdict([(0.25, ""), (0.3, ">=")]), "unknown")
        self.assertEqual(race.verdict([]), "unknown")

    def test_an_invalid_ptracer_is_shown_but_not_raced(self):
        row = race.rows({"caustics": scene(BLACK_GLASS)}, "orthogonal")[0]
        t = row["targets"][1e-2]
        self.assertAlmostEqual(t["ptracer"][0], 0.01)        # ten times faster than Glint...
        self.assertFalse(t["valid"]["ptracer"])              # ...to another image
        self.assertEqual(t["best"], "independent")
        self.assertAlmostEqual(t["ratio_best"][0], 0.25)
        self.assertEqual(t["verdict"], "yes")                # 0.25 and 0.125 against path
        text = race.markdown([row], "orthogonal", lambda s: f"{s:g} s")
        self.assertIn("| caustics | 1 s | 4 s | 0.25 | 8 s | 0.13 | 0.01 s | 100.00 (not valid) | "
                      "independent | 0.25 | yes |", text)
        self.assertIn("| caustics | 0.12 | 0.00015 | 0.08 | 0.0001 | -5.00% | no | no |", text)

    def test_a_valid_faster_ptracer_decides(self):
        row = race.rows({"caustics": scene(AGREES, 0.01)}, "orthogonal")[0]
        t = row["targets"][1e-3]
        self.assertEqual(t["best"], "ptracer")
        self.assertAlmostEqual(t["ratio_best"][0], 10.0)
        self.assertEqual(t["verdict"], "no (fit)")  # Glint's 1e-3 is past its ladder

    def test_scenes_without_ptracer_keep_two_contenders(self):
        r = scene(None)
        del r["mitsuba_ptracer"]
        row = race.rows({"cornell": r}, "orthogonal")[0]
        self.assertNotIn("ptracer", row["targets"][1e-2])
        self.assertEqual(row["targets"][1e-2]["best"], "independent")
        self.assertNotIn("ptracer", race.markdown([row], "orthogonal", str))


if __name__ == "__main__":
    unittest.main()
