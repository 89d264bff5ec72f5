#!/usr/bin/env python3
"""Fits a GPU cost model (harness/core/cost_model.h) to measured rows and judges it on rows it
was not fitted to.

  scripts/fit-cost-model.py --gpu "NVIDIA H200" --name nvidia-h200 \
      --fit TIMES.csv[:COUNTS.csv] ... --judge TIMES.csv[:COUNTS.csv] ... \
      --model configs/gpu-models/nvidia-h200.toml --report results/gpu-model/README.md [--check]

TIMES.csv: rows measured on the GPU (frame_ms_min is the time fitted). COUNTS.csv: rows of the
same cells with the op counts (warp_*_ops, fragments), when the GPU rows predate them; the two
are joined on the cell's identity (technique, its parameters, scene, view, sizes). Without
COUNTS the GPU rows' own counts are used.

The model: frame_ms = frame + pixel*Mpx + fragment*Mfragments + sum_k op_k*Mops_k, weights >= 0,
fitted by non-negative least squares on relative error (each row weighted by 1/measured), so a
0.3 ms frame counts as much as a 30 ms one. Judged as a reader of the tables would use it: per
view (scene, elevation, azimuth, viewport), does it rank the search settings as the GPU does
(Spearman), how far is each prediction from the measured time, and do the Pareto fronts of error
against time agree? Cross-validated by map: each map's rows predicted by a fit without them.

--check recomputes everything from the committed rows and fails when the model file or the
report differs from what it would write: the report cannot drift from its rows.
"""
import argparse
import csv
import math
import sys
from collections import defaultdict

KINDS = ["fetch", "float", "special", "int", "branch", "dynamic_index"]
WEIGHTS = ["frame", "pixel", "fragment"] + KINDS
WEIGHT_UNITS = ["ms per frame", "ms per million pixels of the viewport",
                "ms per million fragments shaded"] + [
                    "ms per million lockstep %s ops" % k.replace("_", " ") for k in KINDS]
# A cell's identity: what names it apart from what was measured.
IDENTITY = ["technique", "scene", "elevation_deg", "azimuth_deg", "texture_res", "viewport"]
NOT_PARAMETERS = set(IDENTITY) | {"covered_px"}
SHADING_ONLY = {"normal", "parallax"}  # no search: left out of the per-view ranking, as before


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def parameter_columns(header):
    """The technique parameter columns: those before covered_px that are not the identity."""
    out = []
    for name in header:
        if name == "covered_px":
            break
        if name not in NOT_PARAMETERS:
            out.append(name)
    return out


def cell_id(row, params):
    return tuple(row.get(k, "") for k in IDENTITY + params)


def joined(spec):
    """Rows of TIMES with the counts of COUNTS joined on: (time row, count row) pairs."""
    times_path, _, counts_path = spec.partition(":")
    times = read_rows(times_path)
    counts = read_rows(counts_path) if counts_path else times
    params = parameter_columns(list(times[0].keys()))
    by_id = {cell_id(r, params): r for r in counts}
    pairs, missing = [], 0
    for r in times:
        c = by_id.get(cell_id(r, params))
        if c is None or c.get("warp_float_ops", "") == "":
            missing += 1
            continue
        pairs.append((r, c))
    if missing:
        sys.exit("fit-cost-model: %d rows of %s have no counts in %s" %
                 (missing, times_path, counts_path or times_path))
    return pairs


def features(count_row):
    w, h = (int(v) for v in count_row["viewport"].split("x"))
    mpx = w * h / 1e6
    return [1.0, mpx, float(count_row["fragments"]) / 1e6] + [
        float(count_row["warp_%s_ops" % k]) * mpx for k in KINDS]


def measured(time_row):
    return float(time_row["frame_ms_min"])


def solve(a, b):
    """Least squares a x = b through the normal equations, columns scaled to unit length."""
    n = len(a[0])
    scale = [math.sqrt(sum(row[j] ** 2 for row in a)) or 1.0 for j in range(n)]
    m = [[sum(row[i] * row[j] for row in a) / (scale[i] * scale[j]) for j in range(n)] +
         [sum(row[i] * bi for row, bi in zip(a, b)) / scale[i]] for i in range(n)]
    for col in range(n):
        pivot = max(range(col, n), key=lambda r: abs(m[r][col]))
        m[col], m[pivot] = m[pivot], m[col]
        if abs(m[col][col]) < 1e-15:
            raise ValueError("singular")
        for r in range(n):
            if r != col:
                f = m[r][col] / m[col][col]
                m[r] = [x - f * y for x, y in zip(m[r], m[col])]
    return [m[i][n] / m[i][i] / scale[i] for i in range(n)]


