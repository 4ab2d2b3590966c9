"""Analytic check of the huge-sphere floor: which renderer is right near the horizon?

For a Lambertian floor that is a convex sphere under a constant sky, and far from every other
shape, the radiance leaving the floor is exactly albedo x sky (a convex surface never sees
itself, and a cosine-weighted hemisphere of constant radiance L gives albedo x L). A pixel whose
camera rays all either miss everything or hit the floor far from the other shapes therefore has
the expected value  f x albedo x sky + (1 - f) x sky,  with f the fraction of the pixel's area
whose rays hit the floor. f is computed here in double precision on a 64 x 64 grid per pixel
(the pinhole camera of shaders/lib/camera.glsl, box filter), with the hit test of a ray against
a sphere done as R^2 - |oc - (oc.d) d|^2 (no cancellation for R = 1e5; Hearn and Baker via
Ray Tracing Gems ch. 7). Pixels with a ray near a small sphere, or a floor hit closer than
`min_distance` to one (where the spheres' occlusion and reflections would count), are skipped.
"""
import json

import numpy as np

GRID = 64


def _frame(cam, width, height):
    pos = np.array(cam["position"], float)
    f = np.array(cam["target"], float) - pos
    f /= np.linalg.norm(f)
    r = np.cross(f, np.array(cam.get("up", [0, 1, 0]), float))
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    return pos, f, r, u, np.tan(np.radians(cam["vfov_deg"]) / 2), width / height


def _hits_sphere(pos, d, center, radius):
    oc = pos - center
    b = d @ oc
    perp = oc[None, :] - b[:, None] * d
    disc = radius * radius - np.sum(perp * perp, -1)
    hit = (disc >= 0) & (b < 0)
    t = np.where(hit, -b - np.sqrt(np.maximum(disc, 0)), np.inf)
    return hit, t


def expected_image(project_path, width, height, min_distance=30.0):
    """Expected linear RGB per pixel (NaN where the analytic value does not apply)."""
    doc = json.load(open(project_path))
    if doc.get("quads") or doc["camera"].get("aperture_radius", 0) > 0 or doc["environment"].get("texture"):
        raise ValueError("horizon check: needs spheres only, a pinhole camera and a constant sky")
    env = doc["environment"]
    sky = np.array(env["color"], float) * env.get("intensity", 1.0)
    materials = {m["name"]: m for m in doc["materials"]}
    floor, others = doc["spheres"][0], doc["spheres"][1:]
    if materials[floor["material"]]["type"] != "matte":
        raise ValueError("horizon check: the first sphere (the floor) must be matte")
    albedo = np.array(materials[floor["material"]]["color"], float)
    fc, fr = np.array(floor["center"], float), float(floor["radius"])
    pos, f, r, u, tan_half, aspect = _frame(doc["camera"], width, height)
    g = (np.arange(GRID) + 0.5) / GRID
    out = np.full((height, width, 3), np.nan)
    for j in range(height):
        fy = ((j + g) / height)[:, None].repeat(GRID, 1).ravel()
        for i in range(width):
            fx = ((i + g) / width)[None, :].repeat(GRID, 0).ravel()
            sx = (2 * fx - 1) * tan_half * aspect
            sy = (1 - 2 * fy) * tan_half
            d = f[None, :] + sx[:, None] * r + sy[:, None] * u
            d /= np.linalg.norm(d, axis=-1, keepdims=True)
            hit, t = _hits_sphere(pos, d, fc, fr)
            points = pos + np.where(hit, t, 0)[:, None] * d
            skip = False
            for s in others:
                c, rad = np.array(s["center"], float), float(s["radius"])
                near, _ = _hits_sphere(pos, d, c, 1.2 * rad)
                if near.any() or (hit & (np.linalg.norm(points - c, axis=-1) < min_distance)).any():
                    skip = True
                    break
            if not skip:
                frac = hit.mean()
                out[j, i] = frac * albedo * sky + (1 - frac) * sky
    return out


def compare(project_path, images):
    """Per-row mean of the green channel over the pixels the analytic value covers, for every
    row that shows floor, and the largest |image - expected| over those pixels per image."""
    h, w = next(iter(images.values())).shape[:2]
    exp = expected_image(project_path, w, h)
    ok = np.isfinite(exp[..., 0])
    sky_rows = [j for j in range(h) if ok[j].any() and np.allclose(exp[j][ok[j]], exp[0][ok[0]][0])]
    rows = []
    for j in range(h):
        if not ok[j].any() or j in sky_rows:
            continue
        row = {"row": j, "pixels": int(ok[j].sum()), "expected": float(exp[j][ok[j]][:, 1].mean())}
        for name, img in images.items():
            row[name] = float(img[j][ok[j]][:, 1].mean())
        rows.append(row)
    worst = {name: float(np.nanmax(np.abs(img[..., :3] - exp)[ok])) for name, img in images.items()}
    return {"rows": rows, "worst": worst, "pixels": int(ok.sum()),
            "floor_pixels": int(sum(r["pixels"] for r in rows))}


def main():
    import argparse
    import metrics
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("project")
    ap.add_argument("images", nargs="+", help="NAME=IMAGE.exr (linear, the project's aspect)")
    a = ap.parse_args()
    images = {s.split("=", 1)[0]: metrics.read_exr(s.split("=", 1)[1]) for s in a.images}
    res = compare(a.project, images)
    names = list(images)
    print("row pixels expected " + " ".join(names))
    for row in res["rows"]:
        print(f"{row['row']} {row['pixels']} {row['expected']:.4f} " +
              " ".join(f"{row[n]:.4f}" for n in names))
    print("largest |image - expected| over the", res["pixels"], "checked pixels:",
          ", ".join(f"{n} {v:.4g}" for n, v in res["worst"].items()))


if __name__ == "__main__":
    main()
