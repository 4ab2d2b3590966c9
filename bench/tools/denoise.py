#!/usr/bin/env python3
"""Denoising at equal time, and the denoiser's time per image size (bench/reports/RESULTS.md,
"Denoising").

For every bench scene (bench/scenes/*.glint), against a reference of Glint itself at --ref-spp
(seed 1000001, as bench/tools/run.py makes it):
  - `glint render --spp N --denoise` for each N of --spp: its time is the tracing time (the AOV
    pass included) plus the denoiser's, both as glint prints them;
  - the raw render of the same total time (`glint render --time T`, same seed), and the noisy
    colour of the denoised render (its EXR layer "noisy": the raw render at N spp);
  - relMSE (renderer/image_metrics.h's definition) and HDR-FLIP of each against the reference.
Then `glint render --spp 1 --denoise` of one scene at each --sizes, both qualities: the
denoiser's wall time as glint prints it (a fresh filter each run: the set-up is included).

Denoising is biased: its error does not fall to zero with more samples, and these tables say
nothing about how close a denoised image is to the truth beyond the reference's own noise.

    bench/.venv/bin/python bench/tools/denoise.py --glint build/glint
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import metrics  # noqa: E402
import mitsuba_export as mx  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
REF_SEED = 1000001
WROTE = re.compile(r"wrote .* \((\d+)x(\d+), (\d+) spp, ([0-9.]+) s, ([0-9.]+) spp/s")
DENOISED = re.compile(r"denoised \(biased\) with Open Image Denoise on the (\w+) in ([0-9.]+) s")


def run(glint, project, out, width, seed, extra):
    cmd = [glint, "render", project, "-o", out, "--width", str(width), "--seed", str(seed)] + extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stderr}")
    m = WROTE.search(r.stderr)
    d = DENOISED.search(r.stderr)
    if "--denoise" in extra and not d:
        raise RuntimeError(f"{' '.join(cmd)} did not denoise:\n{r.stderr}")
    spp, spp_s = int(m.group(3)), float(m.group(5))
    return {"spp": spp, "seconds": spp / spp_s if spp_s > 0 else float(m.group(4)),
            "denoise_seconds": float(d.group(2)) if d else 0.0, "device": d.group(1) if d else "",
            "width": int(m.group(1)), "height": int(m.group(2))}


def layers(path):
    """The EXR's RGB layers as float32 arrays by channel name: "" the main image, "noisy"."""
    mi = mx._mitsuba()
    bmp = mi.Bitmap(path)
    fields = bmp.struct_()
    names = [fields[i].name for i in range(len(fields))]
    pixels = np.array(bmp, dtype=np.float32).reshape(bmp.height(), bmp.width(), len(names))
    out = {}
    for layer in ("", "noisy"):
        prefix = layer + "." if layer else ""
        if all(prefix + c in names for c in "RGB"):
            out[layer] = np.stack([pixels[..., names.index(prefix + c)] for c in "RGB"], axis=-1)
    return out


def errors(img, ref):
    return {"relmse": metrics.relmse(img, ref), "flip": metrics.flip(img, ref)}