def nnls(a, b):
    """Lawson and Hanson's active-set non-negative least squares."""
    n = len(a[0])
    x, passive = [0.0] * n, []

    def gradient(x):
        r = [bi - sum(ai * xi for ai, xi in zip(row, x)) for row, bi in zip(a, b)]
        return [sum(row[j] * ri for row, ri in zip(a, r)) for j in range(n)]

    for _ in range(3 * n):
        w = gradient(x)
        free = [j for j in range(n) if j not in passive]
        if not free or max(w[j] for j in free) <= 1e-12:
            break
        passive.append(max(free, key=lambda j: w[j]))
        while True:
            sub = solve([[row[j] for j in passive] for row in a], b)
            s = [0.0] * n
            for j, v in zip(passive, sub):
                s[j] = v
            if all(s[j] > 0 for j in passive):
                x = s
                break
            alpha = min(x[j] / (x[j] - s[j]) for j in passive if s[j] <= 0)
            x = [xi + alpha * (si - xi) for xi, si in zip(x, s)]
            passive = [j for j in passive if x[j] > 1e-12]
    return x


def fit(pairs):
    a = [[v / measured(t) for v in features(c)] for t, c in pairs]
    return nnls(a, [1.0] * len(pairs))


def predict(weights, count_row):
    return sum(w * v for w, v in zip(weights, features(count_row)))


def ranks(values):
    order = sorted(range(len(values)), key=lambda i: values[i])
    r = [0.0] * len(values)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
            j += 1
        for k in range(i, j + 1):
            r[order[k]] = (i + j) / 2.0
        i = j + 1
    return r


def spearman(x, y):
    rx, ry = ranks(x), ranks(y)
    mx, my = sum(rx) / len(rx), sum(ry) / len(ry)
    cov = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    var = math.sqrt(sum((a - mx) ** 2 for a in rx) * sum((b - my) ** 2 for b in ry))
    return cov / var if var else 1.0


def setting(row, params):
    parts = [row["technique"]] + ["%s=%s" % (p, row[p]) for p in params if row.get(p, "") != ""]
    return " ".join(parts)


def pareto(points):
    """The settings no other beats on both error and time (ties on both kept)."""
    front = set()
    for name, err, ms in points:
        if not any((e <= err and m <= ms) and (e < err or m < ms) for _, e, m in points):
            front.add(name)
    return front


def view_key(row):
    return (row["scene"], row["elevation_deg"], row["azimuth_deg"], row["viewport"])


def views(pairs, predictions):
    by_view = defaultdict(list)
    params = parameter_columns(list(pairs[0][0].keys()))
    for (t, c), p in zip(pairs, predictions):
        by_view[view_key(t)].append((setting(t, params), float(c["wrong_pct"] or "nan"),
                                     measured(t), p, t["technique"]))
    return by_view


