"""The race: time to relMSE 1e-2 and 1e-3 for Glint and for Mitsuba with two samplers, each
against its own converged image, and the ratio Glint time / Mitsuba time (the target: at most
0.5 on every scene that both model, against both samplers).

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


def rows(results, ld):
    """One row per scene that Mitsuba models: the times and ratios for each target."""
    out = []
    for name, r in results.items():
        m = r.get("mitsuba")
        if not m or not m.get("exported") or ld not in r.get("mitsuba_ld", {}):
            continue
        row = {"scene": name, "targets": {}}
        for target in RACE_TARGETS:
            g = time_to(r["summary"], target)
            mi = time_to(m["summary"], target)
            ml = time_to(r["mitsuba_ld"][ld]["summary"], target)
            row["targets"][target] = {"glint": g, "independent": mi, ld: ml,
                                      "ratio_independent": ratio(g, mi), "ratio_" + ld: ratio(g, ml)}
        out.append(row)
    return out


def markdown(race_rows, ld, fmt_s):
    L = ["## The race: time to relMSE 1e-2 and 1e-3, Glint against Mitsuba\n",
         "Same machine, same run, every scene that both model the same way. Glint with its "
         f"default sampler (Owen-scrambled Sobol), Mitsuba with `independent` and with `{ld}` (the "
         "winner of the equal-spp trial below); each against its own converged image, so that "
         "the times measure noise only. Ratio = Glint's time / Mitsuba's; the target is at most "
         f"{GOAL} against both samplers. A time inside a ladder is interpolated (log-log) "
         "between the rungs on either side of the target; \"(fit)\": a time past the last rung "
         f"of that ladder, extrapolated from a log-log fit of its last {TAIL_RUNGS} rungs (not "
         "measured); \"<=\": already reached at the first rung, so the time is at most that "
         "rung's.\n"]
    for target in RACE_TARGETS:
        L.append(f"| scene | Glint t({target:g}) | Mitsuba independent | ratio | Mitsuba {ld} | ratio | target met |")
        L.append("|---|---|---|---|---|---|---|")
        for row in race_rows:
            t = row["targets"][target]
            ok = [meets(t["ratio_independent"]), meets(t["ratio_" + ld])]
            verdict = "yes" if all(o is True for o in ok) else (
                "no" if any(o is False for o in ok) else "unknown")
            if verdict != "unknown" and any("fit" in t[k][1] for k in ("ratio_independent", "ratio_" + ld)):
                verdict += " (fit)"
            L.append(f"| {row['scene']} | {fmt_time(t['glint'], fmt_s)} | "
                     f"{fmt_time(t['independent'], fmt_s)} | {fmt_ratio(t['ratio_independent'])} | "
                     f"{fmt_time(t[ld], fmt_s)} | {fmt_ratio(t['ratio_' + ld])} | {verdict} |")
        L.append("")
    return "\n".join(L)
