#!/usr/bin/env python3
"""Glint project (.glint, format version 1) -> Mitsuba 3 scene dictionary (mi.load_dict).

Only scenes whose parts Mitsuba models the same way are exported; anything else raises
Unsupported with the reasons. What maps, and how (each checked by bench/tools/run.py's convention
test or by the Cornell/furnace comparisons in RESULTS.md):

- matte            -> twosided(diffuse)          (Glint shades both sides of every surface)
- reflective with colour exactly (1, 1, 1) and roughness < 0.03, no textures
                   -> twosided(conductor, material "none": specular reflectance 1). Glint's
                      mirror weight is Schlick F(colour, cos), which is 1 only for colour 1.
- refractive       -> dielectric (roughness < 0.03) or roughdielectric (distribution ggx,
                      alpha = roughness^2, visible-normal sampling), int_ior = ior,
                      ext_ior = 1, specular_transmittance = colour, specular_reflectance 1.
                      Not wrapped in twosided: the inside is a sphere's ball, and for a quad
                      the side opposite cross(p1 - p0, p2 - p0), which is also the back of
                      Mitsuba's face normal (one interface, as in Glint). Both renderers' shadow
                      rays stop at it.
- emission         -> area emitter. Mitsuba's area lights emit from the front side only; Glint's
                      emission leaves both sides. Quads are exported as two back-to-back
                      one-sided copies (a "sandwich"): the original, front along
                      cross(p1 - p0, p2 - p0), and a copy with reversed winding moved by a tiny
                      distance to its back. A ray from either side meets the copy facing it, so
                      both sides emit (and reflect) as in Glint. Emissive spheres emit outwards;
                      an inward-facing inner sphere is added only when the camera or another
                      shape is inside (otherwise the inside is never seen).
- quads            -> a two-triangle PLY mesh (p0, p1, p2), (p1, p3, p2) with face normals,
                      exactly Glint's triangles (also for non-planar corners)
- spheres          -> sphere
- environment      -> constant (colour * intensity) or envmap (texture, scale = intensity).
                      Mitsuba looks up u = atan2(v.x, -v.z) / 2pi, v = acos(v.y) / pi with
                      v = to_world^-1 d; Glint looks up u = atan2(d'.z, d'.x) / 2pi with
                      d' = R_y(-rotation) d. They agree for to_world = R_y(rotation - 90 deg).
                      Mitsuba also places the image's rows at v = i / (H - 1) (first and last
                      row on the poles) where Glint's GL_LINEAR lookup puts them at
                      (i + 0.5) / H with clamp-to-edge, so the exporter hands Mitsuba a
                      (2H + 1)-row image resampled so that Mitsuba's bilinear lookup equals
                      Glint's exactly (columns already agree: Mitsuba shifts u by half a texel).
- camera           -> perspective (pinhole) or thinlens (aperture_radius, focus_distance: both
                      put the sharp plane at that distance along the view axis), fov_axis "y",
                      look_at(position, target, up), near clip 1e-6 of the scene size.
- film             -> hdrfilm with a box filter of radius 0.5 (Glint averages uniformly
                      jittered samples inside each pixel), linear float RGB.
- integrator       -> path, max_depth = max_bounces + 1 (docs/DESIGN.md section 6), Russian roulette
                      from depth 5 as Mitsuba's default (unbiased; Glint has none).

Refused: glossy and transparent materials, rough or non-white mirrors, refractive materials
with ior 1 (Mitsuba refuses eta = 1) or with emission, any texture, coverage (opacity < 1).

Usage: mitsuba_export.py PROJECT.glint [-o OUT.exr --spp N --seed S --width W --height H]
"""
import argparse
import json
import math
import os
import struct
import sys
import time

import numpy as np

MATERIAL_DEFAULTS = {"type": "matte", "color": [0.8, 0.8, 0.8], "color_texture": None,
                     "emission": [0, 0, 0], "emission_texture": None, "roughness": 0,
                     "roughness_texture": None, "ior": 1.5, "opacity": 1}
