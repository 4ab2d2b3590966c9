#!/usr/bin/env python3
"""Tests bench/tools/backends.py's detection and table against stand-ins for `glint`: one whose
`render --help` has no --backend (the table is left out, with the note), one whose help has it
and whose renders print the CLI's "wrote" line (both back ends are raced, interleaved).

    python3 bench/tools/test_backends.py        (the ctest bench.backends runs it)
"""
import os
import stat
import sys
import tempfile
import unittest

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import backends  # noqa: E402

FAKE = """#!/bin/sh
# A stand-in for glint: `render --help` prints HELP; a render logs its back end and prints the line
# run.py parses, at RATE_fragment or RATE_compute spp/s.
if [ "$2" = "--help" ]; then printf '%s\\n' "usage: glint render PROJECT -o OUT {help}"; exit 0; fi
backend=fragment
for a in "$@"; do [ "$prev" = "--backend" ] && backend=$a; prev=$a; done
echo "$backend" >> "{log}"
if [ "$backend" = compute ]; then rate=40.0; else rate=10.0; fi
echo "glint: wrote out (8x4, 16 spp, 0.10 s, $rate spp/s, 0.01 Msamples/s)" >&2
"""


def fake_render(glint, project, out, spp, seed, width, extra=()):
    """run.py's glint_render without numpy: runs the stand-in, parses the spp/s."""
    import re
    import subprocess
    r = subprocess.run([glint, "render", project, "-o", out, "--spp", str(spp)] + list(extra),
                       capture_output=True, text=True, check=True)
    m = re.search(r"\((\d+)x(\d+), (\d+) spp, ([0-9.]+) s, ([0-9.]+) spp/s", r.stderr)
    return {"width": int(m.group(1)), "height": int(m.group(2)), "spp": int(m.group(3)),
            "seconds": int(m.group(3)) / float(m.group(5))}


class Detection(unittest.TestCase):
    def make(self, help_text):
        d = tempfile.mkdtemp(prefix="glint_fake_")
        path, log = os.path.join(d, "glint"), os.path.join(d, "calls.log")
        with open(path, "w") as f:
            f.write(FAKE.replace("{help}", help_text).replace("{log}", log))
        os.chmod(path, os.stat(path).st_mode | stat.S_IEXEC)
        return path, log

    def test_absent(self):
        glint, _ = self.make("[--spp N] [--sampler pcg|sobol] [--accel auto|loop|bvh]")
        self.assertEqual(backends.available(glint), ())
        text = "\n".join(backends.table([], False))
        self.assertIn("does not mention `--backend`", text)
        self.assertNotIn("|", text)

    def test_present(self):
        glint, log = self.make("[--backend fragment|compute|auto]")
        self.assertEqual(backends.available(glint), ("fragment", "compute"))
        rows = backends.measure(fake_render, glint, [("s", "s.glint")], os.path.dirname(log),
                                8, 16, 3, log=lambda m: None)
        with open(log) as f:
            calls = f.read().split()
        self.assertEqual(calls, ["fragment", "compute"] * 3)  # interleaved
        self.assertAlmostEqual(rows[0]["spp_per_s"]["fragment"], 10.0)
        self.assertAlmostEqual(rows[0]["spp_per_s"]["compute"], 40.0)
        text = "\n".join(backends.table(rows, True))
        self.assertIn("| s | 8x4 | 16 | 10 | 40 | 4.00 | n/a |", text)


if __name__ == "__main__":
    unittest.main()
