#!/usr/bin/env python3
"""Checks that the exporter's environment-map and camera conventions match Glint's.

Renders a tiny environment-only project (max_bounces 0, an HDR map rotated by 40 degrees:
the generated sky, or a real map with run.py --assets) from three views with Glint (two seeds: the noise floor) and with Mitsuba under the
exporter's convention and under deliberately wrong ones; returns the relMSE of each against
Glint. The right convention must sit at the noise floor and every wrong one far above it.
"""
import json
import os
import subprocess

import numpy as np

import metrics
import mitsuba_export as mx

VIEWS = {"horizon +x": [1, 0.2, 0.3], "towards -z, up": [0.2, 0.8, -1], "near the pole": [0.3, 3, 0.1]}
VARIANTS = [("exporter (R_y(rot - 90), rows resampled)", -90.0, True),
            ("rows not resampled", -90.0, False),
            ("to_world = R_y(rot)", 0.0, True),
            ("to_world = R_y(rot + 90)", 90.0, True),
            ("to_world = R_y(rot + 180)", 180.0, True)]


def run(glint, work, env_path, size=(64, 48), spp=64, log=print):
    os.makedirs(work, exist_ok=True)
    rows = []
    for view, target in VIEWS.items():
        doc = {"format": "glint-project", "version": 1,
               "camera": {"position": [0, 0, 0], "target": target, "up": [0, 1, 0], "vfov_deg": 70},
               "film": {"width": size[0], "height": size[1]},
               "render": {"max_bounces": 0, "seed": 0},
               "environment": {"color": [1, 1, 1], "texture": os.path.abspath(env_path),
                               "intensity": 1.5, "rotation_deg": 40},
               "materials": [], "spheres": [], "quads": []}
        proj = os.path.join(work, "env_view.glint")
        with open(proj, "w") as f:
            json.dump(doc, f)
        g = []
        for seed in (1, 2):
            out = os.path.join(work, f"glint_{seed}.exr")
            subprocess.run([glint, "render", proj, "-o", out, "--spp", str(spp), "--seed", str(seed)],
                           check=True, capture_output=True)
            g.append(metrics.read_exr(out))
        row = {"view": view, "glint seed 1 vs seed 2": metrics.relmse(g[1], g[0])}
        doc["_base_dir"] = work
        for name, offset, resample in VARIANTS:
            d, _ = mx.export(doc, size[0], size[1], spp, 7, mesh_dir=work,
                             rotation_offset_deg=offset, resample_env_rows=resample)
            img, _ = mx.render(d, spp, 7)
            row[name] = metrics.relmse(img, g[0])
            row[name + " bias"] = metrics.mean_bias(img, g[0])
        rows.append(row)
        log(f"  convention check, {view}: " + ", ".join(
            f"{k} {v:.3g}" for k, v in row.items() if k != "view" and not k.endswith("bias")))
    return rows