CAMERA_DEFAULTS = {"position": [0, 1, 5], "target": [0, 0.5, 0], "up": [0, 1, 0], "vfov_deg": 40,
                   "aperture_radius": 0, "focus_distance": 5}
ENV_DEFAULTS = {"color": [0.5, 0.5, 0.5], "texture": None, "intensity": 1, "rotation_deg": 0}


class Unsupported(Exception):
    """The project uses something Mitsuba does not model the way Glint does."""


def _mitsuba():
    import mitsuba as mi
    if mi.variant() is None:
        mi.set_variant(choose_variant()[0])
    return mi


_PROBE = ("import drjit as dr\nfrom drjit.llvm import Float\n"
          "x = dr.minimum(dr.maximum(dr.arange(Float, 8) - 2, 0), 3)\n"
          "assert list(x) == [0, 0, 0, 1, 2, 3, 3, 3]\n")


def _llvm_works(path):
    """Dr.Jit 1.x emits llvm.minimum/maximum, which LLVM 15's x86 back end cannot select (it
    aborts the process), so each candidate library is tried in a child process."""
    import subprocess
    env = dict(os.environ, DRJIT_LIBLLVM_PATH=path)
    try:
        r = subprocess.run([sys.executable, "-c", _PROBE], env=env, capture_output=True, timeout=120)
    except subprocess.TimeoutExpired:
        return False
    return r.returncode == 0


def llvm_candidates():
    import glob
    here = os.path.dirname(os.path.abspath(__file__))
    c = []
    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        c.append(os.environ["DRJIT_LIBLLVM_PATH"])
    c += sorted(glob.glob(os.path.join(here, "..", ".venv", "llvm", "usr", "lib", "*", "libLLVM*.so*")),
                reverse=True)
    c += sorted(glob.glob("/usr/lib/*/libLLVM-*.so*") + glob.glob("/usr/lib/llvm-*/lib/libLLVM*.so*"),
                key=lambda p: [int(x) for x in __import__("re").findall(r"\d+", os.path.basename(p))][:1] or [0],
                reverse=True)
    seen, out = set(), []
    for p in c:
        if os.path.exists(p) and os.path.realpath(p) not in seen:
            seen.add(os.path.realpath(p))
            out.append(p)
    return out


def choose_variant(log=None):
    """("llvm_ad_rgb", libLLVM path) when a libLLVM that works with this Dr.Jit is found, else
    ("scalar_rgb", None). Sets DRJIT_LIBLLVM_PATH for this process. The choice is cached in the
    environment (GLINT_BENCH_MITSUBA_VARIANT) for child processes."""
    if os.environ.get("GLINT_BENCH_MITSUBA_VARIANT"):
        v = os.environ["GLINT_BENCH_MITSUBA_VARIANT"]
        return v, os.environ.get("DRJIT_LIBLLVM_PATH") if v.startswith("llvm") else None
    chosen = None
    for p in llvm_candidates():
        ok = _llvm_works(p)
        if log:
            log(f"  libLLVM {p}: {'works' if ok else 'fails the Dr.Jit probe'}")
        if ok:
            chosen = p
            break
    if chosen:
        os.environ["DRJIT_LIBLLVM_PATH"] = chosen
        os.environ["GLINT_BENCH_MITSUBA_VARIANT"] = "llvm_ad_rgb"
        return "llvm_ad_rgb", chosen
    os.environ["GLINT_BENCH_MITSUBA_VARIANT"] = "scalar_rgb"
    return "scalar_rgb", None


def load_project(path):
    with open(path) as f:
        doc = json.load(f)
    doc["_base_dir"] = os.path.dirname(os.path.abspath(path))
    doc["_file"] = path
    return doc


def _v(x):
    return np.asarray(x, dtype=np.float64)


