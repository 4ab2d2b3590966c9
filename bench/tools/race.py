"""The race: time to relMSE 1e-2 and 1e-3 for Glint and for Mitsuba's contenders (`path` with two
samplers, and on the caustic scenes the particle tracer `ptracer`), each against its own
converged image, and the ratio Glint time / Mitsuba time (the target: at most 0.5 on every scene
that both model, against the better valid contender). A contender other than path counts only
where its converged image is shown to be path's (valid_at): ptracer leaves mirrors and glass
seen from the camera black, so it may converge quickly to another image.

A time comes from the ladder of mean relMSE against trace time (rungs of doubling spp). Inside the
measured range it is interpolated, linearly in log-log, between the two rungs on either side of
the target; below the first rung it is an upper bound (the first rung's time); past the last rung
it is the extrapolation of a log-log fit of the last TAIL_RUNGS rungs, marked "fit". Only the top
rungs: the low ones carry a fixed cost per render (start of the passes, threads waking) and
low-discrepancy errors that fall faster than 1/N at first, so a fit of the whole ladder tilts
with them and puts the extrapolated time where no long render would be. A ratio inherits the
marks: an upper bound on Glint's time makes it an upper bound, one on Mitsuba's a lower bound,
and either time from the fit makes it "fit".
"""
import math

RACE_TARGETS = (1e-2, 1e-3)
GOAL = 0.5
TAIL_RUNGS = 4  # the rungs fitted for an extrapolation (32 to 256 spp of a 1-256 ladder)


def _fit(x, y):
    """log y = a + b log x by least squares over the finite positive points; (a, b) or None.
    (Plain Python, so that bench/tools/test_race.py needs no numpy.)"""
    pts = [(math.log(u), math.log(v)) for u, v in zip(x, y)
           if u > 0 and v > 0 and math.isfinite(u) and math.isfinite(v)]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return None
    b = sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx
    return my - b * mx, b


def time_to(summary, target):
    """(seconds, mark): mark "" measured, "<=" upper bound, "fit" extrapolated; (None, why)."""
    pts = [(u, v) for u, v in zip(summary["seconds"], summary["relmse"])
           if u > 0 and v > 0 and math.isfinite(u) and math.isfinite(v)]
    if len(pts) < 2:
        return None, "no fit"
    if pts[0][1] <= target:
        return pts[0][0], "<="
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e1 <= target:  # the first rung at the target: interpolate from the one before
            w = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + w * (math.log(t1) - math.log(t0))), ""
    tail = pts[-TAIL_RUNGS:]
    fit = _fit([p[0] for p in tail], [p[1] for p in tail])
    if fit is None or fit[1] >= 0:
        return None, "not converging"
    log_t = (math.log(target) - fit[0]) / fit[1]
    if log_t > math.log(1e7):  # a nearly flat fit: past any useful time
        return None, "fit: > 100 days"
    return math.exp(log_t), "fit"


def ratio(g, m):
    """Glint time / Mitsuba time with its mark, or (None, why)."""
    (tg, mg), (tm, mm) = g, m
    if tg is None or tm is None:
        return None, "n/a"
    if mg == "<=" and mm == "<=":
        return None, "both below at the first point"
    mark = "<=" if mg == "<=" else (">=" if mm == "<=" else "")
    if "fit" in (mg, mm):
        mark = (mark + " " if mark else "") + "fit"
    return tg / tm, mark


def fmt_time(t, fmt_s):
    secs, mark = t
    if secs is None:
        return mark
    if mark == "<=":
        return f"<= {fmt_s(secs)}"
    return f"{fmt_s(secs)} (fit)" if mark == "fit" else fmt_s(secs)


def fmt_ratio(r):
    v, mark = r
    if v is None:
        return mark
    bound = mark.split(" ")[0] if mark.startswith(("<=", ">=")) else ""
    text = f"{bound + ' ' if bound else ''}{v:.2f}"
    return text + (" (fit)" if "fit" in mark else "")


