#!/usr/bin/env bash
# Per-call times of the generated code beside plain Eigen and MuJoCo, from ONE run of
# generated_bench, as the markdown table of docs/performance.md (with the machine and date).
# Usage: bench/run_speed_comparison.sh [BUILD_DIR]   (default build/release)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build/release}
cmake --build "$build" --target generated_bench >/dev/null
json=$(mktemp)
trap 'rm -f "$json"' EXIT
"$build/bench/generated_bench" --benchmark_min_time=0.3 --benchmark_repetitions=3 \
  --benchmark_report_aggregates_only=true --benchmark_format=json >"$json" 2>/dev/null
python3 - "$json" <<'PY'
import json, sys, collections
data = json.load(open(sys.argv[1]))
ctx = data["context"]
times = {}
for b in data["benchmarks"]:
    if b.get("aggregate_name") != "median":
        continue
    quantity, impl, robot = b["run_name"].split("/")
    times[(quantity, impl, robot)] = b["real_time"] if b["time_unit"] == "ns" else b["real_time"] * 1e3
print(f"Machine: {ctx.get('host_name')}, {ctx['num_cpus']} CPUs at {ctx.get('mhz_per_cpu')} MHz; "
      f"{ctx['date']}; median of 3 repetitions, ns per call.\n")
print("| quantity | robot | dyncc | dyncc float | Eigen | MuJoCo | Eigen / dyncc | MuJoCo / dyncc |")
print("|---|---|---:|---:|---:|---:|---:|---:|")
for quantity in ["InverseDynamics", "MassMatrix", "Gravity", "Coriolis", "Regressor", "ControlStep"]:
    for robot in ["kraft", "puma560", "panda"]:
        d = times.get((quantity, "dyncc", robot))
        if d is None:
            continue
        f = times.get((quantity, "dyncc-float", robot))
        e = times.get((quantity, "Eigen", robot))
        m = times.get((quantity, "MuJoCo", robot))
        cell = lambda x: f"{x:.0f}" if x is not None else "–"
        ratio = lambda x: f"{x / d:.1f}×" if x is not None else "–"
        print(f"| {quantity} | {robot} | {cell(d)} | {cell(f)} | {cell(e)} | {cell(m)} | {ratio(e)} | {ratio(m)} |")
PY
