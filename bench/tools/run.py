#!/usr/bin/env python3
"""Glint's speed-against-error benchmark. Run it through bench/run.sh.

For each bench scene (bench/scenes/*.glint, written by make_scenes.py):
  1. a reference: Glint itself at --ref-spp samples per pixel with a seed no test render uses;
  2. renders at 1, 2, 4, ... --max-spp samples per pixel with --seeds seeds; each is its own
     `glint render` (its trace time is the one the CLI reports, excluding start-up and shader
     compilation), and relMSE (epsilon 0.01, as renderer/image_metrics.h), trimmed relMSE, MAPE,
     mean bias and HDR-FLIP against the reference are computed here; when the CLI has
     `--reference/--log`, one logged render per seed at --max-spp is added and its CSV is
     checked against these numbers;
  3. for the scenes the exporter accepts, Mitsuba 3 (path integrator, same resolution, CPU):
     a converged image (--mitsuba-ref-spp) for the bias of Glint's reference against it, and
     its own 1, 2, 4, ... --mitsuba-max-spp ladder for the equal-time error ratio; on the
     caustic scenes (PTRACER_SCENES) also the particle tracer, with its own converged image and
     ladder, and a second path image for the check that ptracer converges to path's image;
  4. bench/reports/RESULTS.md with log-log plots, fitted slopes, the time to reach relMSE 1e-1, 1e-2
     and 1e-3, samples per second, and the Mitsuba comparison.
"""
import argparse
import csv
import datetime
import glob
import json
import math
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ in the repository
HERE = os.path.dirname(os.path.abspath(__file__))  # bench/tools
BENCH = os.path.dirname(HERE)
REPORTS = os.path.join(BENCH, "reports")
ROOT = os.path.dirname(BENCH)
sys.path.insert(0, HERE)

import numpy as np  # noqa: E402

import ablation  # noqa: E402
import backends  # noqa: E402
import horizon_check  # noqa: E402
import make_scenes  # noqa: E402
import metrics  # noqa: E402
import mitsuba_export as mx  # noqa: E402
import mitsuba_samplers  # noqa: E402
import race  # noqa: E402

SCENES = ["cornell", "roughness_ladder", "thin_glass", "small_emitter", "env_dof",
          "huge_sphere_floor", "white_furnace", "glass", "showcase", "caustics", "caustics_sky"]
# The scenes where Mitsuba's particle tracer races too: light focused by glass and mirrors.
PTRACER_SCENES = ("caustics", "caustics_sky", "glass")
TARGETS = [1e-1, 1e-2, 1e-3]
REF_SEED = 1000001
MITSUBA_REF_SEED = 2000001

FULL = dict(width=128, max_spp=256, ref_spp=4096, seeds=3, mitsuba_ref_spp=4096,
            mitsuba_max_spp=256, ablation_spp=64, ablation_seeds=2, backend_spp=64, backend_repeats=3)
QUICK = dict(width=32, max_spp=16, ref_spp=256, seeds=3, mitsuba_ref_spp=256, mitsuba_max_spp=16,
             ablation_spp=4, ablation_seeds=1, backend_spp=4, backend_repeats=1)
# The per-sample gain of Glint's Sobol sampler over PCG on the direct-light Cornell box
# (bench/tools/qmc_gain.py; Burley 2020, JCGT 9(4), Fig. 1 reports about 12x in RMSE at 16 spp).
QMC_ARGS = {"full": ["--ref-spp", "4096", "--seeds", "12", "--spp", "4", "16", "64"],
            "quick": ["--ref-spp", "256", "--seeds", "3", "--spp", "4", "16", "--size", "32"]}
# Sample counts of the equal-spp trial of Mitsuba's samplers (bench/tools/mitsuba_samplers.py).
TRIAL_SPP = {"full": (16, 64), "quick": (4, 8)}


def log(msg):
    print(msg, flush=True)


# --------------------------------------------------------------------------------------------
# Glint

WROTE = re.compile(r"wrote .* \((\d+)x(\d+), (\d+) spp, ([0-9.]+) s, ([0-9.]+) spp/s")


def glint_render(glint, project, out, spp, seed, width, extra=()):
    cmd = [glint, "render", project, "-o", out, "--spp", str(spp), "--seed", str(seed),
           "--width", str(width), "--verbose"] + list(extra)  # --verbose: the OpenGL line
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stderr}")
    m = WROTE.search(r.stderr)
    if not m:
        raise RuntimeError(f"cannot parse the render time from:\n{r.stderr}")
    gl = re.search(r"glint: OpenGL (.*)", r.stderr)
    return {"width": int(m.group(1)), "height": int(m.group(2)), "spp": int(m.group(3)),
            # The CLI prints seconds to 10 ms; spp / (spp/s, printed to 0.1) is finer for short renders.
            "seconds": int(m.group(3)) / float(m.group(5)) if float(m.group(5)) > 0 else float(m.group(4)),
            "gl": gl.group(1) if gl else "?"}


def cli_has_log(glint):
    r = subprocess.run([glint, "render", "--help"], capture_output=True, text=True)
    return "--log" in r.stdout and "--reference" in r.stdout


# --------------------------------------------------------------------------------------------
# Fits

def loglog_fit(x, y):
    """log y = a + b log x, least squares over finite positive points; returns (a, b) or None."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = (x > 0) & (y > 0) & np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 2:
        return None
    b, a = np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)
    return float(a), float(b)


def fit_eval(fit, x):
    return math.exp(fit[0] + fit[1] * math.log(x))


def time_to(summary, target):
    """The time to `target` as bench/tools/race.py reads it from a ladder, as text: interpolated
    between the rungs around it, "<= first rung", or past the last rung "not reached" with the
    extrapolation of the top rungs' fit."""
    t, mark = race.time_to(summary, target)
    if t is None:
        return {"no fit": "n/a", "not converging": "not reached"}.get(mark, f"not reached ({mark})")
    if mark == "<=":
        return f"<= {fmt_s(t)}"
    return f"not reached (fit: {fmt_s(t)})" if mark == "fit" else fmt_s(t)


def fmt_s(t):
    if t < 1:
        return f"{t * 1000:.0f} ms" if t >= 0.01 else f"{t * 1000:.1f} ms"
    if t < 120:
        return f"{t:.1f} s"
    if t < 7200:
        return f"{t / 60:.1f} min"
    return f"{t / 3600:.1f} h"