def meets(r):
    """True when the ratio is known to be at most GOAL, False when known above, None if unsure."""
    v, mark = r
    if v is None:
        return None
    if mark.startswith(">=") and v > GOAL:
        return False
    if mark.startswith("<=") and v <= GOAL:
        return True
    if mark.startswith(("<=", ">=")):
        return None
    return v <= GOAL


def valid_at(vs_path, target):
    """Whether a contender is shown to converge to path's image at the precision of `target`.
    `vs_path` is None for path itself, else {"difference": relMSE (trimmed) of its converged
    image against path's, "floor": the same between two converged path images of different
    seeds (what noise alone gives)}. Valid when the floor is at most the target (path's image
    is precise enough to tell) and the difference beyond the floor is at most the target too (a
    contender that converges elsewhere by more than the error the race measures is not racing
    to the same image)."""
    if vs_path is None:
        return True
    d, floor = vs_path.get("difference"), vs_path.get("floor")
    if d is None or floor is None or not (math.isfinite(d) and math.isfinite(floor)):
        return False
    return floor <= target and d - floor <= target


def best(times, valid):
    """The valid contender with the shortest time (its name), or None when none has a time.
    `times`: {name: (seconds, mark)}; `valid`: {name: bool}."""
    known = [(t[0], name) for name, t in times.items() if valid.get(name) and t[0] is not None]
    return min(known)[1] if known else None


def verdict(ratios):
    """"yes" when the goal is met against every ratio given (the valid contenders), "no" when
    known to be missed against one, else "unknown"; "(fit)" when a ratio leans on a fit."""
    ok = [meets(r) for r in ratios]
    text = "yes" if ok and all(o is True for o in ok) else (
        "no" if any(o is False for o in ok) else "unknown")
    if text != "unknown" and any("fit" in r[1] for r in ratios):
        text += " (fit)"
    return text


def contenders(r, ld):
    """{name: (summary, vs_path)} of the Mitsuba contenders that a scene's results hold: path with
    `independent` and with `ld`, and ptracer where it was run."""
    out = {"independent": (r["mitsuba"]["summary"], None), ld: (r["mitsuba_ld"][ld]["summary"], None)}
    p = r.get("mitsuba_ptracer")
    if p and p.get("exported"):
        out["ptracer"] = (p["summary"], p.get("vs_path"))
    return out


def rows(results, ld):
    """One row per scene that Mitsuba models: the times and ratios for each target, and the
    better valid contender."""
    out = []
    for name, r in results.items():
        m = r.get("mitsuba")
        if not m or not m.get("exported") or ld not in r.get("mitsuba_ld", {}):
            continue
        cs = contenders(r, ld)
        row = {"scene": name, "targets": {},
               "vs_path": {c: vp for c, (_, vp) in cs.items() if vp is not None}}
        for target in RACE_TARGETS:
            g = time_to(r["summary"], target)
            t = {"glint": g, "valid": {}}
            for c, (summary, vs_path) in cs.items():
                t[c] = time_to(summary, target)
                t["ratio_" + c] = ratio(g, t[c])
                t["valid"][c] = valid_at(vs_path, target)
            t["best"] = best({c: t[c] for c in cs}, t["valid"])
            t["ratio_best"] = ratio(g, t[t["best"]]) if t["best"] else (None, "n/a")
            t["verdict"] = verdict([t["ratio_" + c] for c in cs if t["valid"][c]])
            row["targets"][target] = t
        out.append(row)
    return out


