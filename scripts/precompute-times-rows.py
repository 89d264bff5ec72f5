#!/usr/bin/env python3
"""results/precompute-times/rows.csv from bench/bench_precompute: every CPU precompute (safety
radii, cone maps, texture-space AO maps) on every benchmark map and size, timed `--runs` times
in random interleaving, so that its verdicts are claims checked by `relieflab verify` like every
other folder's (issue 32: each at 1024^2 in at most 1 s on 2 cores).

    cmake --build build --target bench_precompute && scripts/precompute-times-rows.py

One row per precompute, map and size: the fastest and slowest of the runs (this machine's wall
times move by up to 25% between identical runs, so the fastest is the figure quoted), the map's
fingerprint (the same bits in every run, or the script stops), the cores it may use (its affinity
mask: `taskset -c 0,1` times 2 cores on a bigger machine), the processor's name and the date. The
per-texel march and its fragment-shader version are left out: they are the slow references
(tens of seconds at 1024^2), timed by the benchmark itself.
"""
import argparse
import csv
import datetime
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FOLDER = os.path.join(ROOT, "results", "precompute-times")
FILTER = r"^BM_(SafetyRadius|ConeMap|AoMap/ao_(rock|bricks|sines))/"

# Benchmark name (BM_<family>/<case>) -> (precompute, map).
def describe(family, case):
    conservative = case.endswith("_conservative")
    case = case.removesuffix("_conservative")
    if family == "BM_SafetyRadius":
        return ("safety_radius_conservative" if conservative else "safety_radius"), case
    if family == "BM_ConeMap":
        return ("cone_conservative" if conservative else "cone_relaxed"), case.removeprefix("cone_")
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


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bench", default=os.path.join(ROOT, "build", "bench", "bench_precompute"))
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    if not os.access(args.bench, os.X_OK):
        sys.exit(f"precompute-times-rows: {args.bench} is not built "
                 "(cmake --build build --target bench_precompute)")
    out = subprocess.run(
        [args.bench, f"--benchmark_filter={FILTER}", f"--benchmark_repetitions={args.runs}",
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
        rows.append({
            "precompute": precompute, "map": map_name, "texture_res": size,
            "precompute_ms": f"{min(times):.1f}", "precompute_ms_slowest": f"{max(times):.1f}",
            "runs": len(times), "fingerprint": f"{int(fingerprints.pop()):d}",
            "cores": len(os.sched_getaffinity(0)), "cpu": cpu_model(),
            "measured": datetime.date.today().isoformat()})
    rows.sort(key=lambda r: (r["precompute"], r["map"], r["texture_res"]))
    os.makedirs(FOLDER, exist_ok=True)
    path = os.path.join(FOLDER, "rows.csv")
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    os.replace(path + ".tmp", path)
    print(f"results/precompute-times/rows.csv: {len(rows)} rows, {args.runs} runs each")


if __name__ == "__main__":
    main()
