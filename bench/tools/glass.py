#!/usr/bin/env python3
"""The solid-glass scene (bench/scenes/glass.glint: a smooth and a rough refractive ball in the
Cornell box) alone against Mitsuba 3, at a small size so that it runs in minutes: the bias of
Glint's converged image against Mitsuba's (mean luminance, with its standard error from the seed
spread of both ladders scaled to the reference sample counts, as bench/tools/run.py computes it), and
the time to relMSE 1e-2 of each renderer against its own converged image (bench/tools/race.py's
log-log fit of mean relMSE against trace time over `--seeds` seeds).

The full bench (bench/run.sh) runs the same scene with its other scenes; this script is the
quick look for the glass material. It prints a Markdown section for bench/reports/RESULTS.md.

Usage: bench/.venv/bin/python bench/tools/glass.py [--glint build/glint --width 64 --ref-spp 4096
       --max-spp 256 --seeds 3 --work build-bench/glass]
"""
import argparse
import os
import sys

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import run  # noqa: E402
import race  # noqa: E402
import mitsuba_export as mx  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--glint", default=os.path.join(run.ROOT, "build", "glint"))
    ap.add_argument("--width", type=int, default=64)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--max-spp", type=int, default=256)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--work", default=os.path.join(run.ROOT, "build-bench", "glass"))
    a = ap.parse_args()
    cfg = dict(width=a.width, ref_spp=a.ref_spp, max_spp=a.max_spp, seeds=a.seeds,
               mitsuba_ref_spp=a.ref_spp, mitsuba_max_spp=a.max_spp)
    run.make_scenes.main()
    project = os.path.join(HERE, "..", "scenes", "glass.glint")
    variant, _ = run.ensure_llvm(False)
    mi = mx._mitsuba()
    mi.set_log_level(mi.LogLevel.Error)
    run.log(f"glass: {a.width} px wide, references {a.ref_spp} spp, ladders 1..{a.max_spp} spp x "
            f"{a.seeds} seeds; mitsuba {mi.__version__} {variant}")
    os.environ["GLINT"] = os.path.abspath(a.glint)  # mitsuba_export.py converts with this glint
    g = run.bench_glint("glass", project, os.path.abspath(a.glint), a.work, cfg, False)
    gs = run.summarize(g["rows"])
    m = run.bench_mitsuba("glass", project, os.path.join(a.work, "mitsuba"), cfg, g, gs)
    if not m["exported"]:
        sys.exit("glass: not exported: " + "; ".join(m["reasons"]))
    tg = race.time_to(gs, 1e-2)
    tm = race.time_to(m["summary"], 1e-2)
    r = race.ratio(tg, tm)
    within = abs(m["bias"]) <= 2 * m["sigma"]
    h, w = g["ref"].shape[:2]
    print()
    print(f"| {w}x{h}, max_bounces 12 | Glint ({g['info']['gl'].split(' on ')[-1][:40]}) | "
          f"Mitsuba {mi.__version__} {variant} independent |")
    print("| --- | --- | --- |")
    print(f"| converged image | {a.ref_spp} spp | {a.ref_spp} spp in {run.fmt_s(m['t_ref'])} |")
    print(f"| mean luminance | {m['mean_lum_glint']:.5g} | {m['mean_lum_mitsuba']:.5g} |")
    print(f"| time to relMSE 1e-2 (own reference) | {race.fmt_time(tg, run.fmt_s)} | "
          f"{race.fmt_time(tm, run.fmt_s)} |")
    print()
    print(f"Bias of Glint against Mitsuba: {m['bias']:+.3%}, standard error {m['sigma']:.3%} "
          f"({'within' if within else 'NOT within'} two standard errors). relMSE between the two "
          f"converged images {m['relmse_conv']:.3g} (noise alone about {m['noise']:.3g}). "
          f"Time ratio Glint / Mitsuba at relMSE 1e-2: {race.fmt_ratio(r)}.")
    return 0 if within else 1


if __name__ == "__main__":
    sys.exit(main())
