#!/usr/bin/env python3
"""Glint project (.glint, format version 1) -> Mitsuba 3 scene dictionary (mi.load_dict).

The scene is what `glint convert PROJECT.glint SCENE.xml` writes (renderer/mitsuba_writer.cpp,
docs/DESIGN.md section 13), read into a dictionary; this script adds the bench's policy (which
scenes are compared at all), its sampler choice and the resampled environment image.

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
- quads            -> a rectangle (a parallelogram with default uvs: the same two triangles'
                      plane) or a two-triangle OBJ mesh (p0, p1, p2), (p1, p3, p2) with face
                      normals, exactly Glint's triangles (also for non-planar corners)
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
                      from depth 5 as Mitsuba's default (unbiased; Glint has none); or
                      ptracer (INTEGRATORS below) with the same max_depth.

Refused: glossy and transparent materials, rough or non-white mirrors, refractive materials
with ior 1 (Mitsuba refuses eta = 1) or with emission, any texture, coverage (opacity < 1).

Usage: mitsuba_export.py PROJECT.glint [-o OUT.exr --spp N --seed S --width W --height H]
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np

from rectangle_frames import right_handed

MATERIAL_DEFAULTS = {"type": "matte", "color": [0.8, 0.8, 0.8], "color_texture": None,
                     "emission": [0, 0, 0], "emission_texture": None, "roughness": 0,
                     "roughness_texture": None, "ior": 1.5, "opacity": 1}
CAMERA_DEFAULTS = {"position": [0, 1, 5], "target": [0, 0.5, 0], "up": [0, 1, 0], "vfov_deg": 40,
                   "aperture_radius": 0, "focus_distance": 5}
ENV_DEFAULTS = {"color": [0.5, 0.5, 0.5], "texture": None, "intensity": 1, "rotation_deg": 0}


class Unsupported(Exception):
    """The project uses something Mitsuba does not model the way Glint does."""


def _mitsuba():
    # Dr.Jit reads DRJIT_LIBLLVM_PATH when it is imported: the library is chosen before that.
    choose_variant()
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

# Mitsuba's integrators that the bench races: `path` (unidirectional, from the camera, as Glint)
# and `ptracer` (particles from the lights, each vertex connected to the camera; the same
# max_depth and rr_depth meaning). ptracer cannot connect a specular vertex to the camera, so a
# mirror or glass seen directly (or anything seen through one) stays black: its converged image
# is a different image wherever those show (bench/tools/race.py checks it before racing it).
INTEGRATORS = ("path", "ptracer")


def glint_executable():
    """The `glint` that converts scenes: $GLINT, else the build folder's (run.py passes --glint
    on as $GLINT)."""
    here = os.path.dirname(os.path.abspath(__file__))
    return os.environ.get("GLINT") or os.path.join(here, "..", "..", "build", "glint")


def _absolute_assets(doc):
    """The project document with its asset paths absolute, to be written anywhere."""
    base = doc["_base_dir"]
    out = {k: v for k, v in doc.items() if not k.startswith("_")}
    absolute = lambda p: p if os.path.isabs(p) else os.path.normpath(os.path.join(base, p))
    out["textures"] = [{**t, "path": absolute(t["path"])} for t in doc.get("textures", [])]
    env = dict(doc.get("environment", {}))
    if env.get("texture"):
        env["texture"] = absolute(env["texture"])
    out["environment"] = env
    return out


def _numbers(text):
    return [float(x) for x in text.replace(",", " ").split()]


def _xml_to_dict(element, folder, params, mi):
    """One object of the XML that `glint convert` writes as mi.load_dict's dictionary. `params`
    replace the $name values of its <default>s; filenames become absolute (load_dict resolves
    them against the current folder)."""
    T = mi.ScalarTransform4f
    value = lambda e, key="value": params.get(e.get(key)[1:], e.get(key)) if e.get(key, "").startswith("$") else e.get(key)
    out = {"type": element.get("type")} if element.get("type") else {}
    for i, c in enumerate(element):
        key = c.get("name") or c.get("id") or (c.tag if c.tag not in out else f"{c.tag}_{i}")
        if c.tag == "float":
            out[key] = float(value(c))
        elif c.tag == "integer":
            out[key] = int(value(c))
        elif c.tag == "boolean":
            out[key] = value(c) == "true"
        elif c.tag == "string":
            v = value(c)
            out[key] = v if key != "filename" or os.path.isabs(v) else os.path.join(folder, v)
        elif c.tag == "rgb":
            out[key] = {"type": "rgb", "value": _numbers(value(c))}
        elif c.tag == "point":
            out[key] = _numbers(value(c))
        elif c.tag == "ref":
            out[key] = {"type": "ref", "id": c.get("id")}
        elif c.tag == "transform":
            if len(c) != 1:
                raise ValueError("glint convert writes one step per <transform>")
            t = c[0]
            if t.tag == "lookat":
                out[key] = T().look_at(origin=_numbers(t.get("origin")), target=_numbers(t.get("target")),
                                       up=_numbers(t.get("up")))
            elif t.tag == "matrix":
                out[key] = T(np.array(_numbers(t.get("value"))).reshape(4, 4))
            elif t.tag == "rotate":
                out[key] = T().rotate([float(t.get(a, 0)) for a in "xyz"], float(t.get("angle")))
            else:
                raise ValueError(f"glint convert wrote an unexpected <{t.tag}>")
        elif c.tag == "default":
            continue
        else:
            out[key] = _xml_to_dict(c, folder, params, mi)
    return out


def export(doc, width=None, height=None, spp=16, seed=0, mesh_dir=None, rotation_offset_deg=-90.0,
           resample_env_rows=True, sampler="independent", integrator="path"):
    """Returns (scene dict, notes). Raises Unsupported. `sampler` is one of SAMPLERS, `integrator`
    one of INTEGRATORS.
    The scene is `glint convert`'s Mitsuba XML (renderer/mitsuba_writer.cpp, whose conventions
    are the ones listed above), read into a dictionary; the environment image is handed over
    resampled (its `envmap` parameter). `rotation_offset_deg` and `resample_env_rows` exist for
    the convention test only (to show that the wrong ones fail)."""
    if sampler not in SAMPLERS:
        raise ValueError(f"unknown Mitsuba sampler {sampler!r} (one of {', '.join(SAMPLERS)})")
    if integrator not in INTEGRATORS:
        raise ValueError(f"unknown Mitsuba integrator {integrator!r} (one of {', '.join(INTEGRATORS)})")
    reasons = unsupported_reasons(doc)
    if reasons:
        raise Unsupported("; ".join(reasons))
    mi = _mitsuba()
    import subprocess
    import xml.etree.ElementTree as ET
    notes = []
    if mesh_dir is None:
        import tempfile
        mesh_dir = tempfile.mkdtemp(prefix="glint_mitsuba_")
    os.makedirs(mesh_dir, exist_ok=True)
    project = os.path.join(mesh_dir, "scene.glint")
    with open(project, "w") as f:
        json.dump(_absolute_assets(doc), f)
    xml_path = os.path.join(mesh_dir, "scene.xml")
    r = subprocess.run([glint_executable(), "convert", project, xml_path, "--spp", str(int(spp))],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"glint convert failed ({r.returncode}): {r.stderr.strip()}")
    film = doc.get("film", {})
    params = {"spp": str(int(spp)), "seed": str(int(seed)),
              "resx": str(int(width or film.get("width", 960))),
              "resy": str(int(height or film.get("height", 540)))}
    d = _xml_to_dict(ET.parse(xml_path).getroot(), mesh_dir, params, mi)
    for v in d.values():  # see rectangle_frames.py: ptracer needs right-handed frames
        if isinstance(v, dict) and v.get("type") == "rectangle" and "to_world" in v:
            v["to_world"] = mi.ScalarTransform4f(np.array(right_handed(np.array(v["to_world"].matrix).tolist())))
    if d["integrator"].get("type") != "path":
        raise RuntimeError(f"glint convert wrote a {d['integrator'].get('type')!r} integrator, not path")
    d["integrator"]["type"] = integrator  # the same max_depth: both count the camera's segment
    d["integrator"]["hide_emitters"] = False
    d["sensor"]["sampler"] = {"type": sampler, "sample_count": int(spp), "seed": int(seed)}
    env = {**ENV_DEFAULTS, **doc.get("environment", {})}
    for key in [k for k, v in d.items() if isinstance(v, dict) and v.get("type") == "envmap"]:
        path = env["texture"] if os.path.isabs(env["texture"]) else os.path.join(doc["_base_dir"], env["texture"])
        img = np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32,
                                               srgb_gamma=False), copy=True)
        if resample_env_rows:
            img = glint_env_to_mitsuba_rows(img)
        d[key] = {"type": "envmap", "bitmap": mi.Bitmap(img.astype(np.float32)), "scale": d[key]["scale"],
                  "to_world": mi.ScalarTransform4f().rotate([0, 1, 0], float(env["rotation_deg"]) + rotation_offset_deg)}
    eye = _v({**CAMERA_DEFAULTS, **doc.get("camera", {})}["position"])
    for i, s in enumerate(doc.get("spheres", [])):
        c, r_ = _v(s.get("center", [0, 0, 0])), float(s.get("radius", 1))
        if r_ > 1e3 * max(1e-30, np.linalg.norm(eye - c) - r_) and mi.variant().startswith("llvm"):
            notes.append(f"spheres[{i}] (radius {r_:g}) is huge next to its distance from the "
                         "camera: Mitsuba's float32 sphere intersection (llvm variants) loses "
                         "light on it; use scalar_rgb for this scene")
    if any(k.startswith("glint-inside-of-sphere-") for k in d):
        notes.append("something is inside an emissive sphere; added an inward-emitting inner sphere")
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
    ap.add_argument("--integrator", choices=INTEGRATORS, default="path")
    a = ap.parse_args(argv)
    doc = load_project(a.project)
    film = doc.get("film", {})
    w, h = a.width, a.height
    if w and not h:
        h = max(1, round(w * film.get("height", 540) / film.get("width", 960)))
    try:
        d, notes = export(doc, w, h, a.spp, a.seed, integrator=a.integrator)
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
