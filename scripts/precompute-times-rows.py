#!/usr/bin/env python3
"""results/precompute-times/rows.csv from bench/bench_precompute: every CPU precompute (safety
radii, cone maps, texture-space AO maps) on every benchmark map and size, timed `--runs` times
in random interleaving, so that its verdicts are claims checked by `relieflab verify` like every
other folder's (the goal: each at 1024^2 in at most 1 s on 2 cores).

    cmake --build build --target bench_precompute && scripts/precompute-times-rows.py

One row per precompute, map and size: the fastest and slowest of the runs (this machine's wall
times move by up to 25% between identical runs, so the fastest is the figure quoted), the map's
fingerprint (the same bits in every run, or the script stops), the cores it may use (its affinity
mask: `taskset -c 0,1` times 2 cores on a bigger machine), the processor's name and the date. The
per-texel march is left out: it is the slow reference (tens of seconds at 1024^2), timed by the
benchmark itself. So is its fragment-shader version unless `--gpu` asks for it on a machine with
a GPU (refused on llvmpipe, where it is the slowest of all): rows `ao_map_fragment_shader`,
naming the GL renderer, beside the CPU's.

    taskset -c 0,1 scripts/precompute-times-rows.py --gpu   # on a GPU-lent machine
"""
import argparse
import csv
import datetime
import json
import os
import subprocess
import sys
import outputs_record  # scripts/outputs_record.py, beside this one

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FOLDER = os.path.join(ROOT, "results", "precompute-times")
FILTER = r"^BM_(SafetyRadius|ConeMap|AoMap/ao_(rock|bricks|sines))/"
GPU_FILTER = r"^BM_AoMap/ao_gpu_(rock|bricks|sines)/"

# Benchmark name (BM_<family>/<case>) -> (precompute, map).
def describe(family, case):
    conservative = case.endswith("_conservative")
    case = case.removesuffix("_conservative")
    if family == "BM_SafetyRadius":
        return ("safety_radius_conservative" if conservative else "safety_radius"), case
    if family == "BM_ConeMap":
        return ("cone_conservative" if conservative else "cone_relaxed"), case.removeprefix("cone_")
    if family == "BM_AoMap" and case.startswith("ao_gpu_"):
        return "ao_map_fragment_shader", case.removeprefix("ao_gpu_")
    if family == "BM_AoMap":
        return "ao_map", case.removeprefix("ao_")
    raise SystemExit(f"precompute-times-rows: unknown benchmark family {family}")


def cpu_model():
    """The processor's name as the kernel gives it ("Intel(R) Xeon(R) Processor"): the verdicts
    are about one machine, and rows from two machines differ by up to 40% (README)."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


def gl_renderer(bench):
    """The GL renderer the fragment-shader rows would be timed on, from one small run."""
    out = subprocess.run(
        [bench, "--benchmark_filter=^BM_AoMap/ao_gpu_rock/256/", "--benchmark_format=json"],
        check=True, capture_output=True, text=True).stdout
    return json.loads(out)["benchmarks"][0].get("label", "")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bench", default=os.path.join(ROOT, "build", "bench", "bench_precompute"))
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--gpu", action="store_true",
                        help="also time the fragment-shader AO map (a real GPU only)")
    args = parser.parse_args()
    if not os.access(args.bench, os.X_OK):
        sys.exit(f"precompute-times-rows: {args.bench} is not built "
                 "(cmake --build build --target bench_precompute)")
    if args.gpu:
        renderer = gl_renderer(args.bench)
        if "llvmpipe" in renderer or "softpipe" in renderer:
            sys.exit(f"precompute-times-rows: --gpu needs a GPU; this machine renders with {renderer}")
    bench_filter = f"({FILTER})|({GPU_FILTER})" if args.gpu else FILTER
    out = subprocess.run(
        [args.bench, f"--benchmark_filter={bench_filter}", f"--benchmark_repetitions={args.runs}",
         "--benchmark_enable_random_interleaving=true", "--benchmark_format=json"],
        check=True, capture_output=True, text=True).stdout
    runs = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        family, case, size = b["run_name"].split("/")[:3]
        assert b["time_unit"] == "ms", b["time_unit"]
        runs.setdefault((family, case, int(size)), []).append(b)
    rows = []
    for (family, case, size), taken in runs.items():
        fingerprints = {b["fingerprint"] for b in taken}
        if len(fingerprints) != 1:
            sys.exit(f"precompute-times-rows: {family}/{case}/{size} gave different maps "
                     f"from run to run: {sorted(fingerprints)}")
        times = [b["real_time"] for b in taken]
        precompute, map_name = describe(family, case)
        renderer = taken[0].get("label", "")
        rows.append({
            "precompute": precompute, "map": map_name, "texture_res": size,
            "precompute_ms": f"{min(times):.1f}", "precompute_ms_slowest": f"{max(times):.1f}",
            "runs": len(times), "fingerprint": f"{int(fingerprints.pop()):d}",
            "cores": len(os.sched_getaffinity(0)), "cpu": cpu_model(), "renderer": renderer,
            "measured": datetime.date.today().isoformat()})
    rows.sort(key=lambda r: (r["precompute"], r["map"], r["texture_res"]))
    os.makedirs(FOLDER, exist_ok=True)
    path = os.path.join(FOLDER, "rows.csv")
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    os.replace(path + ".tmp", path)
    outputs_record.write_record(FOLDER, ["rows.csv"])
    print(f"results/precompute-times/rows.csv: {len(rows)} rows, {args.runs} runs each")


if __name__ == "__main__":
    main()