def unsupported_reasons(doc):
    """Why the project cannot be exported identically; [] when it can."""
    reasons = []
    for i, m in enumerate(doc.get("materials", [])):
        m = {**MATERIAL_DEFAULTS, **m}
        name = f"materials[{i}] ({m.get('name', '?')})"
        t = m["type"]
        if t == "glossy":
            reasons.append(f"{name}: glossy (Schlick-weighted GGX coat over Lambert: no Mitsuba "
                           "plugin has the same coat/base split)")
        elif t == "transparent":
            reasons.append(f"{name}: transparent (Glint's thin glass with Schlick Fresnel and "
                           "unbent transmission; Mitsuba's thindielectric uses exact Fresnel and "
                           "inter-reflections)")
        elif t == "reflective":
            if [float(c) for c in m["color"]] != [1.0, 1.0, 1.0] or not float(m["roughness"]) < 0.03:
                reasons.append(f"{name}: reflective with colour {m['color']} / roughness "
                               f"{m['roughness']} (only a white perfect mirror matches: Glint "
                               "uses Schlick F(colour), Mitsuba's conductors use complex IORs)")
        elif t == "refractive":
            if float(m["ior"]) == 1.0:
                reasons.append(f"{name}: refractive with ior 1 (Mitsuba's dielectrics refuse "
                               "eta = 1; the surface is invisible)")
            if _is_emissive(m):
                reasons.append(f"{name}: refractive and emissive (Mitsuba's area lights on a "
                               "one-sided dielectric emit from its front only)")
        elif t != "matte":
            reasons.append(f"{name}: unknown type {t}")
        for key in ("color_texture", "emission_texture", "roughness_texture"):
            if m.get(key):
                reasons.append(f"{name}: {key} (textures are not exported)")
        if float(m["opacity"]) < 1:
            reasons.append(f"{name}: opacity {m['opacity']} (stochastic coverage is not exported)")
    return reasons


def _is_emissive(m):
    return any(float(c) > 0 for c in m["emission"])


def _write_ply(path, verts, faces):
    with open(path, "wb") as f:
        f.write(b"ply\nformat binary_little_endian 1.0\n")
        f.write(f"element vertex {len(verts)}\n".encode())
        f.write(b"property float x\nproperty float y\nproperty float z\n")
        f.write(f"element face {len(faces)}\n".encode())
        f.write(b"property list uchar int vertex_indices\nend_header\n")
        for v in verts:
            f.write(struct.pack("<3f", *[float(c) for c in v]))
        for fc in faces:
            f.write(struct.pack("<B3i", 3, *fc))


def glint_env_to_mitsuba_rows(img):
    """(H, W, 3) lat-long image -> (2H + 1, W, 3): Mitsuba's row-on-pole bilinear lookup of the
    result equals Glint's (i + 0.5) / H, clamp-to-edge bilinear lookup of the input."""
    h = img.shape[0]
    out = np.empty((2 * h + 1,) + img.shape[1:], dtype=np.float32)
    out[1::2] = img
    above = img[np.clip(np.arange(h + 1) - 1, 0, h - 1)]
    below = img[np.clip(np.arange(h + 1), 0, h - 1)]
    out[0::2] = 0.5 * (above + below)
    return out


def scene_size(doc):
    pts = [_v(doc.get("camera", {}).get("position", CAMERA_DEFAULTS["position"]))]
    for s in doc.get("spheres", []):
        c, r = _v(s.get("center", [0, 0, 0])), float(s.get("radius", 1))
        pts += [c - r, c + r]
    for q in doc.get("quads", []):
        pts += [_v(p) for p in q["corners"]]
    pts = np.array(pts)
    return float(np.max(pts.max(0) - pts.min(0))) or 1.0


# Mitsuba's samplers that the bench races: `independent` (uniform random numbers) and its
# low-discrepancy ones (https://mitsuba.readthedocs.io/en/stable/src/generated/plugins_samplers.html).
# `ldsampler` rounds the sample count up to a power of two and `orthogonal` to the square of a
# prime; `samples_per_pixel` says what a scene really traced.
SAMPLERS = ("independent", "ldsampler", "multijitter", "orthogonal")


