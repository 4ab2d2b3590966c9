#!/usr/bin/env python3
"""Writes the bench scenes, bench/scenes/*.glint (Glint project format version 1).

Run by bench/tools/run.py before every benchmark (the files are committed too, so they can be opened
in the editor). Only the standard library is used.

Environments: by default the two scenes lit by an HDR map use the sky that the project generates
(projects/assets/sky.hdr, written by `glint-make-assets` from renderer/procedural_assets.cpp and
checked by the assets.regenerate_identically test), so the bench runs on a bare clone. With
`--assets DIR` (run.py passes it through) they use real HDR maps from DIR instead, by name
(HDR_MAPS below), written to another folder so that the committed scenes stay as they are.
"""
import json
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))  # bench/tools
ROOT = os.path.dirname(os.path.dirname(HERE))
SCENES = os.path.join(os.path.dirname(HERE), "scenes")
GENERATED_SKY = os.path.join(ROOT, "projects", "assets", "sky.hdr")
# Scene -> the real HDR map it uses with --assets DIR.
HDR_MAPS = {"roughness_ladder": "poly_haven_studio_1k.hdr", "env_dof": "hangar_interior_1k.hdr"}


def project(camera, film, materials, spheres=(), quads=(), environment=None, max_bounces=8,
            textures=()):
    doc = {
        "format": "glint-project",
        "version": 1,
        "camera": camera,
        "film": {"width": film[0], "height": film[1]},
        "render": {"max_bounces": max_bounces, "seed": 0},
        "display": {"exposure": 0, "tonemap": "filmic"},
        "environment": environment or {"color": [0, 0, 0], "texture": None, "intensity": 1,
                                       "rotation_deg": 0},
        "textures": list(textures),
        "materials": list(materials),
        "spheres": list(spheres),
        "quads": list(quads),
    }
    return doc


def cam(position, target, vfov, aperture=0.0, focus=None):
    d = sum((a - b) ** 2 for a, b in zip(position, target)) ** 0.5
    return {"position": position, "target": target, "up": [0, 1, 0], "vfov_deg": vfov,
            "aperture_radius": aperture, "focus_distance": round(focus if focus else d, 4)}


def mat(name, type_, color, **kw):
    m = {"name": name, "type": type_, "color": color}
    m.update(kw)
    return m


def sphere(name, center, radius, material):
    return {"name": name, "center": center, "radius": radius, "material": material}


def quad(name, material, corners):
    return {"name": name, "material": material, "corners": corners}


def floor_quad(name, material, half, y=0.0):
    # Normal cross(p1 - p0, p2 - p0) points up (+Y).
    return quad(name, material, [[-half, y, -half], [-half, y, half], [half, y, -half],
                                 [half, y, half]])


def const_env(color, intensity=1.0):
    return {"color": color, "texture": None, "intensity": intensity, "rotation_deg": 0}


def hdr_env(scene, assets, out_dir, rotation_deg):
    """The environment of a scene lit by an HDR map: DIR's map with --assets (an absolute path),
    else the generated sky, relative to the folder the project is written to (the committed
    scenes work from any clone)."""
    path = os.path.abspath(os.path.join(assets, HDR_MAPS[scene])) if assets else \
        os.path.relpath(GENERATED_SKY, out_dir)
    return {"color": [1, 1, 1], "texture": path.replace(os.sep, "/"), "intensity": 1,
            "rotation_deg": rotation_deg}


def missing_assets(assets):
    """The HDR maps that --assets DIR lacks (as messages naming the file)."""
    return [f"{os.path.join(assets, f)}: file not found (--assets needs it for {s})"
            for s, f in HDR_MAPS.items() if not os.path.isfile(os.path.join(assets, f))]