def judge(pairs, predictions):
    """Per-view Spearman over the search settings, the share within 1.25x, the median ratio,
    and the Pareto fronts' agreement (settings on both fronts over those on the measured one)."""
    rhos, shared, on_measured = [], 0, 0
    for cells in views(pairs, predictions).values():
        search = [c for c in cells if c[4] not in SHADING_ONLY]
        rhos.append(spearman([c[2] for c in search], [c[3] for c in search]))
        by_time = pareto([(c[0], c[1], c[2]) for c in cells])
        by_model = pareto([(c[0], c[1], c[3]) for c in cells])
        shared += len(by_time & by_model)
        on_measured += len(by_time | by_model)
    ratios = sorted(max(p / measured(t), measured(t) / p) for (t, _), p in zip(pairs, predictions))
    return {
        "views": len(rhos),
        "spearman": sum(rhos) / len(rhos),
        "spearman_min": min(rhos),
        "within_125": sum(r <= 1.25 for r in ratios) / len(ratios),
        "median_ratio": ratios[len(ratios) // 2],
        "front_agreement": shared / on_measured if on_measured else 1.0,
        "rows": len(pairs),
    }


def by_map_cross_validation(pairs):
    maps = sorted({t["scene"] for t, _ in pairs})
    predictions = [0.0] * len(pairs)
    for m in maps:
        weights = fit([p for p in pairs if p[0]["scene"] != m])
        for i, (t, c) in enumerate(pairs):
            if t["scene"] == m:
                predictions[i] = predict(weights, c)
    return predictions


def is_relief_32_6(row):
    return row["technique"] == "relief" and row.get("linear_steps") == "32"


def by_technique_cross_validation(pairs):
    """Each search technique's rows predicted by a fit without any of its rows (every setting):
    how far the model carries to a shader it has not seen. Per technique: the rows, the median
    and range of predicted/measured time, and of its time over relief 32+6's in the same view,
    predicted over measured (None for relief itself)."""
    out = []
    for technique in sorted({t["technique"] for t, _ in pairs} - SHADING_ONLY):
        weights = fit([p for p in pairs if p[0]["technique"] != technique])
        guess = {view_key(t): (predict(weights, c), measured(t))
                 for t, c in pairs if is_relief_32_6(t)}
        time_ratios, relief_ratios = [], []
        for t, c in pairs:
            if t["technique"] != technique:
                continue
            p = predict(weights, c)
            time_ratios.append(p / measured(t))
            g = guess.get(view_key(t))
            if technique != "relief" and g:
                relief_ratios.append((p / g[0]) / (measured(t) / g[1]))
        out.append((technique, len(time_ratios), sorted(time_ratios),
                    sorted(relief_ratios) or None))
    return out


def unseen_technique_lines(pairs):
    def spread(xs):
        return "%s× (%s–%s)" % (fmt(xs[len(xs) // 2]), fmt(xs[0]), fmt(xs[-1]))

    lines = ["", "## A technique it has not seen", "",
             "Each search technique's rows (all its settings) predicted by a fit to every other",
             "technique's rows: how far the model carries to a shader it was not fitted to, such",
             "as one written after the GPU rows were measured. Median (range) over the technique's",
             "rows of predicted over measured time, and of its time over relief 32+6's in the",
             "same view, predicted over measured: above 1, the model makes it look dearer than",
             "the GPU does.", "",
             "| technique left out | rows | predicted / measured time | its time over relief "
             "32+6's, predicted / measured |", "| --- | ---: | ---: | ---: |"]
    for technique, n, time_ratios, relief_ratios in by_technique_cross_validation(pairs):
        lines.append("| `%s` | %d | %s | %s |" % (technique, n, spread(time_ratios),
                                                 spread(relief_ratios) if relief_ratios else "–"))
    return lines


def bias_lines(pairs, weights):
    """Where the fit errs in sample: per search technique and elevation, the median of predicted
    over measured time. A pattern across elevations is what the counters miss (a cost that grows
    with the view but not with the ops); relief 32+6, every ratio's yardstick, has its own row."""
    ratios = defaultdict(list)
    for t, c in pairs:
        if t["technique"] in SHADING_ONLY:
            continue
        r = predict(weights, c) / measured(t)
        ratios[(t["technique"], float(t["elevation_deg"]))].append(r)
        if is_relief_32_6(t):
            ratios[("relief 32+6", float(t["elevation_deg"]))].append(r)
    elevations = sorted({e for _, e in ratios})
    lines = ["", "## Where it errs", "",
             "Per search technique and elevation, the median over the fitted rows (in sample: every",
             "map and setting) of predicted over measured time. Above 1 the model makes it dearer",
             "than the GPU does. A row that climbs or falls across the elevations is a cost the",
             "counters do not see; the ratios to relief 32+6 that the exact-at-guess-cost folders",
             "state inherit its row's error.", "",
             "| technique | " + " | ".join("%g°" % e for e in elevations) + " |",
             "| --- |" + " ---: |" * len(elevations)]
    for technique in sorted({k for k, _ in ratios}, key=lambda k: (k != "relief 32+6", k)):
        cells = []
        for e in elevations:
            xs = sorted(ratios.get((technique, e), []))
            cells.append(fmt(xs[len(xs) // 2]) if xs else "–")
        name = technique if technique == "relief 32+6" else "`%s`" % technique
        lines.append("| %s | %s |" % (name, " | ".join(cells)))
    return lines


def fmt(x, digits=3):
    return "%.*g" % (digits, x)


def model_text(args, weights, fitted_paths):
    lines = ["# %s's frame time predicted from what any renderer counts (harness/core/cost_model.h)." %
             args.gpu,
             "# Written by scripts/fit-cost-model.py from the rows it names; results/gpu-model/",
             "# README.md gives the fit's cross-validation by map and its judgement on held-out rows.",
             'gpu = "%s"' % args.gpu,
             "fitted_to = [%s]" % ", ".join('"%s"' % p for p in fitted_paths),
             "", "[weights]"]
    for name, unit, w in zip(WEIGHTS, WEIGHT_UNITS, weights):
        lines.append("%s = %s  # %s" % (name, repr(round(w, 9)), unit))
    return "\n".join(lines) + "\n"


def judgement_row(label, j):
    return "| %s | %d | %d | %s (min %s) | %s%% | %s× | %s%% |" % (
        label, j["rows"], j["views"], fmt(j["spearman"]), fmt(j["spearman_min"]),
        fmt(100 * j["within_125"], 3), fmt(j["median_ratio"]), fmt(100 * j["front_agreement"], 3))


def baseline_rows(pairs, label):
    """The same judgement for single counts used as the cost, as the project ranked before."""
    out = []
    for column in ["warp_fetches_per_px", "fetches_mean"]:
        guess = [float(c[column]) for _, c in pairs]
        j = judge(pairs, guess)
        out.append("| %s by `%s` alone | %d | %d | %s (min %s) | – | – | %s%% |" % (
            label, column, j["rows"], j["views"], fmt(j["spearman"]), fmt(j["spearman_min"]),
            fmt(100 * j["front_agreement"], 3)))
    return out


def short(spec):
    """A rows file's folder and name, e.g. gpu-cost/h200-2026-12-04/rows.csv."""
    path = spec.split(":")[0]
    return "/".join(path.split("/")[-3:])


def report_text(args, weights, fit_sets, judge_sets):
    fit_pairs = [p for _, ps in fit_sets for p in ps]
    lines = ["# A GPU cost model: %s" % args.gpu, "",
             "Written by `scripts/fit-cost-model.py` (regenerate: `scripts/gpu-model.sh`); the build",
             "re-runs it with `--check`, so these numbers cannot drift from the rows. The model, its",
             "counters and its use are described in `harness/core/cost_model.h`; the weights are",
             "`%s`." % args.model, "",
             "**Fitted to** %d rows measured on the %s: %s; their op counts from %s." % (
                 len(fit_pairs), args.gpu, ", ".join("`%s`" % short(s) for s in args.fit),
                 ", ".join("`%s`" % short(s.split(":")[1] if ":" in s else s) for s in args.fit)),
             "", "| weight | value | unit |", "| --- | ---: | --- |"]
    for name, unit, w in zip(WEIGHTS, WEIGHT_UNITS, weights):
        lines.append("| `%s` | %s | %s |" % (name, fmt(w, 4), unit))
    lines += ["", "## How well it predicts", "",
              "Per view (map, elevation, azimuth, viewport): Spearman's rank correlation between",
              "predicted and measured time over the search settings (normal and parallax left",
              "out), the share of rows predicted within 1.25× of the measured time, the median of",
              "max(predicted/measured, measured/predicted), and how much the Pareto fronts of",
              "`wrong_pct` against predicted and against measured time agree (settings on both",
              "over settings on either).", "",
              "| rows | n | views | Spearman per view | within 1.25× | median ratio | fronts agree |",
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    lines.append(judgement_row("fitted rows, in sample", judge(fit_pairs, [predict(weights, c) for _, c in fit_pairs])))
    lines.append(judgement_row("fitted rows, each map predicted by a fit without it",
                               judge(fit_pairs, by_map_cross_validation(fit_pairs))))
    # Each fitted set predicted by a fit to the others alone: other maps, views and sizes.
    for spec, pairs in fit_sets if len(fit_sets) > 1 else []:
        others = [p for other, ps in fit_sets if other != spec for p in ps]
        w = fit(others)
        lines.append(judgement_row("`%s` by a fit to the other set(s) alone" % short(spec),
                                   judge(pairs, [predict(w, c) for _, c in pairs])))
    for spec, pairs in judge_sets:
        lines.append(judgement_row("held out: `%s`" % short(spec),
                                   judge(pairs, [predict(weights, c) for _, c in pairs])))
    for spec, pairs in fit_sets + judge_sets:
        lines += baseline_rows(pairs, "`%s`" % short(spec))
    lines += bias_lines(fit_pairs, weights)
    lines += unseen_technique_lines(fit_pairs)
    for spec in args.renderer_check:
        lines += renderer_check(spec)
    unweighted = [k for k, w in zip(WEIGHTS, weights) if k in KINDS and w == 0]
    return "\n".join(lines) + "\n" + LIMITS.format(
        unweighted="The fit gives %s no weight of its own: on these rows their cost is carried by "
        "the kinds around them." % ", ".join("`%s`" % k for k in unweighted)
        if unweighted else "Every kind has a weight of its own.")


def renderer_check(spec):
    """How far op counts made on the GPU itself are from the same cells' counts on llvmpipe."""
    gpu_path, _, llvmpipe_path = spec.partition(":")
    pairs = joined(gpu_path + ":" + llvmpipe_path)
    worst = {k: 0.0 for k in KINDS}
    gpu_rows = read_rows(gpu_path)
    params = parameter_columns(list(gpu_rows[0].keys()))
    llvmpipe = {cell_id(r, params): r for r in read_rows(llvmpipe_path)}
    for g in gpu_rows:
        l = llvmpipe[cell_id(g, params)]
        for k in KINDS:
            a, b = float(g["warp_%s_ops" % k]), float(l["warp_%s_ops" % k])
            if b > 0:
                worst[k] = max(worst[k], abs(a - b) / b)
    lines = ["", "## The counts are the shader's, not the renderer's", "",
             "The %d cells of `%s` were counted on the %s itself and on llvmpipe" %
             (len(gpu_rows), short(gpu_path), pairs[0][0]["renderer"]),
             "(`%s`) by one build of the counting code, the package's. The largest" % short(llvmpipe_path),
             "difference in any cell, by kind:", "",
             "| kind | largest relative difference |", "| --- | ---: |"]
    lines += ["| %s | %s%% |" % (k, fmt(100 * worst[k], 2)) for k in KINDS]
    lines += ["", "They differ where the two runs' rays differ: the GPU run resampled the maps through the",
              "stb fallback, llvmpipe's run through OpenImageIO, and the two renderers round apart."]
    return lines


LIMITS = """
## What it leaves out

- One GPU: the weights are the H200's, whose graphics run on a few of its TPCs; another GPU
  needs its own rows (`scripts/gpu-rows.sh` with the package) and its own fit.
- Op counts are glslang's SPIR-V before any optimiser, classified by kind (the harness's own
  fetch and iteration counters, which the timed program never reads, left out); the driver's
  compiler removes, fuses and schedules. The fit absorbs a constant ratio per kind, not what
  differs between shaders.
- Memory is not modelled beyond texture reads as ops: cache behaviour (a dependent read, a
  scattered quadtree node) is priced like any read. {unweighted}
- A lockstep group is an 8 x 4 tile paying, per kind, its slowest lane's count: a divergent
  group that runs both sides of a branch pays more than that on a GPU.
"""


def write_or_check(path, text, check):
    if check:
        with open(path) as f:
            if f.read() != text:
                sys.exit("fit-cost-model: %s differs from what its rows give; regenerate it with "
                         "scripts/gpu-model.sh" % path)
        return
    with open(path, "w") as f:
        f.write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--gpu", required=True)
    ap.add_argument("--fit", action="append", required=True)
    ap.add_argument("--judge", action="append", default=[])
    ap.add_argument("--model", required=True)
    ap.add_argument("--report", required=True)
    ap.add_argument("--renderer-check", action="append", default=[],
                    help="GPU_ROWS.csv:LLVMPIPE_ROWS.csv: the same cells counted on both")
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    fit_sets = [(spec, joined(spec)) for spec in args.fit]
    weights = fit([p for _, ps in fit_sets for p in ps])
    judge_sets = [(spec, joined(spec)) for spec in args.judge]
    write_or_check(args.model, model_text(args, weights, [s.split(":")[0] for s in args.fit]),
                   args.check)
    write_or_check(args.report, report_text(args, weights, fit_sets, judge_sets), args.check)


if __name__ == "__main__":
    main()
