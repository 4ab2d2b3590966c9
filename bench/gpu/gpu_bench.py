#!/usr/bin/env python3
"""The GPU bench: `glint render` on the showcase (projects/default.glint, paths of up to 8
bounces) and the Cornell box (bench/scenes/cornell.glint) at 1920x1080, each trace back end
(`--backend fragment` and `--backend compute` when the CLI has them), samples per second; then
the time to relMSE 1e-3 of Glint and, when the mitsuba package is importable, of Mitsuba 3
(`cuda_ad_rgb`) on the scenes it models the same way, each against its own converged image.
Writes bench/reports/GPU.md (GPU, driver, date, the tables).

    python3 bench/gpu/gpu_bench.py                      # on the GPU machine (bench/gpu/README.md)
    python3 bench/gpu/gpu_bench.py --dry --out /tmp/GPU.md   # end-to-end check on llvmpipe,
                                                        # 64x36, Mitsuba llvm_ad_rgb

Needs numpy; Mitsuba is optional. Each measurement is sized by a time budget (a 1-spp probe gives
the rate), so the whole run takes a few minutes on any device.
"""
import argparse
import csv
import datetime
import math
import os
import shutil
import subprocess
import sys
import time

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
BENCH = os.path.dirname(HERE)
ROOT = os.path.dirname(BENCH)
sys.path.insert(0, os.path.join(BENCH, "tools"))

import numpy as np  # noqa: E402

import backends  # noqa: E402
import mitsuba_export as mx  # noqa: E402
from run import fmt_s, glint_render  # noqa: E402

SCENES = [("showcase", os.path.join(ROOT, "projects", "default.glint")),
          ("cornell", os.path.join(BENCH, "scenes", "cornell.glint"))]
# Mitsuba renders the samples of one mi.render call in one launch; at 1920x1080 the reference and
# long rungs are split into passes of this many samples (independent seeds, averaged).
MITSUBA_PASS_SPP = 16


def log(msg):
    print(msg, flush=True)


def relmse(x, r):
    """As renderer/image_metrics.h (and bench/tools/metrics.py): mean of (x - r)^2 / (r^2 + 0.01)."""
    x, r = x.astype(np.float64), r.astype(np.float64)
    return float(np.mean((x - r) ** 2 / (r * r + 0.01)))


def time_to(points, target):
    """points: [(seconds, relmse)] in increasing time. (seconds, mark): log-log interpolation
    between the two rungs around the target (mark ""), "<=" when the first rung is already below,
    "fit" when the last is still above (a log-log fit of the last four rungs, extrapolated)."""
    pts = [(t, e) for t, e in points if t > 0 and e > 0]
    if not pts:
        return None, "no data"
    if pts[0][1] <= target:
        return pts[0][0], "<="
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e1 <= target:
            b = math.log(e1 / e0) / math.log(t1 / t0)
            return math.exp(math.log(t0) + math.log(target / e0) / b), ""
    tail = pts[-4:]
    if len(tail) < 2:
        return None, "one rung"
    b, a = np.polyfit(np.log([t for t, _ in tail]), np.log([e for _, e in tail]), 1)
    if b >= 0:
        return None, "not converging"
    log_t = (math.log(target) - a) / b
    if log_t > math.log(1e7):  # a nearly flat fit: past any useful time
        return None, "fit: > 100 days"
    return math.exp(log_t), "fit"


def fmt_time(t):
    secs, mark = t
    if secs is None:
        return mark
    return {"<=": f"<= {fmt_s(secs)}", "fit": f"{fmt_s(secs)} (fit)"}.get(mark, fmt_s(secs))


def device_info(gl):
    info = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "gl": gl, "gpu": "?", "driver": "?"}
    if shutil.which("nvidia-smi"):
        r = subprocess.run(["nvidia-smi", "--query-gpu=name,driver_version,memory.total",
                            "--format=csv,noheader"], capture_output=True, text=True)
        if r.returncode == 0 and r.stdout.strip():
            parts = [p.strip() for p in r.stdout.strip().splitlines()[0].split(",")]
            info["gpu"], info["driver"] = parts[0], parts[1]
            info["memory"] = parts[2] if len(parts) > 2 else "?"
    if info["gpu"] == "?":
        info["gpu"] = gl.split(" on ", 1)[-1] if " on " in gl else gl
    return info


# --------------------------------------------------------------------------------------------
# Glint

