#!/usr/bin/env python3
"""The race on the caustic scenes alone: Glint against Mitsuba's `path` (with `independent` and
a low-discrepancy sampler) and Mitsuba's particle tracer `ptracer`, written to
bench/reports/CAUSTICS.md (RESULTS.md, which `bash bench/run.sh` writes for every scene, is left
as it is). Run it through `bash bench/run.sh --caustics [options]`.

Per scene: each renderer's converged image (Glint's, Mitsuba path's, Mitsuba ptracer's), then the
ladders of 1, 2, 4, ... spp, seed by seed, with the contenders' order rotated from one seed to
the next, so that other work on the machine falls on all of them alike; a rung's time is the
median over seeds (its error the mean). Each contender is raced against its own converged image
(bench/tools/race.py); ptracer's converged image is compared with path's, since ptracer leaves
mirrors and glass seen from the camera black, and it only counts where the two agree. The race
is also given on trimmed relMSE (a few caustic fireflies decide the plain one here). The
converged images are reused while nothing they depend on changed; the ladders are written to
caustics_results.json beside the report.
"""
import argparse
import datetime
import json
import os
import subprocess
import sys
import time

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import numpy as np  # noqa: E402

import make_scenes  # noqa: E402
import mitsuba_export as mx  # noqa: E402
import race  # noqa: E402
import run  # noqa: E402

SCENES = ("caustics", "caustics_sky", "glass")
DEFAULTS = dict(width=128, max_spp=256, ref_spp=8192, seeds=3, mitsuba_ref_spp=8192,
                mitsuba_max_spp=256)


TRIMMED_NOTE = (
    "On these scenes a path tracer's relMSE is heavy-tailed: a caustic path (camera, mirror or "
    "glass, the tiny lamp) is rare and very bright, and one such firefly in one image of one "
    "seed moves the mean relMSE of a rung by orders of magnitude, so the ladders above are not "
    "monotonic and their times hang on a few pixels. Here each image's relMSE drops its worst "
    "0.1% of pixels (bench/tools/metrics.py relmse_trimmed) before the mean over seeds; "
    "otherwise as above (same renders, same validity of ptracer). It measures the noise of the "
    "rest of the image, and leaves out the caustic fireflies that the race above charges.\n")


class LoadLog:
    """The 1-minute load average, read before and after every ladder."""

    def __init__(self):
        self.samples = []

    def read(self):
        self.samples.append(os.getloadavg()[0])

    def text(self):
        if not self.samples:
            return "not read"
        s = sorted(self.samples)
        return (f"1-minute load average over {len(s)} readings: min {s[0]:.2f}, median "
                f"{s[len(s) // 2]:.2f}, max {s[-1]:.2f} ({os.cpu_count()} logical CPUs)")