def g3(x):
    return "n/a" if x is None or not np.isfinite(x) else f"{x:.3g}"


# --------------------------------------------------------------------------------------------
# One scene

def ladder(max_spp):
    out, s = [], 1
    while s <= max_spp:
        out.append(s)
        s *= 2
    return out


def glint_ladder(project, glint, work, cfg, ref, seed):
    """One seed's renders at 1, 2, 4, ... max_spp, each against Glint's reference `ref`."""
    rows = []
    for spp in ladder(cfg["max_spp"]):
        out = os.path.join(work, f"s{seed}_{spp}.exr")
        r = glint_render(glint, project, out, spp, seed, cfg["width"])
        img = metrics.read_exr(out)
        rows.append({"seed": seed, "spp": spp, "seconds": r["seconds"],
                     "relmse": metrics.relmse(img, ref),
                     "relmse_trimmed": metrics.relmse_trimmed(img, ref),
                     "mape": metrics.mape(img, ref), "mean_bias": metrics.mean_bias(img, ref),
                     "flip": metrics.flip(img, ref), "mean_lum": metrics.mean_lum(img),
                     "nonfinite": int(np.sum(~np.isfinite(img)))})
        if spp != cfg["max_spp"]:
            os.remove(out)
    last = rows[-1]
    log(f"  seed {seed}: {cfg['max_spp']} spp in {fmt_s(last['seconds'])}, relMSE "
        f"{last['relmse']:.3g}, FLIP {last['flip']:.3g}")
    return rows


def glint_reference(project, glint, work, cfg):
    """Glint's converged image (reused while the project, counts and binary are unchanged):
    (image, the render's info)."""
    os.makedirs(work, exist_ok=True)
    ref_path = os.path.join(work, "reference.exr")
    meta_path = os.path.join(work, "reference.json")
    key = {"project": open(project).read(), "spp": cfg["ref_spp"], "width": cfg["width"],
           "glint_mtime": os.path.getmtime(glint)}
    if os.path.exists(ref_path) and os.path.exists(meta_path) and json.load(open(meta_path))["key"] == key:
        info = json.load(open(meta_path))["info"]
        log(f"  reference: reused {ref_path}")
    else:
        info = glint_render(glint, project, ref_path, cfg["ref_spp"], REF_SEED, cfg["width"])
        json.dump({"key": key, "info": info}, open(meta_path, "w"))
        log(f"  reference: {cfg['ref_spp']} spp in {fmt_s(info['seconds'])}")
    return metrics.read_exr(ref_path), info


def bench_glint(name, project, glint, work, cfg, has_log):
    ref, info = glint_reference(project, glint, work, cfg)
    ref_path = os.path.join(work, "reference.exr")
    rows = []
    for seed in range(1, cfg["seeds"] + 1):
        rows += glint_ladder(project, glint, work, cfg, ref, seed)
    logcheck = None
    if has_log:
        logcheck = []
        for seed in range(1, cfg["seeds"] + 1):
            csv_path = os.path.join(work, f"log_s{seed}.csv")
            glint_render(glint, project, os.path.join(work, f"log_s{seed}.exr"), cfg["max_spp"],
                         seed, cfg["width"], ["--reference", ref_path, "--log", csv_path])
            with open(csv_path) as f:
                logcheck.append(list(csv.DictReader(f)))
    return {"info": info, "ref": ref, "rows": rows, "log": logcheck}


def summarize(rows, key="relmse", time_stat=np.mean):
    """Per sample count: the errors' mean over seeds and the seconds' `time_stat` (the mean, or
    the median where other work on the machine makes some renders slow)."""
    spps = sorted({r["spp"] for r in rows})
    mean = lambda k, s: float(np.mean([r[k] for r in rows if r["spp"] == s]))
    return {"spp": spps, "seconds": [float(time_stat([r["seconds"] for r in rows if r["spp"] == s]))
                                     for s in spps],
            key: [mean(key, s) for s in spps],
            "flip": [mean("flip", s) for s in spps] if "flip" in rows[0] else None,
            "lum_std": [float(np.std([r["mean_lum"] for r in rows if r["spp"] == s], ddof=1))
                        if len([r for r in rows if r["spp"] == s]) > 1 else float("nan") for s in spps]}


def mitsuba_scene(project, work, w, h, sampler="independent", integrator="path"):
    """The exported project loaded with `sampler` and `integrator`, its kernels compiled (a
    1-spp warm-up, not counted in any time below)."""
    d, notes = mx.export(mx.load_project(project), w, h, 1, 0, mesh_dir=work, sampler=sampler,
                         integrator=integrator)
    scene = mx._mitsuba().load_dict(d)
    mx.render(scene, 1, 0)
    return scene, notes


def mitsuba_reference(project, work, w, h, cfg, integrator="path", seed=MITSUBA_REF_SEED):
    """Mitsuba's converged image with `integrator` (independent sampler): (image, seconds).
    Reused while the project, size, count, seed, integrator and Mitsuba are unchanged."""
    os.makedirs(work, exist_ok=True)
    name = ("mitsuba" if integrator == "path" else f"mitsuba_{integrator}") + \
        ("" if seed == MITSUBA_REF_SEED else f"_seed{seed}")
    path, meta = (os.path.join(work, f"{name}_reference{ext}") for ext in (".exr", ".json"))
    key = {"project": open(project).read(), "spp": cfg["mitsuba_ref_spp"], "size": [w, h],
           "integrator": integrator, "seed": seed, "mitsuba": mx._mitsuba().__version__,
           "variant": mx._mitsuba().variant()}
    if os.path.exists(path) and os.path.exists(meta) and json.load(open(meta)).get("key") == key:
        log(f"  mitsuba {integrator} reference (seed {seed}): reused {path}")
        return metrics.read_exr(path), json.load(open(meta))["seconds"]
    scene, _ = mitsuba_scene(project, work, w, h, integrator=integrator)
    ref_m, t_ref = mx.render(scene, cfg["mitsuba_ref_spp"], seed)
    mx.write_exr(path, ref_m)
    json.dump({"key": key, "seconds": t_ref}, open(meta, "w"))
    log(f"  mitsuba {integrator} reference (seed {seed}): {cfg['mitsuba_ref_spp']} spp in {fmt_s(t_ref)}")
    return ref_m, t_ref


