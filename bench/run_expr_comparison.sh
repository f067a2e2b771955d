#!/usr/bin/env bash
# Expression engine vs SymPy on the kinetic energy of a 3- and a 6-link chain.
#
# Builds bench/expr_bench (release preset) if needed, runs it and bench/sympy_expr_bench.py in the
# same run, checks that both produced the same number of terms, and rewrites the results section of
# docs/performance.md (between the expr-comparison markers; appended when the markers are missing).
#
# usage: bench/run_expr_comparison.sh [--sizes "3 6"] [--timeout SECONDS] [--side-timeout SECONDS]
#                                     [--no-doc]
#   --timeout       CPU-second limit per SymPy run of a main task (default 120)
#   --side-timeout  CPU-second limit per run of the slower, context-only SymPy zero tests (default 30)
#   --no-doc        print the table, leave docs/performance.md alone
# Raw results stay in build/release/expr_comparison/. About 5 CPU-minutes, mostly SymPy (12 minutes
# wall on a loaded 2-core machine).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build/release"
OUT="$BUILD/expr_comparison"
PYTHON=/usr/bin/python3  # Debian's python3 with python3-sympy, not a pyenv python from PATH
SIZES="3 6"
TIMEOUT=120
SIDE_TIMEOUT=30
WRITE_DOC=1

while [[ $# -gt 0 ]]; do
  case "$1" in
    --sizes) SIZES="$2"; shift 2 ;;
    --timeout) TIMEOUT="$2"; shift 2 ;;
    --side-timeout) SIDE_TIMEOUT="$2"; shift 2 ;;
    --no-doc) WRITE_DOC=0; shift ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
done

if ! "$PYTHON" -c 'import sympy' 2>/dev/null; then
  echo "error: $PYTHON cannot import sympy (apt-get install python3-sympy)" >&2
  exit 1
fi

# ---- build (only the benchmark and what it links) ----
if [[ ! -f "$BUILD/build.ninja" ]]; then
  (cd "$ROOT" && cmake --preset release)
fi
cmake --build "$BUILD" -j2 --target expr_bench
BENCH="$BUILD/bench/expr_bench"

mkdir -p "$OUT"
rm -f "$OUT"/dyncc_*.json "$OUT"/sympy.json
LOAD_BEFORE="$(cut -d' ' -f1-3 /proc/loadavg)"
START_DATE="$(date -u '+%Y-%m-%d %H:%M UTC')"

# ---- dyncc: one process per benchmark, so the intern pool of one does not slow the next ----
for n in $SIZES; do
  for b in BM_Build BM_BuildExpand BM_Diff BM_ZeroTest BM_BuildExpandWarm BM_DiffWarm BM_ZeroTestWarm; do
    echo "dyncc $b/$n" >&2
    "$BENCH" --benchmark_filter="^$b/$n\$" --benchmark_repetitions=5 --benchmark_min_time=0.25 \
      --benchmark_report_aggregates_only=true --benchmark_out_format=json \
      --benchmark_out="$OUT/dyncc_${b}_$n.json" >/dev/null
  done
done

# ---- SymPy ----
# shellcheck disable=SC2086  # SIZES is a list
"$PYTHON" "$ROOT/bench/sympy_expr_bench.py" --sizes $SIZES --timeout "$TIMEOUT" --side-timeout "$SIDE_TIMEOUT" \
  --json "$OUT/sympy.json"

LOAD_AFTER="$(cut -d' ' -f1-3 /proc/loadavg)"

# ---- table ----
CXX_VERSION="$("$(grep -E '^CMAKE_CXX_COMPILER:' "$BUILD/CMakeCache.txt" | cut -d= -f2)" --version | head -1)"
BENCHMARK_VERSION="$(dpkg-query -W -f='${Version}' libbenchmark-dev 2>/dev/null || echo unknown)"
CPU_MODEL="$(grep -m1 '^model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
CORES="$(nproc)"

