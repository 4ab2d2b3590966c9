#!/usr/bin/env python3
"""Samples per second against the number of primitives, plain loop against BVH.

For each size N (default 10, 100, 1e3, 1e4, 1e5, 1e6) a scene of N spheres on a grid with
N/100 small quads and a floor quad is written to --work, and rendered by `glint render` with
`--accel loop` and `--accel bvh` (--repeats times each, the median kept) at --width x --width
pixels and --spp samples per pixel. Samples per second come from the line the CLI prints
(trace time only: loading, packing, the BVH build and shader compilation are outside its clock);
the BVH's build time is the one the CLI prints ("built in ... ms").

Mesa 22's llvmpipe stops a shader's loops after 65535 iterations in all (renderer/loop_budget.h):
the loop's figures are reported only where one of its samples fits, (max_bounces + 2) x
(3 x (N + 2) + 64) <= 65535, and marked invalid above (its images are wrong there). On another
driver every size is valid; --max-loop bounds the sizes the loop is run at (it is slow).

Writes a Markdown table and an SVG plot (no Python packages needed):
  python3 bench/tools/scale.py                       # bench/reports/SCALING.md, bench/reports/scaling.svg
  python3 bench/tools/scale.py --sizes 10,1000 --out /tmp/s.md
"""
import argparse
import math
import os
import platform
import re
import statistics
import subprocess
import sys
import datetime

HERE = os.path.dirname(os.path.abspath(__file__))  # bench/tools
ROOT = os.path.dirname(os.path.dirname(HERE))
LOOP_LIMIT = 65535


def loop_fits_llvmpipe(n, bounces):
    return (bounces + 2) * (3 * (n + 2) + 64) <= LOOP_LIMIT