def mitsuba_ladder(scene, cfg, seed, ref_m, ref_g):
    """One seed's renders of a loaded Mitsuba scene at 1, 2, 4, ... mitsuba_max_spp, against its
    own converged image `ref_m` (and Glint's `ref_g`)."""
    rows = []
    for spp in ladder(cfg["mitsuba_max_spp"]):
        img, secs = mx.render(scene, spp, seed)
        # Samplers that round the count (orthogonal: prime squares) are logged at what they traced.
        rows.append({"seed": seed, "spp": mx.samples_per_pixel(scene), "seconds": secs,
                     "relmse": metrics.relmse(img, ref_m),
                     "relmse_trimmed": metrics.relmse_trimmed(img, ref_m), "mean_lum": metrics.mean_lum(img),
                     "relmse_vs_glint_ref": metrics.relmse(img, ref_g)})
    return rows


def bench_mitsuba(name, project, work, cfg, glint_result, glint_summary, sampler="independent",
                  ref_m=None, integrator="path"):
    """Mitsuba's converged image (unless `ref_m` is given: then only the ladder) and its 1, 2,
    4, ... ladder with `sampler` and `integrator`, against that converged image; the comparison
    with Glint."""
    doc = mx.load_project(project)
    reasons = mx.unsupported_reasons(doc)
    if reasons:
        return {"exported": False, "reasons": reasons}
    os.makedirs(work, exist_ok=True)
    ref_g = glint_result["ref"]
    h, w = ref_g.shape[:2]
    t_ref = None
    if ref_m is None:
        ref_m, t_ref = mitsuba_reference(project, work, w, h, cfg, integrator)
    scene, notes = mitsuba_scene(project, work, w, h, sampler, integrator)
    rows = []
    for seed in range(1, cfg["seeds"] + 1):
        rows += mitsuba_ladder(scene, cfg, seed, ref_m, ref_g)
    return mitsuba_comparison(rows, cfg, ref_m, ref_g, glint_summary, notes, t_ref, sampler, integrator)


def mitsuba_comparison(rows, cfg, ref_m, ref_g, glint_summary, notes, t_ref, sampler, integrator,
                       time_stat=np.mean):
    """A Mitsuba ladder's summary and fits, and its comparison with Glint's."""
    h, w = ref_g.shape[:2]
    ms = summarize(rows, time_stat=time_stat)
    fit_mt = loglog_fit(ms["seconds"], ms["relmse"])
    fit_ms = loglog_fit(ms["spp"], ms["relmse"])
    fit_gt = loglog_fit(glint_summary["seconds"], glint_summary["relmse"])
    fit_gs = loglog_fit(glint_summary["spp"], glint_summary["relmse"])
    # Equal time: both fits evaluated at the longest time both ladders measured.
    t_star = min(ms["seconds"][-1], glint_summary["seconds"][-1])
    ratio = fit_eval(fit_gt, t_star) / fit_eval(fit_mt, t_star) if fit_gt and fit_mt else float("nan")
    # Bias of Glint's converged image against Mitsuba's, and what noise alone would give.
    bias = metrics.mean_bias(ref_g, ref_m)
    rel_conv = metrics.relmse(ref_g, ref_m)
    noise = (fit_eval(fit_gs, cfg["ref_spp"]) if fit_gs else float("nan")) + \
            (fit_eval(fit_ms, cfg["mitsuba_ref_spp"]) if fit_ms else float("nan"))
    # Standard error of the mean-luminance difference, from the seed spread at the top of each
    # ladder scaled to the reference sample counts.
    m_lum = metrics.mean_lum(ref_m)
    sg = glint_summary["lum_std"][-1] * math.sqrt(glint_summary["spp"][-1] / cfg["ref_spp"])
    sm = ms["lum_std"][-1] * math.sqrt(ms["spp"][-1] / cfg["mitsuba_ref_spp"])
    sigma = math.sqrt(sg ** 2 + sm ** 2) / m_lum if m_lum > 0 else float("nan")
    log(f"  mitsuba {integrator} ({sampler}): bias {bias:+.3%} (sigma {sigma:.2%}), relMSE(glint ref, mitsuba ref) "
        f"{rel_conv:.3g} (noise alone ~{noise:.3g}), equal-time ratio {ratio:.3g} at {fmt_s(t_star)}")
    return {"exported": True, "notes": notes, "rows": rows, "summary": ms, "t_ref": t_ref,
            "bias": bias, "sigma": sigma, "relmse_conv": rel_conv, "noise": noise,
            "ratio": ratio, "t_star": t_star, "fit_time": fit_mt, "fit_spp": fit_ms,
            "pixels": w * h, "mean_lum_mitsuba": m_lum, "mean_lum_glint": metrics.mean_lum(ref_g),
            "ref": ref_m, "sampler": sampler, "integrator": integrator}


def versus_path(contender_ref, path_ref, path_ref2):
    """How far a contender's converged Mitsuba image is from path's (same sample count), beside
    the floor that noise alone gives: path's converged image of another seed against it. relMSE
    as the race measures it, and trimmed (the worst 0.1% of pixels dropped, so that a few
    fireflies in either image do not decide) for race.valid_at."""
    return {"relmse": metrics.relmse(contender_ref, path_ref),
            "floor_relmse": metrics.relmse(path_ref2, path_ref),
            "difference": metrics.relmse_trimmed(contender_ref, path_ref),
            "floor": metrics.relmse_trimmed(path_ref2, path_ref),
            "mean_bias": metrics.mean_bias(contender_ref, path_ref)}


# --------------------------------------------------------------------------------------------
# Report