def export(doc, width=None, height=None, spp=16, seed=0, mesh_dir=None, rotation_offset_deg=-90.0,
           resample_env_rows=True, sampler="independent"):
    """Returns (scene dict, notes). Raises Unsupported. `sampler` is one of SAMPLERS.
    `rotation_offset_deg` and `resample_env_rows` exist for the convention test only (to show
    that the wrong ones fail)."""
    if sampler not in SAMPLERS:
        raise ValueError(f"unknown Mitsuba sampler {sampler!r} (one of {', '.join(SAMPLERS)})")
    reasons = unsupported_reasons(doc)
    if reasons:
        raise Unsupported("; ".join(reasons))
    mi = _mitsuba()
    T = mi.ScalarTransform4f
    notes = []
    base = doc["_base_dir"]
    if mesh_dir is None:
        import tempfile
        mesh_dir = tempfile.mkdtemp(prefix="glint_mitsuba_")
    os.makedirs(mesh_dir, exist_ok=True)
    film = doc.get("film", {})
    width = int(width or film.get("width", 960))
    height = int(height or film.get("height", 540))
    cam = {**CAMERA_DEFAULTS, **doc.get("camera", {})}
    size = scene_size(doc)
    eye = _v(cam["position"])

    sensor = {
        "type": "thinlens" if float(cam["aperture_radius"]) > 0 else "perspective",
        "fov": float(cam["vfov_deg"]), "fov_axis": "y",
        "near_clip": 1e-6 * size, "far_clip": 1e3 * size + 1e6,
        "to_world": T().look_at(origin=[float(c) for c in cam["position"]],
                                target=[float(c) for c in cam["target"]],
                                up=[float(c) for c in cam["up"]]),
        "film": {"type": "hdrfilm", "width": width, "height": height, "pixel_format": "rgb",
                 "component_format": "float32", "rfilter": {"type": "box"}},
        "sampler": {"type": sampler, "sample_count": int(spp), "seed": int(seed)},
    }
    if sensor["type"] == "thinlens":
        sensor["aperture_radius"] = float(cam["aperture_radius"])
        sensor["focus_distance"] = float(cam["focus_distance"])

    max_bounces = int(doc.get("render", {}).get("max_bounces", 8))
    d = {"type": "scene",
         "integrator": {"type": "path", "max_depth": max_bounces + 1, "hide_emitters": False},
         "sensor": sensor}

    mats = {m["name"]: {**MATERIAL_DEFAULTS, **m} for m in doc.get("materials", [])}

    def bsdf(m):
        rgb = {"type": "rgb", "value": [float(c) for c in m["color"]]}
        if m["type"] == "refractive":
            out = {"type": "dielectric", "int_ior": float(m["ior"]), "ext_ior": 1.0,
                   "specular_transmittance": rgb}
            if float(m["roughness"]) >= 0.03:
                out.update(type="roughdielectric", distribution="ggx",
                           alpha=float(m["roughness"]) ** 2, sample_visible=True)
            return out
        if m["type"] == "matte":
            inner = {"type": "diffuse", "reflectance": rgb}
        else:  # white perfect mirror (checked above)
            inner = {"type": "conductor", "material": "none"}
        return {"type": "twosided", "material": inner}

    def emitter(m):
        return {"type": "area", "radiance": {"type": "rgb", "value": [float(c) for c in m["emission"]]}}

    inside_points = [eye] + [_v(q["corners"][k]) for q in doc.get("quads", []) for k in range(4)]
    for i, s in enumerate(doc.get("spheres", [])):
        m = mats[s["material"]]
        c, r = [float(x) for x in s.get("center", [0, 0, 0])], float(s.get("radius", 1))
        shape = {"type": "sphere", "center": c, "radius": r, "bsdf": bsdf(m)}
        if _is_emissive(m):
            shape["emitter"] = emitter(m)
            others = inside_points + [_v(o.get("center", [0, 0, 0])) for j, o in
                                      enumerate(doc.get("spheres", [])) if j != i]
            if any(np.linalg.norm(p - _v(c)) < r for p in others):
                d[f"sphere_{i}_inner"] = {"type": "sphere", "center": c, "radius": r * (1 - 1e-5),
                                          "flip_normals": True, "bsdf": bsdf(m), "emitter": emitter(m)}
                notes.append(f"spheres[{i}]: something is inside an emissive sphere; added an "
                             "inward-emitting inner sphere")
        d[f"sphere_{i}"] = shape
        if r > 1e3 * max(1e-30, np.linalg.norm(eye - _v(c)) - r) and mi.variant().startswith("llvm"):
            notes.append(f"spheres[{i}] (radius {r:g}) is huge next to its distance from the "
                         "camera: Mitsuba's float32 sphere intersection (llvm variants) loses "
                         "light on it; use scalar_rgb for this scene")

    for i, q in enumerate(doc.get("quads", [])):
        m = mats[q["material"]]
        p = [_v(c) for c in q["corners"]]
        path = os.path.join(mesh_dir, f"quad_{i}.ply")
        _write_ply(path, p, [(0, 1, 2), (1, 3, 2)])
        shape = {"type": "ply", "filename": path, "face_normals": True, "bsdf": bsdf(m)}
        if _is_emissive(m):
            shape["emitter"] = emitter(m)
            n = np.cross(p[1] - p[0], p[2] - p[0])
            n /= np.linalg.norm(n)
            eps = 1e-5 * (1.0 + max(float(np.abs(x).max()) for x in p))
            back = [x - eps * n for x in p]
            bpath = os.path.join(mesh_dir, f"quad_{i}_back.ply")
            _write_ply(bpath, back, [(0, 2, 1), (1, 2, 3)])
            d[f"quad_{i}_back"] = {"type": "ply", "filename": bpath, "face_normals": True,
                                   "bsdf": bsdf(m), "emitter": emitter(m)}
        d[f"quad_{i}"] = shape

    env = {**ENV_DEFAULTS, **doc.get("environment", {})}
    if env["texture"]:
        path = env["texture"] if os.path.isabs(env["texture"]) else os.path.join(base, env["texture"])
        img = np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32,
                                               srgb_gamma=False), copy=True)
        if resample_env_rows:
            img = glint_env_to_mitsuba_rows(img)
        d["environment"] = {"type": "envmap", "bitmap": mi.Bitmap(img.astype(np.float32)),
                            "scale": float(env["intensity"]),
                            "to_world": T().rotate([0, 1, 0], float(env["rotation_deg"]) + rotation_offset_deg)}
    else:
        rgb = [float(c) * float(env["intensity"]) for c in env["color"]]
        if any(c > 0 for c in rgb):
            d["environment"] = {"type": "constant", "radiance": {"type": "rgb", "value": rgb}}
    return d, notes