def markdown(race_rows, ld, fmt_s, heading="## The race: time to relMSE 1e-2 and 1e-3, Glint against Mitsuba",
             intro=None, vs_path_table=True):
    """The race's tables under `heading`, after `intro` (default: how the race is run and read),
    and where ptracer ran (unless `vs_path_table` is False) the table of its converged image
    against path's."""
    with_pt = any("ptracer" in row["targets"][RACE_TARGETS[0]] for row in race_rows)
    L = [heading + "\n", intro or (
         "Same machine, same run, every scene that both model the same way. Glint with its "
         f"default sampler (Owen-scrambled Sobol), Mitsuba's `path` with `independent` and with `{ld}` "
         "(the winner of the equal-spp trial)" +
         (", and Mitsuba's particle tracer `ptracer` (`independent`) on the scenes where it ran"
          if with_pt else "") +
         "; each against its own converged image, so that the times measure noise only. Ratio = "
         f"Glint's time / Mitsuba's; the target is at most {GOAL} against the better valid "
         "contender (met when it is met against every valid one). " +
         ("A contender is valid at a target when two converged path images (two seeds) agree "
          "to the target (trimmed relMSE) and its converged image differs from path's by at "
          "most the target beyond that floor (path always is; ptracer leaves mirrors and glass "
          "seen from the camera black, see the table after these). " if with_pt else "") +
         "A time inside a ladder is "
         "interpolated (log-log) between the rungs on either side of the target; \"(fit)\": a "
         f"time past the last rung of that ladder, extrapolated from a log-log fit of its last {TAIL_RUNGS} "
         "rungs (not measured); \"<=\": already reached at the first rung, so the time is at "
         "most that rung's.\n")]
    names = ["independent", ld] + (["ptracer"] if with_pt else [])
    for target in RACE_TARGETS:
        L.append(f"| scene | Glint t({target:g}) | " +
                 " | ".join(f"Mitsuba {c} | ratio" for c in names) + " | better valid | ratio | target met |")
        L.append("|---|---|" + "---|---|" * len(names) + "---|---|---|")
        for row in race_rows:
            t = row["targets"][target]
            cells = []
            for c in names:
                if c not in t:
                    cells += ["-", "-"]
                    continue
                r = fmt_ratio(t["ratio_" + c])
                cells += [fmt_time(t[c], fmt_s), r if t["valid"][c] else f"{r} (not valid)"]
            L.append(f"| {row['scene']} | {fmt_time(t['glint'], fmt_s)} | " + " | ".join(cells) +
                     f" | {t['best'] or 'none'} | {fmt_ratio(t['ratio_best'])} | {t['verdict']} |")
        L.append("")
    if with_pt and vs_path_table:
        L += vs_path_markdown(race_rows)
    return "\n".join(L)


def vs_path_markdown(race_rows):
    """The table of how far each non-path contender's converged image is from path's."""
    L = ["### ptracer's converged image against path's\n",
         "relMSE between Mitsuba's converged `ptracer` image and its converged `path` image (same "
         "samples per pixel), beside the same between two converged `path` images of different "
         "seeds (the floor that noise alone gives); trimmed: the worst 0.1% of pixels dropped, "
         "so that a few fireflies do not decide. Valid at a target when the trimmed floor is at "
         "most the target and the trimmed difference beyond it is too.\n",
         "| scene | relMSE(ptracer, path) | relMSE(path, path) | trimmed | trimmed floor | "
         "mean-lum. bias ptracer vs path | valid at " +
         " | valid at ".join(f"{t:g}" for t in RACE_TARGETS) + " |",
         "|---|---|---|---|---|---|" + "---|" * len(RACE_TARGETS)]
    for row in race_rows:
        vp = row["vs_path"].get("ptracer")
        if vp is None:
            continue
        L.append(f"| {row['scene']} | {vp['relmse']:.3g} | {vp['floor_relmse']:.3g} | "
                 f"{vp['difference']:.3g} | {vp['floor']:.3g} | {vp['mean_bias']:+.2%} | " +
                 " | ".join("yes" if row["targets"][t]["valid"]["ptracer"] else "no"
                            for t in RACE_TARGETS) + " |")
    L.append("")
    return L
