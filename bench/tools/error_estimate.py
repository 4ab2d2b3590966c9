#!/usr/bin/env python3
"""The error estimate and adaptive sampling on the bench scenes (bench/scenes/*.glint).

Per scene, at a small size so that it runs in a few minutes on llvmpipe:
  1. a reference: Glint at --ref-spp with a seed no other render uses (as bench/tools/run.py);
  2. a uniform render to --spp and an adaptive one (`--adaptive`) for the same time, each
     logged with `--reference --log` (true relMSE and estimated_relmse at 1, 2, 4, ... spp,
     with seconds);
  3. a plot of the estimated and the true relMSE against time, uniform and adaptive;
  4. a table: the ratio estimated / true at the last checkpoint, the relMSE of both at equal
     time (the uniform render's last time; the adaptive log, at powers of two, interpolated
     log-log, or its last row when that comes first), and the
     slope of log relMSE against log time over the checkpoints from 16 spp (-1 is Monte Carlo's
     rate; a plateau shows as a slope near 0).
The output is a Markdown section printed to stdout and the plot written to --plot.
Usage: bench/tools/error_estimate.py --glint build/glint [--width 48] [--spp 256] [--ref-spp 4096]
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))

import numpy as np  # noqa: E402

SCENES = ["cornell", "roughness_ladder", "thin_glass", "small_emitter", "env_dof",
          "huge_sphere_floor", "white_furnace", "showcase"]
REF_SEED = 1000001


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stderr}")
    return r.stderr


def read_log(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def slope(t, e, spp, from_spp=16):
    ok = (spp >= from_spp) & (t > 0) & (e > 0)
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(t[ok]), np.log(e[ok]), 1)[0])


def at_time(t, e, when):
    """relMSE at `when` seconds, interpolated log-log between checkpoints (nan outside)."""
    ok = (t > 0) & (e > 0)
    t, e = t[ok], e[ok]
    if len(t) == 0 or when < t[0] or when > t[-1]:
        return float("nan")
    return float(math.exp(np.interp(math.log(when), np.log(t), np.log(e))))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--glint", default=os.path.join(HERE, "..", "..", "build", "glint"))
    p.add_argument("--width", type=int, default=48)
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--ref-spp", type=int, default=4096)
    p.add_argument("--scenes", nargs="*", default=SCENES)
    p.add_argument("--plot", default=os.path.join(HERE, "..", "reports", "error_estimate.png"))
    a = p.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    work = tempfile.mkdtemp(prefix="glint-errest-")
    rows = []
    cols = 4
    fig, axes = plt.subplots(math.ceil(len(a.scenes) / cols), cols, figsize=(4 * cols, 3.2 * math.ceil(len(a.scenes) / cols)),
                             squeeze=False)
    for i, name in enumerate(a.scenes):
        project = os.path.join(HERE, "..", "scenes", name + ".glint")
        ref = os.path.join(work, name + "_ref.exr")
        print(f"{name}: reference {a.ref_spp} spp", file=sys.stderr, flush=True)
        run([a.glint, "render", project, "-o", ref, "--spp", str(a.ref_spp), "--seed", str(REF_SEED),
             "--width", str(a.width)])
        logs = {}
        # Uniform to --spp; adaptive for the same time (its passes skip pixels, so it would reach
        # --spp sooner), so that the two meet at equal time.
        for mode in ("uniform", "adaptive"):
            out, log = os.path.join(work, f"{name}_{mode}.exr"), os.path.join(work, f"{name}_{mode}.csv")
            limit = (["--spp", str(a.spp)] if mode == "uniform" else
                     ["--adaptive", "--time", f"{logs['uniform']['seconds'][-1]:.6f}"])
            run([a.glint, "render", project, "-o", out, "--seed", "1", "--width", str(a.width),
                 "--reference", ref, "--log", log] + limit)
            logs[mode] = read_log(log)
        ax = axes[i // cols][i % cols]
        for mode, color in (("uniform", "tab:blue"), ("adaptive", "tab:orange")):
            L = logs[mode]
            ax.loglog(L["seconds"], L["relmse"], "-o", ms=3, color=color, label=f"{mode}: true")
            ax.loglog(L["seconds"], L["estimated_relmse"], "--", color=color, label=f"{mode}: estimated")
        ax.set_title(name)
        ax.set_xlabel("seconds")
        ax.set_ylabel("relMSE")
        if i == 0:
            ax.legend(fontsize=7)
        u, ad = logs["uniform"], logs["adaptive"]
        t_end = u["seconds"][-1]
        rows.append({
            "scene": name,
            "ratio_u": u["estimated_relmse"][-1] / u["relmse"][-1] if u["relmse"][-1] > 0 else float("nan"),
            "ratio_a": ad["estimated_relmse"][-1] / ad["relmse"][-1] if ad["relmse"][-1] > 0 else float("nan"),
            "t": t_end, "u": u["relmse"][-1],
            "a": at_time(ad["seconds"], ad["relmse"], t_end) if ad["seconds"][-1] >= t_end else ad["relmse"][-1],
            "a_end": ad["relmse"][-1], "t_a_end": ad["seconds"][-1],
            "slope_u": slope(u["seconds"], u["relmse"], u["spp"]),
            "slope_a": slope(ad["seconds"], ad["relmse"], ad["spp"]),
        })
    for j in range(len(a.scenes), axes.size):
        axes[j // cols][j % cols].axis("off")
    fig.tight_layout()
    fig.savefig(a.plot, dpi=90)

    g = lambda x: "n/a" if not np.isfinite(x) else f"{x:.3g}"  # noqa: E731
    print(f"{a.width} px wide, {a.spp} spp (Sobol sampler, seed 1), reference {a.ref_spp} spp; "
          f"plot: {os.path.basename(a.plot)}\n")
    print(f"| scene | estimated / true, uniform | estimated / true, adaptive | time (uniform, {a.spp} spp) | "
          "relMSE uniform | relMSE adaptive at that time | equal-time gain | adaptive's last row "
          "(time) | slope uniform | slope adaptive |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        gain = r["u"] / r["a"] if r["a"] > 0 else float("nan")
        print(f"| {r['scene']} | {g(r['ratio_u'])} | {g(r['ratio_a'])} | {r['t']:.2f} s | {g(r['u'])} | "
              f"{g(r['a'])} | {g(gain)} | {g(r['a_end'])} ({r['t_a_end']:.2f} s) | {g(r['slope_u'])} | "
              f"{g(r['slope_a'])} |")


if __name__ == "__main__":
    main()