def plots(results, out_dir, prefix):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    files = []
    cmap = plt.get_cmap("tab10")
    specs = [("relmse_vs_time", "seconds", "relmse", "render time (s)", "relMSE"),
             ("relmse_vs_spp", "spp", "relmse", "samples per pixel", "relMSE"),
             ("flip_vs_spp", "spp", "flip", "samples per pixel", "mean HDR-FLIP")]
    for fname, xk, yk, xl, yl in specs:
        fig, ax = plt.subplots(figsize=(8, 5.5))
        for i, (name, r) in enumerate(results.items()):
            s = r["summary"]
            x, y = np.array(s[xk]), np.array(s[yk])
            for row in r["glint"]["rows"]:
                ax.scatter(row[xk], row[yk], s=6, color=cmap(i % 10), alpha=0.3, lw=0)
            fit = loglog_fit(x, y)
            label = name + (f" (slope {fit[1]:.2f})" if fit else "")
            ax.plot(x, y, "o", color=cmap(i % 10), ms=4, label=label)
            if fit:
                xs = np.geomspace(x.min(), x.max(), 20)
                ax.plot(xs, np.exp(fit[0] + fit[1] * np.log(xs)), "-", color=cmap(i % 10), lw=1)
            if yk == "relmse" and r.get("mitsuba", {}).get("exported"):
                ms = r["mitsuba"]["summary"]
                ax.plot(ms[xk], ms[yk], "x--", color=cmap(i % 10), ms=5, lw=0.8, alpha=0.8,
                        label=f"{name}, Mitsuba (own ref.)")
        if yk == "relmse":
            for t in TARGETS:
                ax.axhline(t, color="grey", lw=0.5, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.set_title(f"{yl} against {xl.split(' (')[0]}: mean of seeds (dots: single seeds), "
                     "log-log fit", fontsize=9)
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        ax.legend(fontsize=6.5, ncol=2)
        fig.tight_layout()
        path = os.path.join(out_dir, f"{prefix}{fname}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        files.append(os.path.basename(path))
    return files


def write_results(results, conv, cfg, env, out_dir, prefix, plot_files, command, results_extra):
    L = []
    L.append("# Glint benchmark: speed against error\n")
    L.append(f"Generated by `{command}` on {env['date']} ({'QUICK validation run: tiny sizes, not results' if cfg['quick'] else 'full run'}).\n")
    L.append(f"- machine: {env['cpu']}, {os.cpu_count()} logical CPUs; Glint on OpenGL {env['gl']}")
    L.append(f"- Mitsuba {env['mitsuba']} variant `{env['variant']}`" +
             (f" (libLLVM: `{env['llvm']}`)" if env["llvm"] else " (no working libLLVM found)"))
    L.append(f"- environments: {env['environments']}")
    L.append(f"- wall time of the run (scenes written to RESULTS.md, plots included): {env['wall']}")
    L.append(f"- width {cfg['width']} px (each scene keeps its film's aspect), {cfg['seeds']} seeds, "
             f"1 to {cfg['max_spp']} spp doubling; reference: Glint itself at {cfg['ref_spp']} spp "
             f"(seed {REF_SEED}, used by no test render); Mitsuba: converged image at "
             f"{cfg['mitsuba_ref_spp']} spp, ladder 1 to {cfg['mitsuba_max_spp']} spp")
    L.append("- errors: relMSE = mean over pixels and RGB of (x - r)^2 / (r^2 + 0.01) (as "
             "renderer/image_metrics.h); FLIP = mean HDR-FLIP (flip-evaluator); times are the "
             "trace time `glint render` reports (start-up and shader compilation excluded)")
    L.append("- the reference is Glint's own, so these errors measure noise, not bias (bias is "
             "the Mitsuba section's job); the reference's own noise adds about relMSE(ladder "
             f"top) / {cfg['ref_spp'] // cfg['max_spp']} to every point")
    L.append("- Glint renders with its default sampler (Owen-scrambled Sobol); the error per sample "
             "of Sobol against PCG at equal spp is measured by bench/tools/qmc_gain.py (bench/reports/SAMPLER.md)\n")
    L.extend(kept_sections(os.path.join(out_dir, f"{prefix}RESULTS.md")))
    if results_extra.get("race") is not None:
        L.append(race.markdown(results_extra["race"], results_extra["trial"]["winner"], fmt_s))
        L.append(mitsuba_samplers.markdown(results_extra["trial"]))
    if results_extra.get("qmc"):
        q = results_extra["qmc"]
        L.append("## Glint's sampler at equal spp: Sobol (the default) against PCG\n")
        L.append(f"`{q['command']}` (details, layout trials and tests in bench/reports/SAMPLER.md): the "
                 "Cornell box of projects/ with every material matte and max_bounces 1 (direct "
                 "light, the case of Burley 2020, \"Practical Hash-based Owen Scrambling\", JCGT "
                 "9(4), Fig. 1, which reports about 12x lower RMSE at 16 spp), RMSE against a "
                 "high-spp Sobol reference, over seeds. Its output:\n")
        L.append("```\n" + q["output"].strip() + "\n```\n")
    L.append("## Back ends: fragment against compute on this machine\n")
    if results_extra.get("backends"):
        L.append(f"`glint render --backend fragment` and `--backend compute`, each scene at the "
                 f"bench's width, {cfg['backend_spp']} spp, {cfg['backend_repeats']} renders per back "
                 "end interleaved, median samples per second (trace time as the CLI reports it). "
                 "The last column is the relMSE between the two back ends' images of the same "
                 "seed.\n")
    L += backends.table(results_extra.get("backends") or [], bool(results_extra.get("backends")))
    L.append("## Convergence and time to error\n")
    L.append("| scene | size | Msamples/s | spp/s | slope vs spp | slope vs time | relMSE @ max spp | "
             "trimmed | FLIP @ max spp | t(relMSE 1e-1) | t(1e-2) | t(1e-3) |")
    L.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, r in results.items():
        s = r["summary"]
        fs, ft = loglog_fit(s["spp"], s["relmse"]), loglog_fit(s["seconds"], s["relmse"])
        rows = r["glint"]["rows"]
        top = [x for x in rows if x["spp"] == s["spp"][-1]]
        w, h = r["size"]
        secs = s["seconds"][-1]
        tt = [time_to(s, t) for t in TARGETS]
        L.append(f"| {name} | {w}x{h} | {s['spp'][-1] * w * h / secs / 1e6:.3g} | "
                 f"{s['spp'][-1] / secs:.3g} | {g3(fs[1] if fs else None)} | {g3(ft[1] if ft else None)} | "
                 f"{s['relmse'][-1]:.3g} | {np.mean([x['relmse_trimmed'] for x in top]):.3g} | "
                 f"{s['flip'][-1]:.3g} | " + " | ".join(tt) + " |")
    L.append("\nTimes to error are read from the ladder of mean relMSE against time as the race "
             "reads them (bench/tools/race.py): interpolated (log-log) between the two rungs around the "
             f"target; \"not reached\" gives in brackets the extrapolation of a log-log fit of the "
             f"last {race.TAIL_RUNGS} rungs. The slopes are fits of the whole ladder. Samples per "
             "second are at the largest sample count.\n")
    for f in plot_files:
        L.append(f"![{f}]({f})\n")
    furnace = results.get("white_furnace")
    if furnace:
        ref = furnace["glint"]["ref"]
        L.append(f"White furnace (analytic value 1 everywhere): Glint's reference has mean "
                 f"{ref.mean():.5f}, min {ref.min():.4f}, max {ref.max():.4f}.\n")
    if any(r["glint"]["log"] for r in results.values()):
        L.append("## `glint render --log` cross-check\n")
        L.append("| scene | seed | CSV relMSE @ max spp | harness relMSE (same seed, spp) | CSV seconds | harness seconds |")
        L.append("|---|---|---|---|---|---|")
        for name, r in results.items():
            for seed, rows in enumerate(r["glint"]["log"] or [], start=1):
                if not rows:
                    continue
                last = rows[-1]
                mine = [x for x in r["glint"]["rows"] if x["seed"] == seed and x["spp"] == int(last["spp"])]
                L.append(f"| {name} | {seed} | {float(last['relmse']):.4g} | "
                         f"{mine[0]['relmse']:.4g} | {float(last['seconds']):.3g} | {mine[0]['seconds']:.3g} |"
                         if mine else f"| {name} | {seed} | {last['relmse']} | n/a | {last['seconds']} | n/a |")
        L.append("")
    if results_extra.get("before_after"):
        L.append(ablation.before_after_markdown(results_extra["before_after"], fmt_s))
    if results_extra.get("ablation"):
        L.append(ablation.markdown(results_extra["ablation"], cfg))
    L.append("## Independent reference: Mitsuba 3\n")
    L.append(f"Exported by `bench/tools/mitsuba_export.py`; Mitsuba's `path` integrator (max_depth = "
             f"max_bounces + 1) on the CPU (`{env['variant']}`), Glint on {env['gl_short']}. "
             "Bias: mean-luminance difference of Glint's converged image against Mitsuba's "
             "(± one standard error from the seed spread), and relMSE between the two converged "
             "images beside what their noise alone would give (from the ladder fits). Equal-time "
             "ratio: Glint's relMSE over Mitsuba's at the same time (each against its own "
             "converged image, so the ratio measures noise only), from the two log-log fits at "
             "t*, the longest time both ladders measured; above 1 means Mitsuba converges faster.\n")
    L.append("| scene | mean-lum. bias Glint vs Mitsuba | relMSE(Glint ref, Mitsuba ref) | noise alone | "
             "equal-time relMSE ratio Glint / Mitsuba | t* | Mitsuba Msamples/s | Mitsuba slope vs time | "
             "Glint t(relMSE 1e-2) | Mitsuba t(relMSE 1e-2) |")
    L.append("|---|---|---|---|---|---|---|---|---|---|")
    refused = []
    for name, r in results.items():
        m = r.get("mitsuba")
        if not m:
            continue
        if not m["exported"]:
            refused.append((name, m["reasons"]))
            continue
        ms = m["summary"]
        gs = r["summary"]
        L.append(f"| {name} | {m['bias']:+.2%} ± {m['sigma']:.2%} | {m['relmse_conv']:.3g} | "
                 f"{m['noise']:.3g} | {g3(m['ratio'])} | {fmt_s(m['t_star'])} | "
                 f"{ms['spp'][-1] * m['pixels'] / ms['seconds'][-1] / 1e6:.3g} | "
                 f"{g3(m['fit_time'][1] if m['fit_time'] else None)} | "
                 f"{time_to(gs, 1e-2)} | {time_to(ms, 1e-2)} |")
    L.append("")
    # Why the equal-time ratio is what it is: samples per second on the same two cores, and
    # what is left for the noise of one sample.
    tput = []
    for name, r in results.items():
        m = r.get("mitsuba")
        if not m or not m["exported"]:
            continue
        s_, ms = r["summary"], m["summary"]
        w, h = r["size"]
        g_rate = s_["spp"][-1] * w * h / s_["seconds"][-1] / 1e6
        m_rate = ms["spp"][-1] * m["pixels"] / ms["seconds"][-1] / 1e6
        if g_rate > 0 and np.isfinite(m["ratio"]):
            tput.append(f"{name} {m_rate / g_rate:.3g}x the samples per second (per-sample relMSE "
                        f"ratio Glint / Mitsuba {m['ratio'] * g_rate / m_rate:.3g})")
    if tput:
        L.append("Mitsuba (vectorised LLVM on the CPU) traces, against Glint's fragment shader on "
                 "llvmpipe: " + "; ".join(tput) + ". The equal-time ratio is the product of the "
                 "two; where it is above 1, most of it is throughput on this CPU. How far Glint's "
                 "shader is from a bare path tracer on the same driver, and where its time goes: "
                 "bench/reports/THROUGHPUT.md.\n")
    if refused:
        L.append("Not exported (Mitsuba would not model them identically):\n")
        for name, reasons in refused:
            L.append(f"- **{name}**: " + "; ".join(reasons[:4]) +
                     (f"; and {len(reasons) - 4} more" if len(reasons) > 4 else ""))
        L.append("")
    notes = [(n, x) for n, r in results.items() if r.get("mitsuba", {}).get("exported")
             for x in r["mitsuba"]["notes"]]
    for n, x in notes:
        L.append(f"- {n}: {x}")
    if notes:
        L.append("")
    if conv:
        L.append("### Convention check: environment map and camera\n")
        L.append(f"An environment-only project (max_bounces 0, `{env['convention_hdr']}` rotated by "
                 "40 degrees, intensity 1.5, 64x48 px, 64 spp) seen from three directions, "
                 "rendered by Glint (two seeds) and by Mitsuba with the exporter's convention and "
                 "with wrong ones. relMSE against Glint's seed-1 image; the right convention must "
                 "sit near the noise floor (Glint against Glint) and every wrong one far above "
                 "it. On a smooth map (the generated sky: a sharp sun disc and horizon, smooth "
                 "elsewhere) the noise floor is tiny and the exporter's residual can sit well "
                 "above it; what tells the conventions apart is then the gap to the wrong ones.\n")
        keys = [k for k in conv[0] if k != "view" and not k.endswith(" bias")]
        L.append("| view | " + " | ".join(keys) + " |")
        L.append("|---|" + "---|" * len(keys))
        for row in conv:
            L.append(f"| {row['view']} | " + " | ".join(f"{row[k]:.3g}" for k in keys) + " |")
        L.append("")
    horizon = results.get("huge_sphere_floor", {}).get("horizon")
    if horizon:
        names = list(horizon["worst"])
        L.append("### Huge-sphere floor against the analytic value\n")
        L.append("Far from the small spheres the floor's radiance is exactly albedo x sky (see "
                 "`bench/tools/horizon_check.py`); a pixel's expected value is that, mixed with the sky "
                 "by the fraction of the pixel covered by floor (computed in double). Green "
                 f"channel, mean over the {horizon['pixels']} pixels this applies to, per image row "
                 "that shows floor:\n")
        L.append("| row | pixels | expected | " + " | ".join(names) + " |")
        L.append("|---|---|---|" + "---|" * len(names))
        for row in horizon["rows"]:
            L.append(f"| {row['row']} | {row['pixels']} | {row['expected']:.4f} | " +
                     " | ".join(f"{row[n]:.4f}" for n in names) + " |")
        L.append("\nLargest |image - expected| over those pixels (any channel; the horizon row's "
                 "pixels keep their sampling noise): " +
                 ", ".join(f"{n} {v:.3g}" for n, v in horizon["worst"].items()) + ".\n")
    L.append("### Modelling differences between Glint and the Mitsuba export\n")
    L.append(DIFFERENCES)
    with open(os.path.join(out_dir, f"{prefix}RESULTS.md"), "w") as f:
        f.write("\n".join(L) + "\n")


DIFFERENCES = """\
- **Two-sided emission.** Glint's emission leaves both sides of a surface; Mitsuba's `area`
  emitter only the front. Emissive quads are exported as two one-sided copies back to back
  (the copy reversed and moved 1e-5 x (1 + |p|) behind), so both sides emit and reflect as in
  Glint; Mitsuba's light sampling then also picks the copy facing away (wasted samples, no bias).
  Emissive spheres emit outwards only, plus an inward-facing inner sphere when the camera or a
  shape is inside one.
- **Two-sided shading.** Glint shades both sides of every surface; Mitsuba's `diffuse` and
  `conductor` are one-sided, so every BSDF is wrapped in `twosided`.
- **Environment lookup.** Mitsuba's envmap uses u = atan2(x, -z) / 2pi; Glint's u = atan2(z, x) /
  2pi: the exporter sets to_world = R_y(rotation_deg - 90). Mitsuba also puts the image's first
  and last rows on the poles (v = i / (H - 1)) while Glint's GL_LINEAR lookup puts row centres at
  (i + 0.5) / H with clamp-to-edge; the exporter resamples the map to 2H + 1 rows so that
  Mitsuba's bilinear lookup equals Glint's. The HDR files are decoded by Mitsuba's RGBE reader
  (Glint: stb_image); both map a texel to mantissa x 2^(exponent - 136).
- **Mirror.** Only a white perfect mirror (colour exactly 1, roughness < 0.03) is exported, as
  `conductor` with `material: none` (reflectance 1): Glint's Schlick F(colour, cos) is 1 only for
  colour 1; any other colour rises towards white at grazing angles, which no Mitsuba conductor
  reproduces.
- **Not exported:** glossy (Glint's Schlick-weighted GGX coat with a (1 - F) Lambertian base has
  no Mitsuba equivalent: `roughplastic` uses exact Fresnel and internal reflection), transparent
  (Glint's thin glass: Schlick Fresnel, no bending, no inter-reflection between the two faces;
  Mitsuba's `thindielectric` sums the inter-reflections with exact Fresnel), rough or coloured
  metals (Schlick against complex-IOR Fresnel; Glint's separable Smith G), textures and coverage.
- **Sampling, not the model:** both sample lights directly (next-event estimation with MIS)
  and use Russian roulette (Mitsuba from depth 5, Glint after 5 bounces; both scale the survival
  probability by the eta^2 of the refractions passed). Mitsuba samples an
  emitting sphere by its visible cap as Glint does and a quad by area; both are unbiased for
  these scenes; they change the noise, which is what the equal-time ratio measures.
- **Camera and film.** Both use a box pixel filter (Glint: uniform jitter inside the pixel),
  a vertical field of view and a thin lens that is sharp on the plane at `focus_distance`
  along the view axis. Mitsuba clips camera rays nearer than `near_clip` (set to 1e-6 of the
  scene's size); Glint has no near plane.
- **Precision: the huge-sphere floor.** Glint traces in float on the GPU (llvmpipe here). In
  Mitsuba's `llvm_ad_rgb` variant (float32) the radius-1e5 floor sphere comes out at about half
  the analytic radiance (albedo x sky; Glint gives 0.39-0.41 in the unoccluded rows, Mitsuba
  llvm 0.19-0.26), consistent with rays leaving the floor re-hitting it. `scalar_rgb` (which
  solves the sphere quadratic in double) is closer but still loses light in the floor rows next
  to the horizon: rendered by hand (GLINT_BENCH_MITSUBA_VARIANT=scalar_rgb bash bench/run.sh
  --scenes huge_sphere_floor, 128x72, 1024 spp) and checked with `bench/tools/horizon_check.py`, its
  three rows below the horizon were 9%, 22% and 18% darker than the analytic value while
  Glint's were within 1e-4 of it; that accounts for the +1.08% mean bias it showed against
  Glint. So the bias row of this scene measures Mitsuba's sphere, not Glint; the analytic
  section above is the check that applies.
- **Mitsuba on Debian 12's LLVM 15.** Dr.Jit 1.5 (Mitsuba 3.9.1) emits `llvm.minimum`, which
  LLVM 15's x86 back end cannot select: the process aborts ("LLVM ERROR: Cannot select ...
  fminimum"). The harness probes each libLLVM in a child process; when none works it unpacks
  Debian's libllvm19 package into bench/.venv/llvm (`apt-get download`, `dpkg -x`: nothing is
  installed) and uses that, else falls back to `scalar_rgb`.
"""


def machine_info(gl):
    cpu = platform.processor() or platform.machine()
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return cpu


# Sections of RESULTS.md that other scripts write (bench/tools/denoise.py's tables): a rewrite by
# this script keeps them as they are, after the header.
KEPT_SECTIONS = ("## Denoising",)


def kept_sections(path):
    """The KEPT_SECTIONS of the RESULTS.md at `path` (up to the next "## " heading), as lines."""
    try:
        with open(path) as f:
            lines = f.read().split("\n")
    except OSError:
        return []
    out, keep = [], False
    for line in lines:
        if line.startswith("## "):
            keep = line.startswith(KEPT_SECTIONS)
        if keep:
            out.append(line)
    while out and not out[-1].strip():
        out.pop()
    return out + [""] if out else []


def ensure_llvm(allow_download):
    if os.environ.get("GLINT_BENCH_MITSUBA_VARIANT") == "scalar_rgb":
        return "scalar_rgb", None  # asked for by the user (e.g. for the huge-sphere floor)
    variant, path = mx.choose_variant(log)
    if variant == "llvm_ad_rgb" or not allow_download or not shutil.which("apt-get") or not shutil.which("dpkg"):
        return variant, path
    # No system libLLVM works with this Dr.Jit (Debian 12's LLVM 15 aborts on llvm.minimum):
    # fetch Debian's libllvm19 package (no installation: unpacked into the git-ignored venv).
    dest = os.path.join(BENCH, ".venv", "llvm")
    log("  fetching Debian's libllvm19 into bench/.venv/llvm (apt-get download; nothing installed)")
    tmp = tempfile.mkdtemp()
    try:
        r = subprocess.run(["apt-get", "download", "libllvm19"], cwd=tmp, capture_output=True, text=True)
        debs = glob.glob(os.path.join(tmp, "*.deb"))
        if r.returncode != 0 or not debs:
            log(f"  apt-get download libllvm19 failed: {r.stderr.strip()[:200]}")
        else:
            os.makedirs(dest, exist_ok=True)
            subprocess.run(["dpkg", "-x", debs[0], dest], check=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    os.environ.pop("GLINT_BENCH_MITSUBA_VARIANT", None)
    return mx.choose_variant(log)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true",
                    help="tiny sizes and sample counts (validation; a few minutes); writes to build-bench/quick/")
    ap.add_argument("--scenes", nargs="+", choices=SCENES, default=SCENES)
    ap.add_argument("--out", help="folder for RESULTS.md and plots (default: bench/reports/, or build-bench/quick/ with --quick)")
    ap.add_argument("--work", help="scratch folder for renders (default: build-bench/work or build-bench/quick/work)")
    ap.add_argument("--glint", default=os.path.join(ROOT, "build", "glint"))
    ap.add_argument("--assets", metavar="DIR",
                    help="real HDR maps for the scenes lit by one (" + ", ".join(make_scenes.HDR_MAPS.values()) +
                    ", by name); default: the sky the project generates (projects/assets/sky.hdr)")
    for k, v in FULL.items():
        ap.add_argument("--" + k.replace("_", "-"), type=int, help=f"(full {v}, quick {QUICK[k]})")
    ap.add_argument("--no-mitsuba", action="store_true")
    ap.add_argument("--no-ablation", action="store_true", help="skip the per-technique renders")
    ap.add_argument("--no-qmc", action="store_true", help="skip the Sobol-against-PCG table (bench/tools/qmc_gain.py)")
    ap.add_argument("--no-llvm-download", action="store_true",
                    help="do not fetch libllvm19 when no system libLLVM works (use scalar_rgb)")
    a = ap.parse_args()
    cfg = dict(QUICK if a.quick else FULL)
    for k in FULL:
        if getattr(a, k) is not None:
            cfg[k] = getattr(a, k)
    cfg["quick"] = a.quick
    out_dir = a.out or (os.path.join(ROOT, "build-bench", "quick") if a.quick else REPORTS)
    work = a.work or os.path.join(out_dir if a.quick else os.path.join(ROOT, "build-bench"), "work")
    os.makedirs(out_dir, exist_ok=True)
    os.makedirs(work, exist_ok=True)
    glint = os.path.abspath(a.glint)
    if not os.path.exists(glint):
        sys.exit(f"bench: {glint} not found (bash scripts/build.sh)")
    os.environ["GLINT"] = glint  # mitsuba_export.py converts the scenes with this glint
    # The committed scenes use the generated sky; with --assets the scenes are written beside the
    # renders (their environments point into DIR) and bench/scenes is left as committed.
    scenes_dir = os.path.join(BENCH, "scenes")
    make_scenes.main()
    if a.assets:
        scenes_dir = os.path.join(work, "scenes-assets")
        make_scenes.main(scenes_dir, os.path.abspath(a.assets))
    t_start = time.time()
    env = {"date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), "variant": "-", "llvm": None,
           "mitsuba": "-"}
    conv = None
    if not a.no_mitsuba:
        env["variant"], env["llvm"] = ensure_llvm(not a.no_llvm_download)
        mi = mx._mitsuba()
        mi.set_log_level(mi.LogLevel.Error)  # `orthogonal` warns at every count it rounds
        env["mitsuba"] = mi.__version__
        log(f"mitsuba {mi.__version__}, variant {env['variant']}")
        hdr = (os.path.join(os.path.abspath(a.assets), make_scenes.HDR_MAPS["env_dof"]) if a.assets
               else make_scenes.GENERATED_SKY)
        env["convention_hdr"] = os.path.basename(hdr) if a.assets else "projects/assets/sky.hdr"
        log(f"convention check ({env['convention_hdr']})")
        conv = __import__("convention_check").run(glint, os.path.join(work, "convention"), hdr)
    has_log = cli_has_log(glint)
    log(f"glint render --log: {'available' if has_log else 'not available (metrics computed here only)'}")
    results = {}
    for name in a.scenes:
        project = os.path.join(scenes_dir, name + ".glint")
        log(f"{name}")
        g = bench_glint(name, project, glint, os.path.join(work, name), cfg, has_log)
        s = summarize(g["rows"])
        r = {"glint": g, "summary": s, "size": (g["ref"].shape[1], g["ref"].shape[0])}
        if not a.no_mitsuba:
            r["mitsuba"] = bench_mitsuba(name, project, os.path.join(work, name, "mitsuba"), cfg, g, s)
            if not r["mitsuba"]["exported"]:
                log("  mitsuba: not exported: " + "; ".join(r["mitsuba"]["reasons"][:2]))
        if name == "huge_sphere_floor":
            log("  analytic check of the floor near the horizon")
            images = {"Glint": g["ref"]}
            if r.get("mitsuba", {}).get("exported"):
                images[f"Mitsuba {env['variant']}"] = r["mitsuba"]["ref"]
            r["horizon"] = horizon_check.compare(project, images)
        results[name] = r
        env["gl"] = g["info"]["gl"]
    env["gl_short"] = env.get("gl", "?").split(" on ")[-1].split(" (")[0] if env.get("gl") else "?"
    env["cpu"] = machine_info(env.get("gl"))
    prefix = ""
    plot_files = plots(results, out_dir, prefix)
    cmd = "bash bench/run.sh" + (" --quick" if a.quick else "") + (" --assets DIR" if a.assets else "")
    env["environments"] = (", ".join(f"{s} `{f}`" for s, f in make_scenes.HDR_MAPS.items()) + " from --assets"
                           if a.assets else "roughness_ladder and env_dof under the generated sky "
                           "(projects/assets/sky.hdr, `glint-make-assets`)")
    extra = {}
    if not a.no_ablation:
        log("ablation (techniques one after another)")
        extra["ablation"] = ablation.run(glint_render, glint,
                                         [(n, os.path.join(scenes_dir, n + ".glint")) for n in a.scenes],
                                         work, cfg, {n: r["glint"]["ref"] for n, r in results.items()}, log)
    if not a.no_mitsuba:
        exported = [(n, r["mitsuba"]["ref"]) for n, r in results.items() if r["mitsuba"]["exported"]]
        if exported:
            log("mitsuba: samplers at equal spp")
            load = lambda n, smp: mitsuba_scene(os.path.join(scenes_dir, n + ".glint"),
                                                os.path.join(work, n, "mitsuba"),
                                                *results[n]["size"], smp)[0]
            extra["trial"] = mitsuba_samplers.trial(exported, TRIAL_SPP["quick" if a.quick else "full"],
                                                    cfg["seeds"], load, log)
            ld = extra["trial"]["winner"]
            for n, ref_m in exported:
                log(f"{n}: mitsuba {ld} ladder")
                results[n]["mitsuba_ld"] = {ld: bench_mitsuba(
                    n, os.path.join(scenes_dir, n + ".glint"), os.path.join(work, n, "mitsuba"), cfg,
                    results[n]["glint"], results[n]["summary"], sampler=ld, ref_m=ref_m)}
            for n, _ in exported:
                if n in PTRACER_SCENES:
                    log(f"{n}: mitsuba ptracer")
                    p = bench_mitsuba(n, os.path.join(scenes_dir, n + ".glint"),
                                      os.path.join(work, n, "mitsuba"), cfg, results[n]["glint"],
                                      results[n]["summary"], integrator="ptracer")
                    h, w = results[n]["glint"]["ref"].shape[:2]
                    ref2, _ = mitsuba_reference(os.path.join(scenes_dir, n + ".glint"),
                                                os.path.join(work, n, "mitsuba"), w, h, cfg,
                                                seed=MITSUBA_REF_SEED + 1)
                    p["vs_path"] = versus_path(p["ref"], results[n]["mitsuba"]["ref"], ref2)
                    results[n]["mitsuba_ptracer"] = p
            extra["race"] = race.rows(results, ld)
    if not a.no_qmc:
        log("sampler gain: bench/tools/qmc_gain.py (Sobol against PCG, direct-light Cornell box)")
        qargs = QMC_ARGS["quick" if a.quick else "full"] + ["--glint", glint, "--out", os.path.join(work, "qmc")]
        r = subprocess.run([sys.executable, os.path.join(HERE, "qmc_gain.py")] + qargs,
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"bench/tools/qmc_gain.py failed ({r.returncode}):\n{r.stderr}{r.stdout}")
        extra["qmc"] = {"command": "python3 bench/tools/qmc_gain.py " + " ".join(QMC_ARGS["quick" if a.quick else "full"]),
                        "output": r.stdout}
        log("  " + r.stdout.strip().splitlines()[-1])
    if backends.available(glint):
        log("back ends: fragment against compute")
        extra["backends"] = backends.measure(
            glint_render, glint, [(n, os.path.join(scenes_dir, n + ".glint")) for n in a.scenes],
            os.path.join(work, "backends"), cfg["width"], cfg["backend_spp"], cfg["backend_repeats"],
            log, lambda p, q: metrics.relmse(metrics.read_exr(p), metrics.read_exr(q)))
    else:
        log("back ends: `glint render --help` has no --backend (fragment only; no table)")
    if not a.quick:
        extra["before_after"] = ablation.before_after(os.path.join(REPORTS, "results_before.json"), results)
    env["wall"] = fmt_s(time.time() - t_start)
    write_results(results, conv, cfg, env, out_dir, prefix, plot_files, cmd, extra)
    # Raw numbers beside the report, for re-plotting without re-rendering.
    raw = {n: {"glint": r["glint"]["rows"],
               "mitsuba": r.get("mitsuba", {}).get("rows") if r.get("mitsuba", {}).get("exported") else None,
               "mitsuba_ld": {k: v["rows"] for k, v in r.get("mitsuba_ld", {}).items()},
               "mitsuba_ptracer": r["mitsuba_ptracer"]["rows"] if "mitsuba_ptracer" in r else None}
           for n, r in results.items()}
    with open(os.path.join(out_dir, f"{prefix}results.json"), "w") as f:
        json.dump({"config": cfg, "env": env, "scenes": raw, "ablation": extra.get("ablation"),
                   "before_after": extra.get("before_after"), "mitsuba_samplers": extra.get("trial"),
                   "race": extra.get("race"), "backends": extra.get("backends"),
                   "qmc": extra.get("qmc")}, f, indent=1)
    log(f"wrote {os.path.join(out_dir, prefix + 'RESULTS.md')} in {fmt_s(time.time() - t_start)}")


if __name__ == "__main__":
    main()