export OUT SIZES START_DATE LOAD_BEFORE LOAD_AFTER CXX_VERSION BENCHMARK_VERSION CPU_MODEL CORES WRITE_DOC
export DOC="$ROOT/docs/performance.md"
"$PYTHON" - <<'PY'
import glob, json, os, sys

out = os.environ["OUT"]
sizes = [int(s) for s in os.environ["SIZES"].split()]

dyncc = {}  # "BM_Diff/6" -> median aggregate
for path in glob.glob(os.path.join(out, "dyncc_*.json")):
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    for b in data["benchmarks"]:
        if b.get("aggregate_name") == "median":
            dyncc[b["run_name"]] = b
with open(os.path.join(out, "sympy.json"), encoding="utf-8") as f:
    sympy = json.load(f)
sres = sympy["results"]

UNIT = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def dyncc_seconds(name):
    b = dyncc.get(name)
    if b is None or b.get("error_occurred"):
        return None
    return b["cpu_time"] * UNIT[b["time_unit"]]


def fmt_time(s):
    if s >= 1:
        return f"{s:.3g} s"
    if s >= 1e-3:
        return f"{s * 1e3:.3g} ms"
    return f"{s * 1e6:.3g} µs"


def sympy_cell(r):
    if r is None:
        return "not run", None, None
    if "timeout" in r:
        note = " (not run: timed out on N=3)" if "skipped" in r else ""
        return f"> {r['timeout']:g} s{note}", None, r["timeout"]
    return fmt_time(r["seconds"]), r["seconds"], None


def ratio_cell(sympy_s, sympy_lower, dyncc_s):
    if dyncc_s is None:
        return "—"
    if sympy_s is not None:
        return f"{sympy_s / dyncc_s:,.0f}×"
    if sympy_lower is not None:
        return f"> {sympy_lower / dyncc_s:,.0f}×"
    return "—"


rows = []
mismatch = []
goal_missed = []
TASKS = [
    ("build", "BM_Build", "build T (unexpanded)", None),
    ("build_expand", "BM_BuildExpand", "build T + `expand`", "terms"),
    ("diff", "BM_Diff", "N + N² derivatives of expanded T", "terms"),
    ("zero", "BM_ZeroTest", "zero test T_body − T_world", None),
]
ZERO_METHODS = ["zero_ring", "zero_ring_final", "zero_reduced", "zero_trigsimp"]
for n in sizes:
    for key, bm, label, count in TASKS:
        d = dyncc_seconds(f"{bm}/{n}")
        if key == "zero":
            finished = [(sres[f"{m}/{n}"]["seconds"], m) for m in ZERO_METHODS
                        if f"{m}/{n}" in sres and "seconds" in sres[f"{m}/{n}"]]
            if finished:
                best_s, best_m = min(finished)
                s_cell, s_s, s_lower = fmt_time(best_s) + f" (`{best_m}`)", best_s, None
            else:
                limits = [sres[f"{m}/{n}"]["timeout"] for m in ZERO_METHODS if f"{m}/{n}" in sres]
                s_cell, s_s, s_lower = f"> {max(limits):g} s (all methods)", None, max(limits)
        else:
            s_cell, s_s, s_lower = sympy_cell(sres.get(f"{key}/{n}"))
        terms = "—"
        if count:
            dt = dyncc.get(f"{bm}/{n}", {}).get(count)
            st = sres.get(f"{key}/{n}", {}).get(count)
            dt = None if dt is None else int(round(dt))
            if dt is not None and st is not None:
                terms = f"{dt:,}" if dt == st else f"**MISMATCH** {dt:,} vs {st:,}"
                if dt != st:
                    mismatch.append(f"{key}/{n}")
            elif dt is not None:
                terms = f"{dt:,} (SymPy: n/a)"
        if d is not None and s_s is not None and s_s / d < 100:
            goal_missed.append(f"{key}/{n}")
        rows.append(f"| {n} | {label} | {fmt_time(d) if d is not None else 'error'} | {s_cell} | "
                    f"{ratio_cell(s_s, s_lower, d)} | {terms} |")

