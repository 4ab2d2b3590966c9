#!/usr/bin/env python3
"""Per-sample error of the samplers: RMSE of `glint render` at a few samples per pixel against a
high-spp reference, for `--sampler pcg` and `--sampler sobol`, over several seeds.

    python3 bench/tools/qmc_gain.py                         # direct-light Cornell box (below)
    python3 bench/tools/qmc_gain.py --project bench/scenes/env_dof.glint --keep-materials \
        --keep-bounces

By default the scene is the Cornell box of projects/ with every material matte (colour and
emission kept) and max_bounces 1: direct lighting only, the case of Burley 2020, "Practical
Hash-based Owen Scrambling", JCGT 9(4), Fig. 1. Needs numpy only (the EXR reader is here).

Besides the RMSE it prints the RMSE of the mean of all seeds' images times sqrt(seeds), which
for independent seeds is the per-seed RMSE (seeds that share part of their error give more), and
the RMSE without the pixels next to a directly seen emitter (reference above 2), which at low
spp hold most of the squared error of the Cornell box.
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import time
import zlib

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def read_exr(path):
    """RGB of a scanline float32 EXR, uncompressed or ZIP (what Glint's writer produces)."""
    with open(path, "rb") as f:
        data = f.read()
    if struct.unpack_from("<I", data, 0)[0] != 20000630:
        raise ValueError(path + ": not an EXR")
    pos = 8
    channels, window, compression = [], None, 0
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        pos = end + 1
        end = data.index(b"\0", pos)
        pos = end + 1
        size = struct.unpack_from("<i", data, pos)[0]
        pos += 4
        value = data[pos:pos + size]
        pos += size
        if name == "channels":
            q = 0
            while value[q] != 0:
                e = value.index(b"\0", q)
                cname = value[q:e].decode()
                ptype = struct.unpack_from("<i", value, e + 1)[0]
                if ptype != 2:
                    raise ValueError(path + ": only float32 channels are read")
                channels.append(cname)
                q = e + 1 + 16
        elif name == "dataWindow":
            window = struct.unpack_from("<4i", value, 0)
        elif name == "compression":
            compression = value[0]
    pos += 1
    x0, y0, x1, y1 = window
    w, h = x1 - x0 + 1, y1 - y0 + 1
    lines = {0: 1, 2: 1, 3: 16}[compression]
    blocks = (h + lines - 1) // lines
    offsets = struct.unpack_from("<%dQ" % blocks, data, pos)
    img = np.zeros((h, len(channels), w), np.float32)
    for off in offsets:
        y, size = struct.unpack_from("<ii", data, off)
        raw = data[off + 8:off + 8 + size]
        n = min(lines, y1 + 1 - y)
        expected = n * len(channels) * w * 4
        if compression != 0 and size < expected:
            t = np.frombuffer(zlib.decompress(raw), np.uint8).astype(np.int32)
            t = (np.cumsum(t - 128) + 128) & 0xFF  # undo the predictor, t[i] += t[i-1] - 128
            t = t.astype(np.uint8)
            half = (len(t) + 1) // 2
            out = np.empty_like(t)
            out[0::2], out[1::2] = t[:half], t[half:]
            raw = out.tobytes()
        block = np.frombuffer(raw, "<f4").reshape(n, len(channels), w)
        img[y - y0:y - y0 + n] = block
    img = img.transpose(0, 2, 1)
    return np.stack([img[..., channels.index(c)] for c in "RGB"], axis=-1).astype(np.float64)


def make_variant(project, out_path, matte, max_bounces):
    with open(project) as f:
        p = json.load(f)
    if matte:
        for m in p["materials"]:
            keep = {k: m[k] for k in ("name", "color", "emission", "color_texture") if k in m}
            m.clear()
            m.update(keep)
            m["type"] = "matte"
    if max_bounces is not None:
        p["render"]["max_bounces"] = max_bounces
    # Assets resolve against the project's folder: keep relative paths working.
    base = os.path.dirname(os.path.abspath(project))
    def fix(v):
        if isinstance(v, str) and not os.path.isabs(v) and os.path.exists(os.path.join(base, v)):
            return os.path.join(base, v)
        return v
    if isinstance(p.get("environment"), dict) and p["environment"].get("texture"):
        p["environment"]["texture"] = fix(p["environment"]["texture"])
    for m in p.get("materials", []):
        for k, v in list(m.items()):
            if k.endswith("texture"):
                m[k] = fix(v)
    with open(out_path, "w") as f:
        json.dump(p, f, indent=1)


def render(glint, project, out, spp, seed, sampler, size, extra):
    cmd = [glint, "render", project, "-o", out, "--spp", str(spp), "--seed", str(seed),
           "--width", str(size), "--height", str(size), "--sampler", sampler] + extra
    t = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("failed: " + " ".join(cmd) + "\n" + r.stderr)
    return time.perf_counter() - t


def rmse(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--project", default=os.path.join(ROOT, "projects", "cornell_box.glint"))
    ap.add_argument("--keep-materials", action="store_true", help="do not make every material matte")
    ap.add_argument("--keep-bounces", action="store_true", help="keep the project's max_bounces (else 1)")
    ap.add_argument("--glint", default=os.path.join(ROOT, "build", "glint"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build-bench", "qmc"))
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", type=int, nargs="+", default=[16])
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--ref-spp", type=int, default=16384)
    ap.add_argument("--samplers", nargs="+", default=["pcg", "sobol"])
    ap.add_argument("--extra", nargs=argparse.REMAINDER, default=[], help="more glint render arguments")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    name = os.path.splitext(os.path.basename(a.project))[0]
    scene = os.path.join(a.out, name + "_variant.glint")
    make_variant(a.project, scene, not a.keep_materials, None if a.keep_bounces else 1)

    # Two references, one per sampler (seeds apart from the test seeds): their difference is a
    # check that neither sampler is biased; the Sobol one (less noise) is the reference.
    refs = {}
    for s in a.samplers:
        path = os.path.join(a.out, "%s_ref_%s_%d.exr" % (name, s, a.ref_spp))
        if not os.path.exists(path):
            t = render(a.glint, scene, path, a.ref_spp, 1000003, s, a.size, a.extra)
            print("reference %s %d spp: %.1f s" % (s, a.ref_spp, t))
        refs[s] = read_exr(path)
    ref = refs["sobol"] if "sobol" in refs else refs[a.samplers[0]]
    if len(refs) == 2:
        print("RMSE between the two references: %.5f (both noisy; PCG's noise dominates)"
              % rmse(refs[a.samplers[0]], refs[a.samplers[1]]))

    # Pixels within one pixel of a directly seen emitter (reference luminance above 2).
    bright = ref.mean(axis=-1) > 2.0
    padded = np.pad(bright, 1)
    near_emitter = np.zeros_like(bright)
    for dy in range(3):
        for dx in range(3):
            near_emitter |= padded[dy:dy + bright.shape[0], dx:dx + bright.shape[1]]
    results = {}
    for spp in a.spp:
        for s in a.samplers:
            imgs, times = [], []
            for seed in range(1, a.seeds + 1):
                path = os.path.join(a.out, "%s_%s_%d_seed%d.exr" % (name, s, spp, seed))
                times.append(render(a.glint, scene, path, spp, seed, s, a.size, a.extra))
                imgs.append(read_exr(path))
            per_seed = [rmse(x, ref) for x in imgs]
            off = [float(np.sqrt(np.mean(((x - ref) ** 2)[~near_emitter]))) for x in imgs]
            mean_img = np.mean(imgs, axis=0)
            results[(spp, s)] = dict(rmse=float(np.mean(per_seed)), rmse_sd=float(np.std(per_seed, ddof=1)),
                                     rmse_of_mean=rmse(mean_img, ref), off=float(np.mean(off)),
                                     bias=float(np.mean(mean_img - ref)),
                                     time=float(np.median(times)))
    print("scene %s, %dx%d, RMSE against the %d-spp reference, %d seeds; %d pixels next to emitters"
          % (name, a.size, a.size, a.ref_spp, a.seeds, int(near_emitter.sum())))
    print("| spp | sampler | RMSE (mean of seeds) | sd | RMSE of the seeds' mean x sqrt(seeds) | RMSE away from emitters | mean error | median time s |")
    print("|---|---|---|---|---|---|---|---|")
    for (spp, s), r in results.items():
        print("| %d | %s | %.5f | %.5f | %.5f | %.5f | %+.2e | %.2f |" % (
            spp, s, r["rmse"], r["rmse_sd"], r["rmse_of_mean"] * np.sqrt(a.seeds), r["off"],
            r["bias"], r["time"]))
    if "pcg" in a.samplers and "sobol" in a.samplers:
        for spp in a.spp:
            p, q = results[(spp, "pcg")], results[(spp, "sobol")]
            print("%d spp: RMSE pcg / sobol = %.2f (away from emitters %.2f)" % (spp, p["rmse"] / q["rmse"], p["off"] / q["off"]))


if __name__ == "__main__":
    main()
