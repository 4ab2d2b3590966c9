"""Which of Mitsuba's low-discrepancy samplers to race Glint against: `ldsampler`, `multijitter`
and `orthogonal` beside `independent`, at equal samples per pixel, on every exported scene.

Per scene and sampler: mean relMSE over seeds at each count of `spp` against the scene's converged
Mitsuba image, then a log-log fit of relMSE against the samples the sampler really traced
(`orthogonal` rounds up to prime squares, `ldsampler` to powers of two), evaluated at the asked
counts, so that every sampler is compared at the same spp. The gain is independent's relMSE over
the sampler's; the winner has the largest geometric mean gain over scenes and counts.
"""
import math

import numpy as np

import metrics
import mitsuba_export as mx

LOW_DISCREPANCY = ("ldsampler", "multijitter", "orthogonal")


def _fit(spp, err):
    b, a = np.polyfit(np.log(spp), np.log(err), 1)
    return lambda n: math.exp(a + b * math.log(n))


def trial(scenes, spp, seeds, load, log=print):
    """scenes: [(name, converged Mitsuba image)]; load(name, sampler) returns the scene loaded
    with that sampler and compiled. Returns {"rows": [...], "gain": {sampler: geometric mean},
    "winner": name}."""
    rows = []
    for name, ref in scenes:
        at = {}
        for sampler in ("independent",) + LOW_DISCREPANCY:
            scene = load(name, sampler)
            traced, err = [], []
            for n in spp:
                e = []
                for seed in range(1, seeds + 1):
                    img, _ = mx.render(scene, n, 3000 + seed)
                    e.append(metrics.relmse(img, ref))
                traced.append(mx.samples_per_pixel(scene))
                err.append(float(np.mean(e)))
            f = _fit(traced, err) if len(set(traced)) > 1 else (lambda n, e0=err[0]: e0)
            at[sampler] = {n: f(n) for n in spp}
        for n in spp:
            row = {"scene": name, "spp": n, "relmse": {s: at[s][n] for s in at}}
            row["gain"] = {s: row["relmse"]["independent"] / row["relmse"][s] for s in LOW_DISCREPANCY}
            log(f"  mitsuba samplers {name} @ {n} spp: " +
                ", ".join(f"{s} {v:.3g}" for s, v in row["relmse"].items()))
            rows.append(row)
    gain = {s: math.exp(float(np.mean([math.log(r["gain"][s]) for r in rows]))) for s in LOW_DISCREPANCY}
    winner = max(gain, key=gain.get)
    log(f"  mitsuba samplers: geometric mean gain over independent " +
        ", ".join(f"{s} {g:.3f}" for s, g in gain.items()) + f"; racing {winner}")
    return {"rows": rows, "gain": gain, "winner": winner, "spp": list(spp), "seeds": seeds}


def markdown(t):
    L = ["### Mitsuba's samplers at equal spp\n",
         f"relMSE against the scene's converged Mitsuba image, mean of {t['seeds']} seeds; in "
         "brackets the gain over `independent` (its relMSE over the sampler's). `orthogonal` and "
         "`ldsampler` round the sample count (to prime squares, powers of two): each sampler's "
         "log-log fit of relMSE against the samples it traced is read at the spp of the row. "
         f"Geometric mean gain: " + ", ".join(f"`{s}` {g:.3f}" for s, g in t["gain"].items()) +
         f"; the race below uses **`{t['winner']}`**.\n",
         "| scene | spp | independent | " + " | ".join(LOW_DISCREPANCY) + " |",
         "|---|---|---|" + "---|" * len(LOW_DISCREPANCY)]
    for r in t["rows"]:
        L.append(f"| {r['scene']} | {r['spp']} | {r['relmse']['independent']:.3g} | " +
                 " | ".join(f"{r['relmse'][s]:.3g} ({r['gain'][s]:.2f})" for s in LOW_DISCREPANCY) + " |")
    L.append("")
    return "\n".join(L)