def scenes(assets=None, out_dir=SCENES):
    out = {}

    # 1. Cornell box: matte walls, an area light one unit below the ceiling (its back side
    # faces the ceiling: Glint's two-sided emission matters there), a white mirror ball and a
    # matte ball. Everything here is modelled identically by Mitsuba.
    out["cornell"] = project(
        cam([278, 273, -800], [278, 273, 0], 39.3), (256, 256),
        [mat("white", "matte", [0.73, 0.73, 0.73]),
         mat("red", "matte", [0.65, 0.05, 0.05]),
         mat("green", "matte", [0.12, 0.45, 0.15]),
         mat("light", "matte", [0.78, 0.78, 0.78], emission=[17, 12, 4]),
         mat("mirror", "reflective", [1, 1, 1], roughness=0)],
        spheres=[sphere("mirror_ball", [370, 100, 370], 100, "mirror"),
                 sphere("matte_ball", [180, 90, 170], 90, "white")],
        quads=[
            quad("floor", "white", [[0, 0, 0], [0, 0, 555], [555, 0, 0], [555, 0, 555]]),
            quad("ceiling", "white", [[0, 555, 0], [555, 555, 0], [0, 555, 555], [555, 555, 555]]),
            quad("back", "white", [[0, 0, 555], [0, 555, 555], [555, 0, 555], [555, 555, 555]]),
            quad("left", "red", [[555, 0, 0], [555, 0, 555], [555, 555, 0], [555, 555, 555]]),
            quad("right", "green", [[0, 0, 0], [0, 555, 0], [0, 0, 555], [0, 555, 555]]),
            quad("light", "light", [[213, 554, 227], [343, 554, 227], [213, 554, 332],
                                    [343, 554, 332]]),
        ])

    # 2. Roughness ladder: metal (back row) and glossy (front row) spheres, roughness 0 to 0.6,
    # on a matte floor under an HDR environment (the generated sky, or a studio map).
    rough = [0.0, 0.05, 0.1, 0.2, 0.35, 0.6]
    mats = [mat("floor", "matte", [0.5, 0.5, 0.5])]
    sph = []
    for i, r in enumerate(rough):
        x = -2.5 + i
        mats.append(mat(f"metal_{i}", "reflective", [0.95, 0.64, 0.54], roughness=r))
        mats.append(mat(f"glossy_{i}", "glossy", [0.1, 0.25, 0.7], roughness=r))
        sph.append(sphere(f"metal_{i}", [x, 0.4, -0.6], 0.4, f"metal_{i}"))
        sph.append(sphere(f"glossy_{i}", [x, 0.4, 0.6], 0.4, f"glossy_{i}"))
    out["roughness_ladder"] = project(
        cam([0, 2.4, 5.2], [0, 0.3, 0], 40), (320, 180), mats, spheres=sph,
        quads=[floor_quad("floor", "floor", 8)],
        environment=hdr_env("roughness_ladder", assets, out_dir, 0))

    # 3. Thin glass: smooth and rough thin-glass spheres and panes in front of coloured stripes,
    # lit by an emissive panel and a dim sky.
    stripes = []
    smats = [mat("floor", "matte", [0.6, 0.6, 0.6]),
             mat("lamp", "matte", [0, 0, 0], emission=[8, 8, 8]),
             mat("glass", "transparent", [1, 1, 1], roughness=0, ior=1.5),
             mat("rough_glass", "transparent", [0.9, 1, 0.95], roughness=0.3, ior=1.5),
             mat("tinted_pane", "transparent", [0.7, 0.85, 1.0], roughness=0, ior=1.5)]
    colours = [[0.8, 0.1, 0.1], [0.9, 0.8, 0.1], [0.1, 0.6, 0.2], [0.1, 0.3, 0.8], [0.9, 0.9, 0.9]]
    for i, c in enumerate(colours):
        smats.append(mat(f"stripe_{i}", "matte", c))
        x0 = -2.5 + i
        stripes.append(quad(f"stripe_{i}", f"stripe_{i}",
                            [[x0, 0, -1.5], [x0, 2.5, -1.5], [x0 + 1, 0, -1.5], [x0 + 1, 2.5, -1.5]]))
    out["thin_glass"] = project(
        cam([0, 1.2, 4.5], [0, 0.8, 0], 40), (320, 180), smats,
        spheres=[sphere("glass_ball", [-0.9, 0.6, 0.3], 0.6, "glass"),
                 sphere("rough_ball", [0.9, 0.6, 0.3], 0.6, "rough_glass")],
        quads=[floor_quad("floor", "floor", 6)] + stripes + [
            quad("pane", "tinted_pane", [[-0.4, 0, 1.3], [-0.4, 1.4, 1.3], [0.4, 0, 1.5],
                                         [0.4, 1.4, 1.5]]),
            quad("lamp", "lamp", [[-1, 3.5, -0.5], [1, 3.5, -0.5], [-1, 3.5, 1], [1, 3.5, 1]])],
        environment=const_env([0.05, 0.06, 0.08]))

    # 4. A small, very bright emitter (radius 0.02, radiance 2500: about 3 W/m^2 of
    # irradiance at distance 1) over matte objects; no environment. Glint follows BSDF samples
    # only, so this is its worst case; Mitsuba samples the light directly.
    out["small_emitter"] = project(
        cam([0, 1.5, 4], [0, 0.5, 0], 40), (256, 192),
        [mat("grey", "matte", [0.6, 0.6, 0.6]), mat("orange", "matte", [0.8, 0.4, 0.1]),
         mat("blue", "matte", [0.15, 0.25, 0.7]),
         mat("bulb", "matte", [0, 0, 0], emission=[2500, 2300, 1900])],
        spheres=[sphere("bulb", [0.0, 1.6, 0.2], 0.02, "bulb"),
                 sphere("ball_a", [-0.7, 0.45, 0], 0.45, "orange"),
                 sphere("ball_b", [0.75, 0.35, 0.4], 0.35, "blue")],
        quads=[floor_quad("floor", "grey", 4),
               quad("wall", "grey", [[-4, 0, -1.2], [-4, 4, -1.2], [4, 0, -1.2], [4, 4, -1.2]])])

    # 5. HDR environment with depth of field: matte and white-mirror spheres receding in depth,
    # thin lens focused on the middle one (the generated sky, or an interior map).
    out["env_dof"] = project(
        cam([0, 0.9, 4.5], [0, 0.5, 0], 35, aperture=0.08, focus=4.5), (320, 180),
        [mat("floor", "matte", [0.45, 0.45, 0.45]), mat("red", "matte", [0.75, 0.15, 0.1]),
         mat("white", "matte", [0.8, 0.8, 0.8]), mat("mirror", "reflective", [1, 1, 1], roughness=0),
         mat("teal", "matte", [0.1, 0.5, 0.5])],
        spheres=[sphere("near", [-0.9, 0.4, 2.2], 0.4, "red"),
                 sphere("mid", [0.0, 0.5, 0.0], 0.5, "mirror"),
                 sphere("far", [1.2, 0.5, -2.5], 0.5, "teal"),
                 sphere("farther", [-1.6, 0.5, -5.0], 0.5, "white")],
        quads=[floor_quad("floor", "floor", 10)],
        environment=hdr_env("env_dof", assets, out_dir, 40))

    # 6. A sphere of radius 1e5 used as a floor (precision of intersection and ray offsets).
    out["huge_sphere_floor"] = project(
        cam([0, 1.2, 5], [0, 0.4, 0], 40), (320, 180),
        [mat("ground", "matte", [0.55, 0.5, 0.45]), mat("red", "matte", [0.7, 0.1, 0.1]),
         mat("white", "matte", [0.8, 0.8, 0.8]), mat("mirror", "reflective", [1, 1, 1], roughness=0)],
        spheres=[sphere("ground", [0, -1e5, 0], 1e5, "ground"),
                 sphere("a", [-1.1, 0.5, 0], 0.5, "red"),
                 sphere("b", [0, 0.5, -0.8], 0.5, "mirror"),
                 sphere("c", [1.1, 0.5, 0], 0.5, "white")],
        environment=const_env([0.7, 0.8, 1.0]))

    # 7. White furnace: albedo-1 matte and a white mirror in a uniform white environment with
    # 64 bounces. The converged image is 1 everywhere (up to paths longer than 64 bounces in the
    # sphere-floor contacts), an analytic check of energy conservation.
    out["white_furnace"] = project(
        cam([0, 1.3, 4], [0, 0.4, 0], 40), (256, 192),
        [mat("white", "matte", [1, 1, 1]), mat("mirror", "reflective", [1, 1, 1], roughness=0)],
        spheres=[sphere("a", [-0.6, 0.5, 0], 0.5, "white"),
                 sphere("b", [0.45, 0.45, 0.3], 0.45, "white"),
                 sphere("m", [0.2, 0.3, -0.9], 0.3, "mirror")],
        quads=[floor_quad("floor", "white", 2),
               quad("wall", "white", [[-2, 0, -1.3], [-2, 2, -1.3], [2, 0, -1.3], [2, 2, -1.3]])],
        environment=const_env([1, 1, 1]), max_bounces=64)

    # 8. Solid glass: a smooth and a rough (0.3) refractive ball (ior 1.5, the rough one tinted) in
    # the Cornell box of scene 1 with a white light; caustics come from BSDF sampling alone
    # in both renderers (their shadow rays stop at glass), so this is a hard scene for both.
    box = out["cornell"]
    out["glass"] = project(
        box["camera"], (256, 256),
        [m for m in box["materials"] if m["name"] in ("white", "red", "green")] +
        [mat("light", "matte", [0.78, 0.78, 0.78], emission=[15, 15, 15]),
         mat("glass", "refractive", [1, 1, 1], roughness=0, ior=1.5),
         mat("rough_glass", "refractive", [0.9, 0.95, 1.0], roughness=0.3, ior=1.5)],
        spheres=[sphere("glass_ball", [370, 100, 300], 100, "glass"),
                 sphere("rough_ball", [170, 90, 200], 90, "rough_glass")],
        quads=box["quads"], max_bounces=12)

    # 10. Caustics: a smooth glass ball (ior 1.5) and a white mirror ball on a floor in front of a
    # wall, lit only by a tiny, very bright sphere lamp (radius 0.03). The focused light on the
    # floor (through the glass, off the mirror) is reached from the camera only by a BSDF sample
    # through a specular bounce hitting the lamp: the hard case for a path tracer. The mirror is
    # white (colour 1) so that Mitsuba models it identically (bench/tools/mitsuba_export.py).
    caustic_materials = [mat("grey", "matte", [0.6, 0.6, 0.6]),
                         mat("glass", "refractive", [1, 1, 1], roughness=0, ior=1.5),
                         mat("mirror", "reflective", [1, 1, 1], roughness=0),
                         mat("bulb", "matte", [0, 0, 0], emission=[2500, 2300, 1900])]
    caustic_spheres = [sphere("bulb", [0.3, 1.8, 0.3], 0.03, "bulb"),
                       sphere("glass_ball", [-0.7, 0.5, 0], 0.5, "glass"),
                       sphere("mirror_ball", [0.75, 0.4, 0.2], 0.4, "mirror")]
    caustic_camera = cam([0, 1.5, 4], [0, 0.45, 0], 40, focus=4.1)
    out["caustics"] = project(
        caustic_camera, (256, 192), caustic_materials, spheres=caustic_spheres,
        quads=[floor_quad("floor", "grey", 4),
               quad("wall", "grey", [[-4, 0, -1.2], [-4, 4, -1.2], [4, 0, -1.2], [4, 4, -1.2]])])

    # 11. The same balls and lamp under a constant sky and without the wall: the caustics sit on a
    # floor that the sky also lights (the caustic is a smaller part of each pixel's value).
    out["caustics_sky"] = project(
        caustic_camera, (256, 192), caustic_materials, spheres=caustic_spheres,
        quads=[floor_quad("floor", "grey", 4)], environment=const_env([0.35, 0.45, 0.6], intensity=1))

    # 9. The showcase, projects/default.glint, with its asset paths rebased to bench/scenes/.
    with open(os.path.join(ROOT, "projects", "default.glint")) as f:
        show = json.load(f)
    rebase = lambda p: p if (p is None or os.path.isabs(p)) else os.path.relpath(
        os.path.join(ROOT, "projects", p), out_dir)
    show["environment"]["texture"] = rebase(show["environment"].get("texture"))
    for t in show.get("textures", []):
        t["path"] = rebase(t["path"])
    out["showcase"] = show
    return out


