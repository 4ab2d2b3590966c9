"""Samples per second of `glint render`'s trace back ends (the fragment-shader tracer and the
compute-shader one), when the CLI offers the choice (`--backend fragment|compute|auto`).

Standard library only, so that bench/tools/test_backends.py can test the detection without the
bench's environment.
"""
import os
import statistics
import subprocess

BACKENDS = ("fragment", "compute")


def available(glint):
    """The back ends to race: BACKENDS when `glint render --help` mentions --backend, else ()."""
    r = subprocess.run([glint, "render", "--help"], capture_output=True, text=True)
    return BACKENDS if r.returncode == 0 and "--backend" in r.stdout else ()


def measure(render, glint, scenes, work, width, spp, repeats, log=print, compare=None):
    """For each (name, project): `repeats` renders per back end at `width` px and `spp`, the back
    ends interleaved (fragment, compute, fragment, ...) so that a change of load on the machine
    hits both alike; the median spp/s per back end. `render(glint, project, out, spp, seed,
    width, extra)` is run.py's glint_render. `compare(path_a, path_b)`, when given, is the relMSE
    between the two back ends' images of the same seed (the same estimator: float noise only)."""
    os.makedirs(work, exist_ok=True)
    rows = []
    for name, project in scenes:
        rates = {b: [] for b in BACKENDS}
        size = None
        for rep in range(repeats):
            for b in BACKENDS:
                out = os.path.join(work, f"{name}_{b}_{rep}.exr")
                r = render(glint, project, out, spp, 1, width, ["--backend", b])
                rates[b].append(r["spp"] / r["seconds"] if r["seconds"] > 0 else float("nan"))
                size = (r["width"], r["height"])
        row = {"scene": name, "size": size, "spp": spp, "repeats": repeats,
               "spp_per_s": {b: statistics.median(v) for b, v in rates.items()},
               "all": rates}
        if compare:
            row["relmse_between"] = compare(os.path.join(work, f"{name}_fragment_0.exr"),
                                            os.path.join(work, f"{name}_compute_0.exr"))
        f, c = row["spp_per_s"]["fragment"], row["spp_per_s"]["compute"]
        log(f"  backends {name}: fragment {f:.1f} spp/s, compute {c:.1f} spp/s "
            f"(compute / fragment {c / f:.2f})")
        rows.append(row)
    return rows


def table(rows, has_backend):
    """Markdown lines: the table, or the note that says why there is none."""
    if not has_backend:
        return ["`glint render --help` does not mention `--backend`: this build has only the "
                "fragment-shader tracer, so there is no back-end table.", ""]
    L = ["| scene | size | spp | fragment spp/s | compute spp/s | compute / fragment | "
         "relMSE between the two images (seed 1) |",
         "|---|---|---|---|---|---|---|"]
    for r in rows:
        f, c = r["spp_per_s"]["fragment"], r["spp_per_s"]["compute"]
        between = r.get("relmse_between")
        L.append(f"| {r['scene']} | {r['size'][0]}x{r['size'][1]} | {r['spp']} | {f:.3g} | {c:.3g} | "
                 f"{c / f:.2f} | {'n/a' if between is None else f'{between:.3g}'} |")
    L.append("")
    return L