def glint_throughput(glint, name, project, width, height, backend, seconds, work):
    extra = ["--height", str(height)] + (["--backend", backend] if backend else [])
    out = os.path.join(work, f"{name}_{backend or 'default'}_probe.exr")
    probe = glint_render(glint, project, out, 1, 1, width, extra)
    rate = 1 / probe["seconds"] if probe["seconds"] > 0 else 1000.0
    spp = max(2, int(rate * seconds))
    r = glint_render(glint, project, out, spp, 2, width, extra)
    sps = r["spp"] / r["seconds"]
    log(f"  {name} {backend or 'default'}: {r['spp']} spp in {fmt_s(r['seconds'])}: {sps:.4g} spp/s, "
        f"{sps * r['width'] * r['height'] / 1e9:.3g} Gsamples/s")
    return {"scene": name, "backend": backend or "(only one)", "spp": r["spp"],
            "seconds": r["seconds"], "spp_per_s": sps, "size": (r["width"], r["height"]),
            "gsamples_per_s": sps * r["width"] * r["height"] / 1e9, "gl": r["gl"]}


def glint_race(glint, name, project, width, height, backend, rate, ref_seconds, target, work):
    """Reference of rate x ref_seconds spp (a power of two), then one logged render of 1/16 of
    that against it; the time to `target` from the log."""
    extra = ["--height", str(height)] + (["--backend", backend] if backend else [])
    ref_spp = 2 ** max(4, int(math.log2(max(16, rate * ref_seconds))))
    ref = os.path.join(work, f"{name}_reference.exr")
    r = glint_render(glint, project, ref, ref_spp, 1000001, width, extra)
    log(f"  {name} reference: {ref_spp} spp in {fmt_s(r['seconds'])}")
    csv_path = os.path.join(work, f"{name}_{backend or 'default'}.csv")
    glint_render(glint, project, os.path.join(work, f"{name}_ladder.exr"), ref_spp // 16, 1, width,
                 extra + ["--reference", ref, "--log", csv_path])
    with open(csv_path) as f:
        points = [(float(row["seconds"]), float(row["relmse"])) for row in csv.DictReader(f)]
    t = time_to(points, target)
    log(f"  {name} glint ({backend or 'default'}): relMSE {points[-1][1]:.3g} at {ref_spp // 16} spp; "
        f"t({target:g}) {fmt_time(t)}")
    return {"ref_spp": ref_spp, "top_spp": ref_spp // 16, "top_relmse": points[-1][1], "time": t}


# --------------------------------------------------------------------------------------------
# Mitsuba

def mitsuba_available(variant):
    """(mitsuba module, None) when `variant` can be set, else (None, why)."""
    if variant.startswith("llvm"):
        # Before Dr.Jit loads: a libLLVM that this Dr.Jit accepts (bench/tools/mitsuba_export.py);
        # with none, Dr.Jit would abort the process in its first kernel.
        if mx.choose_variant(log)[0] != variant:
            return None, (f"no libLLVM that this Dr.Jit accepts for {variant} "
                          "(bash bench/run.sh fetches one into bench/.venv/llvm)")
    try:
        import mitsuba as mi
    except ImportError as e:
        return None, f"no mitsuba package ({e})"
    try:
        mi.set_variant(variant)
    except (ImportError, AttributeError, RuntimeError) as e:
        return None, f"mitsuba {mi.__version__}: variant {variant} unavailable ({e})"
    mi.set_log_level(mi.LogLevel.Error)
    return mi, None


def mitsuba_render(scene, spp, seed):
    """An image of at least `spp` samples as the mean of passes of at most MITSUBA_PASS_SPP, each
    weighted by the samples it really traced (`orthogonal` rounds a count up to a prime square);
    (image, seconds)."""
    done, total, secs = 0, None, 0.0
    k = 0
    while done < spp:
        img, t = mx.render(scene, min(MITSUBA_PASS_SPP, spp - done), (seed * 4099 + k) % 2 ** 32)
        n = mx.samples_per_pixel(scene)
        total = img * n if total is None else total + img * n
        done, secs, k = done + n, secs + t, k + 1
    return total / done, secs


def mitsuba_race(mi, name, project, width, height, sampler, ref_seconds, target, work, ref=None):
    """Mitsuba's converged image (unless `ref` = (image, spp) from an earlier sampler) and its
    ladder with `sampler` against it."""
    doc = mx.load_project(project)
    reasons = mx.unsupported_reasons(doc)
    if reasons:
        return {"exported": False, "reasons": reasons}
    d, _ = mx.export(doc, width, height, 1, 0, mesh_dir=os.path.join(work, f"{name}_mitsuba"),
                     sampler=sampler)
    scene = mi.load_dict(d)
    mx.render(scene, 1, 0)  # kernel compilation, not timed
    mx.render(scene, MITSUBA_PASS_SPP, 1)
    _, t1 = mx.render(scene, MITSUBA_PASS_SPP, 2)
    rate = MITSUBA_PASS_SPP / t1
    if ref is None:
        ref_spp = 2 ** max(4, int(math.log2(max(16, rate * ref_seconds))))
        img, t_ref = mitsuba_render(scene, ref_spp, 2000001)
        ref = (img, ref_spp)
        log(f"  {name} mitsuba reference ({sampler}): {ref_spp} spp in {fmt_s(t_ref)}")
    ref, ref_spp = ref
    points, spp = [], 1
    while spp <= ref_spp // 16:
        img, secs = mitsuba_render(scene, spp, 7)
        points.append((secs, relmse(img, ref)))
        spp *= 2
    t = time_to(points, target)
    log(f"  {name} mitsuba ({sampler}): relMSE {points[-1][1]:.3g} at {ref_spp // 16} spp, "
        f"{rate:.4g} spp/s; t({target:g}) {fmt_time(t)}")
    return {"exported": True, "ref_spp": ref_spp, "top_spp": ref_spp // 16,
            "top_relmse": points[-1][1], "time": t, "spp_per_s": rate,
            "gsamples_per_s": rate * width * height / 1e9, "ref": (ref, ref_spp)}


# --------------------------------------------------------------------------------------------

def markdown(a, info, tput, races, mitsuba_note, has_backend, wall):
    w, h = a.size
    L = ["# Glint on a GPU: samples per second and time to error\n",
         f"Generated by `python3 bench/gpu/gpu_bench.py {' '.join(sys.argv[1:])}` on {info['date']}"
         f"{' (DRY RUN: a small check of the script, not results)' if a.dry else ''}; "
         f"the run took {fmt_s(wall)}.\n",
         f"- GPU: {info['gpu']}" + (f", {info['memory']}" if info.get("memory") else "") +
         f"; driver {info['driver']}",
         f"- Glint on OpenGL {info['gl']}",
         f"- {w}x{h} px; throughput: a 1-spp probe, then about {a.seconds:g} s of samples, trace "
         "time as `glint render` reports it (start-up and shader compilation excluded)",
         f"- time to relMSE {a.target:g}: each renderer against its own converged image (about "
         f"{a.ref_seconds:g} s of samples, a power of two), one seed, rungs 1, 2, 4, ... up to "
         "1/16 of the reference's samples (the reference's own noise adds about 1/16 of the top "
         "rung's error); log-log interpolation between rungs; \"(fit)\": past the last rung, "
         "extrapolated from the last four; \"<=\": reached at the first rung\n"]
    if not has_backend:
        L.append("`glint render --help` does not mention `--backend`: this build has only the "
                 "fragment-shader tracer.\n")
    L.append("## Samples per second\n")
    L.append("| scene | back end | spp | seconds | spp/s | G samples/s |")
    L.append("|---|---|---|---|---|---|")
    for r in tput:
        L.append(f"| {r['scene']} | {r['backend']} | {r['spp']} | {r['seconds']:.3g} | "
                 f"{r['spp_per_s']:.4g} | {r['gsamples_per_s']:.3g} |")
    L.append("\nTarget on an H100 or H200: at least 1 G samples/s on the showcase.\n")
    L.append(f"## Time to relMSE {a.target:g}\n")
    L.append("| scene | renderer | reference spp | top rung spp | relMSE at top rung | "
             f"t({a.target:g}) | Glint / this |")
    L.append("|---|---|---|---|---|---|---|")
    for name, rs in races.items():
        g = rs.get("glint")
        for label, r in rs.items():
            if not r.get("exported", True):
                continue
            ratio = ""
            if label != "glint" and g and g["time"][0] and r["time"][0]:
                marks = {g["time"][1], r["time"][1]}
                ratio = f"{g['time'][0] / r['time'][0]:.2f}" + (" (fit)" if "fit" in marks else "") + \
                    (" (bound)" if "<=" in marks else "")
            L.append(f"| {name} | {r.get('label', label)} | {r['ref_spp']} | {r['top_spp']} | "
                     f"{r['top_relmse']:.3g} | {fmt_time(r['time'])} | {ratio} |")
    L.append("")
    for name, rs in races.items():
        for label, r in rs.items():
            if not r.get("exported", True):
                L.append(f"- {name}: not raced against Mitsuba, which would not model it the same "
                         "way: " + "; ".join(r["reasons"][:3]) + ("; ..." if len(r["reasons"]) > 3 else ""))
    if mitsuba_note:
        L.append(f"- Mitsuba: {mitsuba_note}")
    L.append("")
    return "\n".join(L)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--glint", default=os.path.join(ROOT, "build", "glint"))
    ap.add_argument("--size", default="1920x1080", help="WxH (default 1920x1080)")
    ap.add_argument("--seconds", type=float, default=8, help="throughput render length per scene and back end")
    ap.add_argument("--ref-seconds", type=float, default=30, help="length of each converged image")
    ap.add_argument("--target", type=float, default=1e-3)
    ap.add_argument("--variant", default="cuda_ad_rgb", help="Mitsuba variant (default cuda_ad_rgb)")
    ap.add_argument("--mitsuba-samplers", default="independent,orthogonal",
                    help="comma-separated (bench/reports/RESULTS.md says which low-discrepancy one wins)")
    ap.add_argument("--no-mitsuba", action="store_true")
    ap.add_argument("--dry", action="store_true",
                    help="small end-to-end check (llvmpipe here): 64x36, short budgets, llvm_ad_rgb")
    ap.add_argument("--out", default=os.path.join(BENCH, "reports", "GPU.md"))
    ap.add_argument("--work", default=os.path.join(ROOT, "build-bench", "gpu"))
    a = ap.parse_args()
    if a.dry:
        a.size, a.seconds, a.ref_seconds = ("64x36" if a.size == "1920x1080" else a.size), min(a.seconds, 1), min(a.ref_seconds, 3)
        a.variant = "llvm_ad_rgb" if a.variant == "cuda_ad_rgb" else a.variant
    a.size = tuple(int(v) for v in a.size.lower().split("x"))
    w, h = a.size
    glint = os.path.abspath(a.glint)
    if not os.path.exists(glint):
        sys.exit(f"gpu_bench: {glint} not found (build it, or give --glint)")
    os.makedirs(a.work, exist_ok=True)
    t0 = time.time()
    has_backend = bool(backends.available(glint))
    choices = list(backends.BACKENDS) if has_backend else [None]
    log(f"glint {glint}; back ends: {', '.join(backends.BACKENDS) if has_backend else 'fragment only (no --backend)'}")
    tput = []
    for name, project in SCENES:
        for b in choices:
            tput.append(glint_throughput(glint, name, project, w, h, b, a.seconds, a.work))
    info = device_info(tput[0]["gl"])
    races = {}
    for name, project in SCENES:
        best = max((r for r in tput if r["scene"] == name), key=lambda r: r["spp_per_s"])
        b = best["backend"] if has_backend else None
        g = glint_race(glint, name, project, w, h, b, best["spp_per_s"], a.ref_seconds, a.target, a.work)
        g["label"] = f"Glint ({b or 'fragment'})"
        races[name] = {"glint": g}
    mitsuba_note = None
    if not a.no_mitsuba:
        mi, why = mitsuba_available(a.variant)
        if mi is None:
            mitsuba_note = why + "; no Mitsuba rows"
            log(f"mitsuba: {mitsuba_note}")
        else:
            mitsuba_note = f"Mitsuba {mi.__version__}, variant `{a.variant}`, `path` integrator " \
                           f"(bench/tools/mitsuba_export.py), passes of at most {MITSUBA_PASS_SPP} spp"
            for name, project in SCENES:
                ref = None
                for sampler in a.mitsuba_samplers.split(","):
                    r = mitsuba_race(mi, name, project, w, h, sampler, a.ref_seconds, a.target, a.work, ref)
                    ref = r.get("ref")
                    r["label"] = f"Mitsuba {a.variant} {sampler}"
                    races[name][f"mitsuba {sampler}"] = r
                    if not r["exported"]:
                        break
    text = markdown(a, info, tput, races, mitsuba_note, has_backend, time.time() - t0)
    with open(a.out, "w") as f:
        f.write(text)
    log(f"wrote {a.out} in {fmt_s(time.time() - t0)}")


if __name__ == "__main__":
    main()