zero_rows = []
for n in sizes:
    cells = []
    for m in ZERO_METHODS:
        c, _, _ = sympy_cell(sres.get(f"{m}/{n}"))
        cells.append(c)
    zero_rows.append(f"| {n} | " + " | ".join(cells) + " |")

warm_rows = []
for n in sizes:
    for bm, label in (("BuildExpand", "build T + `expand`"), ("Diff", "derivatives"), ("ZeroTest", "zero test")):
        fresh, warm = dyncc_seconds(f"BM_{bm}/{n}"), dyncc_seconds(f"BM_{bm}Warm/{n}")
        pool = dyncc.get(f"BM_{bm}/{n}", {}).get("pool_nodes_per_iter")
        if fresh is None or warm is None:
            continue
        warm_rows.append(f"| {n} | {label} | {fmt_time(fresh)} | {fmt_time(warm)} | "
                         f"{'—' if pool is None else f'{pool:,.0f}'} |")

lines = [
    "<!-- expr-comparison:begin (generated by bench/run_expr_comparison.sh; edits here are overwritten) -->",
    f"Run of {os.environ['START_DATE']}.",
    "",
    f"- Machine: {os.environ['CPU_MODEL']}, {os.environ['CORES']} cores (shared); load average "
    f"{os.environ['LOAD_BEFORE']} before, {os.environ['LOAD_AFTER']} after (1, 5, 15 min).",
    f"- dyncc: {os.environ['CXX_VERSION']}, release preset (-O3), Google Benchmark {os.environ['BENCHMARK_VERSION']};"
    " median of 5 repetitions, CPU time.",
    f"- SymPy {sympy['sympy']} (ground types: {sympy['ground_types']}) on Python {sympy['python']} "
    f"({sympy['python_executable']}); median of up to 5 runs, CPU time; limit {sympy['timeout']:g} CPU s "
    f"per run ({sympy['side_timeout']:g} s for the context-only zero-test methods).",
    "",
    "| N | task | dyncc | SymPy | SymPy / dyncc | terms (both) |",
    "|---|------|------:|------:|--------------:|-------------:|",
    *rows,
    "",
    "SymPy zero-test methods (the table above uses the fastest that finished):",
    "",
    "| N | `zero_ring` | `zero_ring_final` | `zero_reduced` | `zero_trigsimp` |",
    "|---|------------:|------------------:|---------------:|----------------:|",
    *zero_rows,
    "",
    "dyncc fresh (new symbols every iteration, used above) vs warm (same nodes already interned):",
    "",
    "| N | task | fresh | warm | new pool nodes per iteration (fresh) |",
    "|---|------|------:|-----:|-------------------------------------:|",
    *warm_rows,
    "",
]
if mismatch:
    lines.append(f"**Term counts differ for {', '.join(mismatch)}: the two engines did not do the same work.**")
    lines.append("")
if goal_missed:
    lines.append(f"Below the 100× goal: {', '.join(goal_missed)}.")
    lines.append("")
lines.append("<!-- expr-comparison:end -->")
section = "\n".join(lines)
print(section)

if os.environ["WRITE_DOC"] == "1":
    doc = os.environ["DOC"]
    text = open(doc, encoding="utf-8").read() if os.path.exists(doc) else "# Performance\n"
    begin = text.find("<!-- expr-comparison:begin")
    end = text.find("<!-- expr-comparison:end -->")
    if begin >= 0 and end > begin:
        text = text[:begin] + section + text[end + len("<!-- expr-comparison:end -->"):]
    else:
        text = text.rstrip("\n") + "\n\n## Results\n\n" + section + "\n"
    with open(doc, "w", encoding="utf-8") as f:
        f.write(text)
    print(f"updated {doc}", file=sys.stderr)
sys.exit(1 if mismatch else 0)
PY