def race_scene(name, project, glint, work, cfg, ld, load):
    """One scene's results in run.py's layout (for race.rows), or None when Mitsuba cannot model
    the scene (then the reasons are logged and returned in the second item)."""
    reasons = mx.unsupported_reasons(mx.load_project(project))
    if reasons:
        return None, reasons
    ref_g, _ = run.glint_reference(project, glint, work, cfg)
    h, w = ref_g.shape[:2]
    mwork = os.path.join(work, "mitsuba")
    refs = {i: run.mitsuba_reference(project, mwork, w, h, cfg, i) for i in mx.INTEGRATORS}
    path_ref2, _ = run.mitsuba_reference(project, mwork, w, h, cfg, seed=run.MITSUBA_REF_SEED + 1)
    kinds = {"independent": ("independent", "path"), ld: (ld, "path"), "ptracer": ("independent", "ptracer")}
    scenes = {k: run.mitsuba_scene(project, mwork, w, h, s, i) for k, (s, i) in kinds.items()}
    order = ["glint"] + list(kinds)
    rows = {k: [] for k in order}
    for seed in range(1, cfg["seeds"] + 1):
        turn = order[(seed - 1) % len(order):] + order[:(seed - 1) % len(order)]
        for k in turn:
            load.read()
            if k == "glint":
                rows[k] += run.glint_ladder(project, glint, work, cfg, ref_g, seed)
            else:
                i = kinds[k][1]
                rows[k] += run.mitsuba_ladder(scenes[k][0], cfg, seed, refs[i][0], ref_g)
        load.read()
    gs = run.summarize(rows["glint"], time_stat=np.median)
    compare = {k: run.mitsuba_comparison(rows[k], cfg, refs[i][0], ref_g, gs, scenes[k][1],
                                         refs[i][1], s, i, time_stat=np.median)
               for k, (s, i) in kinds.items()}
    trimmed = {k: trimmed_summary(v) for k, v in rows.items()}
    vp = run.versus_path(refs["ptracer"][0], refs["path"][0], path_ref2)
    compare["ptracer"]["vs_path"] = vp
    run.log(f"  ptracer against path: relMSE {vp['relmse']:.3g} (path against path {vp['floor_relmse']:.3g}), "
            f"trimmed {vp['difference']:.3g} (path against path {vp['floor']:.3g})")
    return {"summary": gs, "size": (w, h), "glint": {"ref": ref_g, "rows": rows["glint"]},
            "mitsuba": compare["independent"], "mitsuba_ld": {ld: compare[ld]},
            "mitsuba_ptracer": compare["ptracer"], "rows": rows,
            "trimmed": {"summary": trimmed["glint"],
                        "mitsuba": {"exported": True, "summary": trimmed["independent"]},
                        "mitsuba_ld": {ld: {"summary": trimmed[ld]}},
                        "mitsuba_ptracer": {"exported": True, "summary": trimmed["ptracer"],
                                            "vs_path": vp}}}, None


def trimmed_summary(rows):
    """A ladder's summary with the trimmed relMSE (the worst 0.1% of pixels dropped) as its error:
    on these scenes a few caustic fireflies decide the plain mean over seeds."""
    s = run.summarize(rows, key="relmse_trimmed", time_stat=np.median)
    return {"spp": s["spp"], "seconds": s["seconds"], "relmse": s["relmse_trimmed"]}


def throughput_table(results, ld):
    """Samples per second of each contender at the top of its ladder, and the bias of Glint's
    converged image against Mitsuba path's."""
    L = ["## Throughput and agreement\n",
         "Million samples (camera paths; light paths for ptracer) per second at the top of each "
         "ladder (median time over seeds), and relMSE between Glint's converged image and "
         "Mitsuba path's beside what their noise alone would give.\n",
         f"| scene | size | Glint | path independent | path {ld} | ptracer | "
         "relMSE(Glint, path) | noise alone | mean-lum. bias Glint vs path |",
         "|---|---|---|---|---|---|---|---|---|"]
    for name, r in results.items():
        w, h = r["size"]
        rate = lambda s: s["spp"][-1] * w * h / s["seconds"][-1] / 1e6
        m = r["mitsuba"]
        L.append(f"| {name} | {w}x{h} | {rate(r['summary']):.3g} | {rate(m['summary']):.3g} | "
                 f"{rate(r['mitsuba_ld'][ld]['summary']):.3g} | "
                 f"{rate(r['mitsuba_ptracer']['summary']):.3g} | {m['relmse_conv']:.3g} | "
                 f"{m['noise']:.3g} | {m['bias']:+.2%} ± {m['sigma']:.2%} |")
    L.append("")
    return L


def write_report(path, results, refused, cfg, ld, env, command):
    L = ["# The caustic race: Glint against Mitsuba's path and particle tracers\n",
         f"Generated by `{command}` on {env['date']}; wall time {env['wall']}.\n",
         f"- machine: {env['cpu']}; Glint {env['glint']} on OpenGL {env['gl']}",
         f"- Mitsuba {env['mitsuba']} variant `{env['variant']}`",
         f"- load: {env['load']}",
         f"- width {cfg['width']} px (each scene keeps its film's aspect), {cfg['seeds']} seeds, "
         f"ladders 1 to {cfg['max_spp']} spp (Glint) and 1 to {cfg['mitsuba_max_spp']} spp "
         f"(Mitsuba) doubling, converged images at {cfg['ref_spp']} spp (Glint) and "
         f"{cfg['mitsuba_ref_spp']} spp (each Mitsuba integrator, `independent`; path twice, "
         "two seeds, for the noise floor of the ptracer check)",
         "- a rung's time is the median over seeds (the contenders' order rotates from seed to "
         "seed), its relMSE the mean; times: the trace time `glint render` reports, the time of "
         "`mi.render` (kernels compiled by a warm-up render first)\n"]
    L.append(race.markdown(race.rows(results, ld), ld, run.fmt_s))
    L.append(race.markdown(race.rows({n: r["trimmed"] for n, r in results.items()}, ld), ld,
                           run.fmt_s, heading="## The same race on trimmed relMSE", intro=TRIMMED_NOTE,
                           vs_path_table=False))
    L += throughput_table(results, ld)
    if refused:
        L.append("## Not raced\n")
        L += [f"- **{n}**: Mitsuba would not model it identically: " + "; ".join(rs[:3]) +
              (f"; and {len(rs) - 3} more" if len(rs) > 3 else "") for n, rs in refused]
        L.append("")
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")