def dumps(doc):
    text = json.dumps(doc, indent=2)
    # Arrays of numbers (and arrays of those) on one line, as the editor writes them.
    num = r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"
    text = re.sub(r"\[\s*(" + num + r"(?:,\s*" + num + r")*)\s*\]",
                  lambda m: "[" + ", ".join(x.strip() for x in m.group(1).split(",")) + "]", text)
    text = re.sub(r"\[\s*((?:\[[^\[\]]*\],?\s*)+)\]",
                  lambda m: "[" + ", ".join(re.findall(r"\[[^\[\]]*\]", m.group(1))) + "]", text)
    return text + "\n"


def main(out_dir=SCENES, assets=None):
    """Writes the scenes into out_dir (bench/scenes by default); returns 0."""
    if assets:
        missing = missing_assets(assets)
        if missing:
            raise SystemExit("bench: " + "; ".join(missing))
    os.makedirs(out_dir, exist_ok=True)
    for name, doc in scenes(assets, out_dir).items():
        path = os.path.join(out_dir, name + ".glint")
        text = dumps(doc)
        old = open(path).read() if os.path.exists(path) else None
        if old != text:
            with open(path + ".tmp", "w") as f:
                f.write(text)
            os.replace(path + ".tmp", path)
    return 0


if __name__ == "__main__":
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--assets", help="folder with the real HDR maps (" + ", ".join(HDR_MAPS.values()) + ")")
    ap.add_argument("--out", default=SCENES, help="folder to write the scenes to (default bench/scenes)")
    a = ap.parse_args()
    sys.exit(main(a.out, a.assets))