def render(scene_dict, spp, seed):
    """Renders with Mitsuba; returns (H x W x 3 float32 image, seconds of mi.render)."""
    mi = _mitsuba()
    scene = scene_dict if not isinstance(scene_dict, dict) else mi.load_dict(scene_dict)
    t0 = time.perf_counter()
    img = mi.render(scene, spp=int(spp), seed=int(seed))
    out = np.array(img, dtype=np.float32)  # forces evaluation
    return out, time.perf_counter() - t0


def samples_per_pixel(scene):
    """The sample count the scene's sampler last used (after its own rounding)."""
    return int(scene.sensors()[0].sampler().sample_count())


def write_exr(path, img):
    mi = _mitsuba()
    mi.Bitmap(np.ascontiguousarray(img, dtype=np.float32)).write(path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("project")
    ap.add_argument("-o", "--output")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--width", type=int)
    ap.add_argument("--height", type=int)
    a = ap.parse_args(argv)
    doc = load_project(a.project)
    film = doc.get("film", {})
    w, h = a.width, a.height
    if w and not h:
        h = max(1, round(w * film.get("height", 540) / film.get("width", 960)))
    try:
        d, notes = export(doc, w, h, a.spp, a.seed)
    except Unsupported as e:
        print(f"{a.project}: not exported: {e}", file=sys.stderr)
        return 3
    for n in notes:
        print("note:", n, file=sys.stderr)
    print(f"mitsuba variant {_mitsuba().variant()}", file=sys.stderr)
    if a.output:
        img, secs = render(d, a.spp, a.seed)
        write_exr(a.output, img)
        print(f"wrote {a.output} ({img.shape[1]}x{img.shape[0]}, {a.spp} spp, {secs:.2f} s)",
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