def glint_version(glint):
    r = subprocess.run(["git", "-C", run.ROOT, "log", "-1", "--format=%h"], capture_output=True, text=True)
    built = datetime.datetime.fromtimestamp(os.path.getmtime(glint), datetime.timezone.utc)
    return (f"`{os.path.relpath(glint, run.ROOT)}` (built {built:%Y-%m-%d %H:%M} UTC; repository at "
            f"commit {r.stdout.strip() or '?'})")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", nargs="+", choices=run.SCENES, default=list(SCENES))
    ap.add_argument("--glint", default=os.path.join(run.ROOT, "build", "glint"))
    ap.add_argument("--out", default=os.path.join(run.REPORTS, "CAUSTICS.md"))
    ap.add_argument("--work", default=os.path.join(run.ROOT, "build-bench", "caustics"))
    ap.add_argument("--ld-sampler", default="orthogonal", choices=mx.SAMPLERS[1:],
                    help="Mitsuba's low-discrepancy sampler for path (default: orthogonal, the "
                         "winner of RESULTS.md's equal-spp trial)")
    for k, v in DEFAULTS.items():
        ap.add_argument("--" + k.replace("_", "-"), type=int, default=v, help=f"(default {v})")
    a = ap.parse_args()
    cfg = {k: getattr(a, k) for k in DEFAULTS}
    glint = os.path.abspath(a.glint)
    if not os.path.exists(glint):
        sys.exit(f"bench: {glint} not found (bash scripts/build.sh)")
    os.environ["GLINT"] = glint
    make_scenes.main()
    t0 = time.time()
    variant, _ = run.ensure_llvm(True)
    mi = mx._mitsuba()
    mi.set_log_level(mi.LogLevel.Error)
    load = LoadLog()
    results, refused, gl = {}, [], "?"
    for name in a.scenes:
        run.log(name)
        project = os.path.join(make_scenes.SCENES, name + ".glint")
        r, reasons = race_scene(name, project, glint, os.path.join(a.work, name), cfg, a.ld_sampler, load)
        if r is None:
            run.log("  not raced: " + "; ".join(reasons[:2]))
            refused.append((name, reasons))
            continue
        results[name] = r
        gl = run.glint_render(glint, project, os.path.join(a.work, "probe.exr"), 1, 1, 8)["gl"]
    env = {"date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), "wall": run.fmt_s(time.time() - t0),
           "cpu": run.machine_info(None), "glint": glint_version(glint), "gl": gl,
           "mitsuba": mi.__version__, "variant": variant, "load": load.text()}
    command = "bash bench/run.sh --caustics " + " ".join(sys.argv[1:])
    write_report(a.out, results, refused, cfg, a.ld_sampler, env, command.strip())
    # The raw ladders beside the report, for re-reading without re-rendering.
    raw = os.path.join(os.path.dirname(a.out), "caustics_results.json")
    with open(raw, "w") as f:
        json.dump({"config": cfg, "env": env, "ld_sampler": a.ld_sampler,
                   "scenes": {n: {"rows": r["rows"], "ptracer_vs_path": r["mitsuba_ptracer"]["vs_path"]}
                              for n, r in results.items()}}, f, indent=1)
    run.log(f"wrote {a.out} in {env['wall']}; {env['load']}")


if __name__ == "__main__":
    main()
