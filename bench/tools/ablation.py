"""Per-technique measurements for RESULTS.md: what each sampling technique buys.

Ablation: every scene is rendered with the techniques switched on one after another, starting
from the original program's estimator (BSDF sampling only, independent PCG numbers, no
roulette, the generic shader with every feature compiled in), at the same sample count and
seeds. Efficiency is 1 / (relMSE x seconds): for an unbiased estimator relMSE falls as 1/time,
so the ratio of two efficiencies is the ratio of their relMSE at equal time (Veach 1997, 1.2).
Before/after: the ladders of the previous committed results (bench/reports/results_before.json, the
program before light and environment sampling on this machine) against the ladders of this run, both fitted in
log-log and compared at the same time.
"""
import json
import math
import os

import numpy as np

import metrics

# Cumulative: each row adds one technique to the row above it.
CONFIGS = [
    ("BSDF sampling only (original estimator)",
     ["--no-light-sampling", "--no-env-sampling", "--no-roulette", "--generic-shader", "--sampler", "pcg"]),
    ("+ light sampling (NEE + MIS) for spheres and quads",
     ["--no-env-sampling", "--no-roulette", "--generic-shader", "--sampler", "pcg"]),
    ("+ environment importance sampling", ["--no-roulette", "--generic-shader", "--sampler", "pcg"]),
    ("+ Russian roulette", ["--generic-shader", "--sampler", "pcg"]),
    ("+ shader specialised to the scene", ["--sampler", "pcg"]),
    ("+ Owen-scrambled Sobol instead of PCG (the defaults)", ["--sampler", "sobol"]),
]


def run(glint_render, glint, scenes, work, cfg, refs, log):
    """refs: scene -> reference image. Returns {scene: [{config, relmse, seconds, eff}...]}."""
    out = {}
    spp, seeds = cfg["ablation_spp"], cfg["ablation_seeds"]
    for name, project in scenes:
        rows = []
        for label, flags in CONFIGS:
            rel, secs = [], []
            for seed in range(1, seeds + 1):
                path = os.path.join(work, name, f"ablation_{len(rows)}_{seed}.exr")
                r = glint_render(glint, project, path, spp, seed, cfg["width"], flags)
                img = metrics.read_exr(path)
                rel.append(metrics.relmse(img, refs[name]))
                secs.append(r["seconds"])
                os.remove(path)
            m_rel, m_sec = float(np.mean(rel)), float(np.median(secs))
            rows.append({"config": label, "flags": flags, "relmse": m_rel, "seconds": m_sec,
                         "efficiency": 1.0 / (m_rel * m_sec) if m_rel > 0 and m_sec > 0 else float("nan")})
        base = rows[0]["efficiency"]
        for r in rows:
            r["speedup"] = r["efficiency"] / base if base > 0 else float("nan")
        log(f"  ablation {name}: " + ", ".join(f"{r['speedup']:.3g}" for r in rows))
        out[name] = rows
    return out


def markdown(ablation, cfg):
    L = ["## Per technique (ablation)\n",
         f"Each scene at {cfg['width']} px, {cfg['ablation_spp']} spp, {cfg['ablation_seeds']} seeds "
         "(mean relMSE against the Glint reference, median trace time), with the techniques "
         "switched on one after another. The number is the efficiency (1 / (relMSE x time)) "
         "relative to the first row: the factor by which relMSE at equal time is lower. "
         "The GGX visible-normal sampling cannot be switched off (it replaced the old sampler); "
         "its effect is in the before/after table above and in tests/unit/shader_vndf_test.cpp.\n"]
    names = list(ablation)
    L.append("| technique | " + " | ".join(names) + " |")
    L.append("|---|" + "---|" * len(names))
    for i, (label, _) in enumerate(CONFIGS):
        cells = []
        for n in names:
            r = ablation[n][i]
            cells.append(f"{r['speedup']:.3g}")
        L.append(f"| {label} | " + " | ".join(cells) + " |")
    L.append("")
    L.append("Trace time in seconds per configuration (same renders; the specialised shader's "
             "effect is the ratio of rows 4 and 5):\n")
    L.append("| technique | " + " | ".join(names) + " |")
    L.append("|---|" + "---|" * len(names))
    for i, (label, _) in enumerate(CONFIGS):
        L.append(f"| {label} | " + " | ".join(f"{ablation[n][i]['seconds']:.3g}" for n in names) + " |")
    L.append("")
    return "\n".join(L)


def _fit(rows):
    spps = sorted({r["spp"] for r in rows})
    t = [np.mean([r["seconds"] for r in rows if r["spp"] == s]) for s in spps]
    e = [np.mean([r["relmse"] for r in rows if r["spp"] == s]) for s in spps]
    x, y = np.log(t), np.log(e)
    b, a = np.polyfit(x, y, 1)
    return a, b, t, e


def before_after(before_path, results):
    """Rows per scene: relMSE of the old and the new program at the same time."""
    if not os.path.exists(before_path):
        return None
    old = json.load(open(before_path))
    rows = []
    for name, r in results.items():
        o = old["scenes"].get(name, {}).get("glint")
        if not o:
            continue
        ao, bo, to, eo = _fit(o)
        an, bn, tn, en = _fit(r["glint"]["rows"])
        t_star = min(to[-1], tn[-1])  # inside both measured ranges
        e_old = math.exp(ao + bo * math.log(t_star))
        e_new = math.exp(an + bn * math.log(t_star))
        rows.append({"scene": name, "t_star": t_star, "relmse_before": e_old, "relmse_after": e_new,
                     "ratio": e_old / e_new, "slope_before": bo, "slope_after": bn,
                     "spp_s_before": o[-1]["spp"] / np.mean([x["seconds"] for x in o if x["spp"] == o[-1]["spp"]]),
                     "spp_s_after": r["summary"]["spp"][-1] / r["summary"]["seconds"][-1]})
    return {"date": old.get("env", {}).get("date", "?"), "rows": rows}


def before_after_markdown(ba, fmt_s):
    L = ["## Before and after light and environment sampling\n",
         f"Before: the committed results of {ba['date']} (BSDF sampling only, PCG, no roulette, "
         "one generic shader, GGX normals sampled from D cos), kept in bench/reports/results_before.json. "
         "After: this run's ladders. Both are fitted in log-log (relMSE against trace time) "
         "and compared at t*, the longest time both measured; the target was a ratio "
         "of at least 4 on the small emitter, the Cornell box and the HDR environment.\n",
         "| scene | t* | relMSE before | relMSE after | ratio | slope before | slope after | spp/s before | spp/s after |",
         "|---|---|---|---|---|---|---|---|---|"]
    for r in ba["rows"]:
        L.append(f"| {r['scene']} | {fmt_s(r['t_star'])} | {r['relmse_before']:.3g} | {r['relmse_after']:.3g} | "
                 f"{r['ratio']:.3g} | {r['slope_before']:.2f} | {r['slope_after']:.2f} | "
                 f"{r['spp_s_before']:.3g} | {r['spp_s_after']:.3g} |")
    L.append("")
    return "\n".join(L)