def write_scene(path, n, bounces):
    """N spheres on a square grid over a fixed 20 x 20 floor (a deterministic jitter), N // 100
    small quads above it. The camera and the extent are the same for every N and the shapes
    shrink with the spacing, so every image shows the same kind of field and only the number of
    shapes changes (the BVH's cost should then grow with log N)."""
    side = max(1, math.ceil(math.sqrt(n)))
    half = 10.0
    spacing = 2 * half / side
    state = 12345

    def rnd():  # xorshift32 in [0, 1)
        nonlocal state
        state ^= (state << 13) & 0xFFFFFFFF
        state ^= state >> 17
        state ^= (state << 5) & 0xFFFFFFFF
        return state / 2 ** 32

    kinds = ["matte", "glossy", "metal", "matte", "lamp"]
    with open(path, "w") as f:
        f.write('{"format": "glint-project", "version": 1,\n')
        f.write('"camera": {"position": [0, 9, 16], "target": [0, 0, -1], "up": [0, 1, 0], '
                '"vfov_deg": 50, "aperture_radius": 0, "focus_distance": 5},\n')
        f.write('"film": {"width": 64, "height": 64}, "render": {"max_bounces": %d, "seed": 0},\n' % bounces)
        f.write('"environment": {"color": [0.6, 0.7, 0.9], "texture": null, "intensity": 1, "rotation_deg": 0},\n')
        f.write('"materials": [{"name": "matte", "type": "matte", "color": [0.8, 0.4, 0.2]},'
                ' {"name": "glossy", "type": "glossy", "color": [0.2, 0.4, 0.8], "roughness": 0.3},'
                ' {"name": "metal", "type": "reflective", "color": [0.9, 0.8, 0.5], "roughness": 0.2},'
                ' {"name": "lamp", "type": "matte", "color": [0.5, 0.5, 0.5], "emission": [3, 2.5, 2]},'
                ' {"name": "floor", "type": "matte", "color": [0.5, 0.5, 0.5]}],\n')
        f.write('"spheres": [\n')
        for i in range(n):
            x = (i % side + 0.5) * spacing - half + 0.3 * spacing * (rnd() - 0.5)
            z = (i // side + 0.5) * spacing - half + 0.3 * spacing * (rnd() - 0.5)
            r = (0.2 + 0.2 * rnd()) * spacing
            f.write('%s{"name": "s%d", "center": [%.6g, %.6g, %.6g], "radius": %.6g, "material": "%s"}\n'
                    % ("," if i else "", i, x, r, z, r, kinds[i % len(kinds)]))
        f.write('],\n"quads": [\n')
        f.write('{"name": "floor", "material": "floor", "corners": [[%g, 0, %g], [%g, 0, %g], [%g, 0, %g], [%g, 0, %g]]}\n'
                % (-half, -half, -half, half, half, -half, half, half))
        q = 1.5 * spacing  # quads: small panels just above the spheres
        for i in range(n // 100):
            x = (rnd() - 0.5) * 2 * half
            z = (rnd() - 0.5) * 2 * half
            y = spacing * (1 + 2 * rnd())
            f.write(',{"name": "q%d", "material": "metal", "corners": [[%.6g, %.6g, %.6g], [%.6g, %.6g, %.6g], '
                    '[%.6g, %.6g, %.6g], [%.6g, %.6g, %.6g]]}\n'
                    % (i, x, y, z, x, y + q, z, x + q, y, z + 0.2 * q, x + q, y + q, z + 0.2 * q))
        f.write(']}\n')


def render(glint, scene, accel, width, spp, out):
    cmd = [glint, "render", scene, "-o", out, "--width", str(width), "--height", str(width),
           "--spp", str(spp), "--accel", accel, "--verbose"]  # --verbose: the device and the BVH
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("%s failed:\n%s" % (" ".join(cmd), p.stderr))
    m = re.search(r"wrote .* \((\d+)x(\d+), (\d+) spp, ([\d.]+) s, ([\d.]+) spp/s", p.stderr)
    if not m:
        raise RuntimeError("no timing line in:\n" + p.stderr)
    result = {"spp_per_s": float(m.group(5)), "seconds": float(m.group(4)),
              "llvmpipe": "llvmpipe" in p.stderr}
    d = re.search(r"warning: (\d+) samples were discarded", p.stderr)
    result["discarded"] = int(d.group(1)) if d else 0
    b = re.search(r"closest hits by BVH: (\d+) nodes, depth (\d+), built in ([\d.]+) ms", p.stderr)
    if b:
        result.update(nodes=int(b.group(1)), depth=int(b.group(2)), build_ms=float(b.group(3)))
    g = re.search(r"OpenGL .* on (.*) \(", p.stderr)
    result["device"] = g.group(1) if g else "?"
    return result


def svg_plot(rows, path):
    """Log-log samples/s against N, both methods."""
    w, h, m = 560, 360, 60
    pts = [(r["n"], r[k]) for r in rows for k in ("loop", "bvh") if r.get(k)]
    xs = [math.log10(n) for n, _ in pts]
    ys = [math.log10(v) for _, v in pts]
    x0, x1 = min(xs) - 0.2, max(xs) + 0.2
    y0, y1 = math.floor(min(ys)), math.ceil(max(ys))
    if y1 == y0:
        y1 += 1
    X = lambda v: m + (math.log10(v) - x0) / (x1 - x0) * (w - 1.5 * m)
    Y = lambda v: h - m + (y0 - math.log10(v)) / (y1 - y0) * (h - 1.7 * m)
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="12">' % (w, h),
           '<rect width="100%" height="100%" fill="white"/>']
    for e in range(int(math.ceil(x0)), int(math.floor(x1)) + 1):
        x = X(10 ** e)
        out.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ddd"/>' % (x, m * 0.7, x, h - m))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">1e%d</text>' % (x, h - m + 16, e))
    for e in range(y0, y1 + 1):
        y = Y(10 ** e)
        out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ddd"/>' % (m, y, w - m / 2, y))
        out.append('<text x="%d" y="%.1f" text-anchor="end">1e%d</text>' % (m - 6, y + 4, e))
    out.append('<text x="%d" y="%d" text-anchor="middle">primitives</text>' % (w / 2, h - 18))
    out.append('<text x="16" y="%d" transform="rotate(-90 16 %d)" text-anchor="middle">samples per pixel per second</text>' % (h / 2, h / 2))
    for key, colour in (("loop", "#d62728"), ("bvh", "#1f77b4")):
        p = [(X(r["n"]), Y(r[key])) for r in rows if r.get(key)]
        if not p:
            continue
        out.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>' % (colour, " ".join("%.1f,%.1f" % q for q in p)))
        for q in p:
            out.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s"/>' % (q[0], q[1], colour))
        out.append('<text x="%.1f" y="%.1f" fill="%s">%s</text>' % (p[-1][0] + 6, p[-1][1] + 4, colour, key))
    out.append('</svg>')
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def fit_log(rows):
    """Least squares of seconds per sample (1 / spp/s) against log10 N for the BVH."""
    pts = [(math.log10(r["n"]), 1.0 / r["bvh"]) for r in rows if r.get("bvh")]
    if len(pts) < 3:
        return None
    n = len(pts)
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
    b = sxy / sxx
    a = my - b * mx
    ss = sum((p[1] - my) ** 2 for p in pts)
    res = sum((p[1] - a - b * p[0]) ** 2 for p in pts)
    return a, b, 1 - res / ss if ss > 0 else 1.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="10,100,1000,10000,100000,1000000", help="comma-separated sphere counts")
    ap.add_argument("--width", type=int, default=64, help="image width and height (default 64)")
    ap.add_argument("--spp", type=int, default=4, help="samples per pixel per render (default 4)")
    ap.add_argument("--bounces", type=int, default=4, help="max_bounces of the scenes (default 4)")
    ap.add_argument("--repeats", type=int, default=3, help="renders per point; the median is kept (default 3)")
    ap.add_argument("--max-loop", type=int, default=100000, help="largest N the loop is run at (default 1e5)")
    ap.add_argument("--glint", default=os.path.join(ROOT, "build", "glint"), help="the glint executable")
    ap.add_argument("--work", default=os.path.join(ROOT, "build-bench", "scale"), help="scenes and renders")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "reports", "SCALING.md"), help="Markdown report (the SVG goes beside it)")
    args = ap.parse_args()
    sizes = [int(float(s)) for s in args.sizes.split(",")]
    os.makedirs(args.work, exist_ok=True)
    rows = []
    device = "?"
    llvmpipe = False
    for n in sizes:
        scene = os.path.join(args.work, "spheres_%d.glint" % n)
        write_scene(scene, n, args.bounces)
        row = {"n": n, "quads": n // 100 + 1}
        # The BVH first: its run tells which driver this is, and on llvmpipe the loop is not run
        # where its image would be wrong.
        for accel in ("bvh", "loop"):
            if accel == "loop" and n > args.max_loop:
                continue
            if accel == "loop" and llvmpipe and not loop_fits_llvmpipe(n + n // 100 + 1, args.bounces):
                row["loop_invalid"] = True
                print("N=%d loop: exceeds llvmpipe's loop limit, not run" % n, flush=True)
                continue
            runs = [render(args.glint, scene, accel, args.width, args.spp, os.path.join(args.work, "out.exr"))
                    for _ in range(args.repeats)]
            device, llvmpipe = runs[0]["device"], runs[0]["llvmpipe"]
            row[accel] = statistics.median(r["spp_per_s"] for r in runs)
            row[accel + "_all"] = [r["spp_per_s"] for r in runs]
            if accel == "bvh":
                row.update(nodes=runs[0]["nodes"], depth=runs[0]["depth"],
                           build_ms=statistics.median(r["build_ms"] for r in runs),
                           discarded=max(r["discarded"] for r in runs))
            print("N=%d %s: %.2f spp/s (%s)" % (n, accel, row[accel], ", ".join("%.2f" % v for v in row[accel + "_all"])), flush=True)
        rows.append(row)

    svg = os.path.splitext(args.out)[0].replace("SCALING", "scaling") + ".svg"
    svg_plot(rows, svg)
    fit = fit_log(rows)
    lines = ["# Scaling: plain loop against BVH", "",
             "Written by `python3 bench/tools/scale.py %s` on %s, %s (%s), %d x %d pixels, %d spp per render, "
             "max_bounces %d, median of %d renders per point. Scenes: N spheres on a grid over a fixed "
             "floor, shrinking with N, N/100 small quads (`write_scene` in bench/tools/scale.py)."
             % (" ".join(sys.argv[1:]), datetime.date.today().isoformat(), device, platform.machine(),
                args.width, args.width, args.spp, args.bounces, args.repeats), "",
             "Samples per pixel per second are those `glint render` reports (trace passes only). "
             "BVH build: CPU time of the binned-SAH construction as printed by `glint render` "
             "(the scene's load and packing are not included). Timings on a shared machine are noisy: "
             "compare the two columns of one row (ratios), and see the individual runs below.", ""]
    if llvmpipe:
        lines += ["On llvmpipe the loop is run only where one sample stays within Mesa 22's limit of "
                  "65535 loop iterations, (max_bounces + 2) x (3 x (N + 2) + 64) <= 65535; above that "
                  "its image is wrong on Mesa 22 and it is not run (\"invalid\").", ""]
    lines += ["| spheres | quads | loop spp/s | BVH spp/s | BVH / loop | BVH nodes | depth | build ms | BVH discarded |",
              "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in rows:
        loop = "%.2f" % r["loop"] if r.get("loop") else ("invalid" if r.get("loop_invalid") else "not run")
        ratio = "%.2f" % (r["bvh"] / r["loop"]) if r.get("loop") and r.get("bvh") else ""
        lines.append("| %d | %d | %s | %.2f | %s | %d | %d | %.3g | %d of %d |" % (
            r["n"], r["quads"], loop, r["bvh"], ratio, r["nodes"], r["depth"], r["build_ms"],
            r["discarded"], args.width * args.width * args.spp))
    lines += ["", "![samples per second against primitives](%s)" % os.path.basename(svg), ""]
    lines += ["Individual runs (spp/s): " + "; ".join(
        "N=%d bvh %s%s" % (r["n"], ", ".join("%.2f" % v for v in r.get("bvh_all", [])),
                           (" loop " + ", ".join("%.2f" % v for v in r["loop_all"])) if r.get("loop_all") else "")
        for r in rows), ""]
    if fit:
        a, b, r2 = fit
        lines += ["BVH time per sample per pixel (1 / spp/s, for the whole %d x %d image) against log10 N "
                  "(least squares): %.4g + %.4g log10 N seconds, R^2 = %.3f." % (args.width, args.width, a, b, r2), ""]
    lines += ["BVH discarded: the most samples one render discarded (non-finite, or a traversal that "
              "reached its step cap, renderer/loop_budget.h), out of the samples it took.", ""]
    with open(args.out, "w") as f:
        f.write("\n".join(lines))
    print("wrote %s and %s" % (args.out, svg))


if __name__ == "__main__":
    main()
