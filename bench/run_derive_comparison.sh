#!/usr/bin/env bash
# Whole-model derivation: `dyncc verify` (parse, kinematics, H, C, g, Y, base parameters, proofs
# and 1000-state numeric checks) on the Kraft arm, the PUMA 560 and the Panda, beside a plain
# SymPy Lagrangian derivation of the same Kraft model (bench/sympy_kraft_lagrangian.py), in one
# run. Checks that SymPy's H, C, g at a state equal `dyncc eval`'s (so both derived the same
# model) and prints a Markdown table for docs/performance.md.
#
# usage: bench/run_derive_comparison.sh [--runs N]     (default 5 runs per robot; median shown)
# Needs the release build (cmake --workflow --preset release) and Debian's python3-sympy/-yaml.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DYNCC="$ROOT/build/release/dyncc"
PYTHON=/usr/bin/python3
RUNS=5
while [[ $# -gt 0 ]]; do
  case "$1" in
    --runs) RUNS="$2"; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
done
[[ -x $DYNCC ]] || { echo "error: $DYNCC missing (cmake --workflow --preset release)" >&2; exit 1; }
cd "$ROOT"

median_seconds() {  # median wall time of RUNS executions of "$@"
  local times=()
  for ((i = 0; i < RUNS; ++i)); do
    local start end
    start=$(date +%s.%N)
    "$@" >/dev/null 2>&1 || { echo "error: '$*' failed" >&2; exit 1; }
    end=$(date +%s.%N)
    times+=("$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')")
  done
  printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'
}

echo "| robot | dyncc verify (derive + base parameters + proofs + checks), median of $RUNS | base parameters |"
echo "|---|---|---|"
for robot in kraft puma560 panda; do
  t=$(median_seconds "$DYNCC" verify "robots/$robot.yaml")
  bases=$("$DYNCC" verify "robots/$robot.yaml" --json | "$PYTHON" -c '
import json, sys
d = json.load(sys.stdin)
print(next((c.get("value", "") for c in d.get("checks", []) if c.get("name", "").startswith("base parameters")), "?"))')
  printf '| %s | %.3f s | %s |\n' "$robot" "$t" "$bases"
done

echo
echo "SymPy $("$PYTHON" -c 'import sympy; print(sympy.__version__)') plain Lagrangian, Kraft, without trigsimp (one run):"
# Without trigsimp: with it, SymPy did not finish in 20 minutes (docs/performance.md).
sympy_json=$("$PYTHON" bench/sympy_kraft_lagrangian.py robots/kraft.yaml --no-trigsimp)
dyncc_json=$("$DYNCC" eval robots/kraft.yaml --q 0.3,-0.4,0.5 --qd 0.7,-0.2,0.9 --json)
"$PYTHON" - "$sympy_json" "$dyncc_json" <<'EOF'
import json, sys
s, d = json.loads(sys.argv[1]), json.loads(sys.argv[2])
for k, v in s["times"].items():
    print(f"  {k:<12} {v:8.2f} s")
worst = 0.0
for key in ("H", "C"):
    for rs, rd in zip(s[key], d[key]):
        worst = max(worst, max(abs(a - b) for a, b in zip(rs, rd)))
worst = max(worst, max(abs(a - b) for a, b in zip(s["g"], d["g"])))
print(f"  largest |SymPy - dyncc| over H, C, g at the check state: {worst:.2e}")
sys.exit(0 if worst < 1e-9 else 1)
EOF