def markdown(result):
    """The tables of bench/reports/RESULTS.md, "Denoising", from the JSON this script writes."""
    L = [f"Equal time, {result['width']} px wide, seed {result['seed']}, against Glint at "
         f"{result['ref_spp']} spp. Time = tracing (AOV pass included) + denoising, as glint "
         "prints them; the raw render ran `--time` of that total (its last pass may overrun it).", "",
         "| scene | spp + denoise | time (s) | relMSE denoised | relMSE raw, equal time (spp) | "
         "relMSE noisy, same spp | FLIP denoised | FLIP raw, equal time | FLIP noisy, same spp |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for name, rows in result["scenes"].items():
        for r in rows:
            t = r["trace_seconds"] + r["denoise_seconds"]
            L.append(f"| {name} | {r['spp']} | {t:.2f} | {r['denoised']['relmse']:.4g} | "
                     f"{r['raw_same_time']['relmse']:.4g} ({r['raw_spp']}) | "
                     f"{r['noisy_same_spp']['relmse']:.4g} | {r['denoised']['flip']:.4f} | "
                     f"{r['raw_same_time']['flip']:.4f} | {r['noisy_same_spp']['flip']:.4f} |")
    L += ["", "| image size | quality | denoise (s) | device |", "|---|---|---:|---|"]
    for t in result["timing"]:
        L.append(f"| {t['size']} | {t['quality']} | {t['seconds']:.2f} | {t['device']} |")
    return "\n".join(L)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--glint", default=os.path.join(ROOT, "build", "glint"))
    ap.add_argument("--width", type=int, default=64)
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--spp", type=int, nargs="+", default=[4, 16, 64])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--sizes", nargs="*", default=["256x256", "512x512", "1920x1080"])
    ap.add_argument("--timing-scene", default=os.path.join(ROOT, "bench", "scenes", "cornell.glint"))
    ap.add_argument("--scenes", nargs="*", default=None, help="default: bench/scenes/*.glint")
    ap.add_argument("--json", default=os.path.join(ROOT, "bench", "reports", "denoise_results.json"))
    ap.add_argument("--markdown", metavar="JSON", help="print the tables of an earlier run and exit")
    a = ap.parse_args()
    if a.markdown:
        print(markdown(json.load(open(a.markdown))))
        return
    scenes = a.scenes or sorted(glob.glob(os.path.join(ROOT, "bench", "scenes", "*.glint")))
    work = tempfile.mkdtemp(prefix="glint-denoise-bench-")
    result = {"width": a.width, "ref_spp": a.ref_spp, "seed": a.seed, "scenes": {}, "timing": []}
    for project in scenes:
        name = os.path.splitext(os.path.basename(project))[0]
        ref_path = os.path.join(work, f"{name}_ref.exr")
        run(a.glint, project, ref_path, a.width, REF_SEED, ["--spp", str(a.ref_spp)])
        ref = layers(ref_path)[""]
        rows = []
        for spp in a.spp:
            d_path = os.path.join(work, f"{name}_{spp}_denoised.exr")
            d = run(a.glint, project, d_path, a.width, a.seed, ["--spp", str(spp), "--denoise"])
            img = layers(d_path)
            total = d["seconds"] + d["denoise_seconds"]
            r_path = os.path.join(work, f"{name}_{spp}_raw.exr")
            r = run(a.glint, project, r_path, a.width, a.seed, ["--time", f"{total:.6f}"])
            raw = layers(r_path)[""]
            row = {"spp": spp, "trace_seconds": d["seconds"], "denoise_seconds": d["denoise_seconds"],
                   "device": d["device"], "raw_spp": r["spp"], "raw_seconds": r["seconds"],
                   "denoised": errors(img[""], ref), "noisy_same_spp": errors(img["noisy"], ref),
                   "raw_same_time": errors(raw, ref)}
            rows.append(row)
            print(f"{name:20s} {spp:4d} spp + denoise: {total:6.2f} s relMSE {row['denoised']['relmse']:.4g} "
                  f"FLIP {row['denoised']['flip']:.4f} | raw {r['spp']:5d} spp in {r['seconds']:.2f} s: "
                  f"relMSE {row['raw_same_time']['relmse']:.4g} FLIP {row['raw_same_time']['flip']:.4f}",
                  flush=True)
        result["scenes"][name] = rows
    for size in a.sizes:
        w, h = (int(v) for v in size.split("x"))
        for quality in ("high", "fast"):
            out = os.path.join(work, f"timing_{size}_{quality}.exr")
            t = run(a.glint, a.timing_scene, out, w, a.seed,
                    ["--height", str(h), "--spp", "1", "--denoise", "--denoise-quality", quality])
            result["timing"].append({"size": size, "quality": quality, "seconds": t["denoise_seconds"],
                                     "device": t["device"]})
            print(f"denoise {size} {quality}: {t['denoise_seconds']:.2f} s on the {t['device']}", flush=True)
    with open(a.json, "w") as f:
        json.dump(result, f, indent=1)
    print(f"wrote {a.json}")


if __name__ == "__main__":
    main()
