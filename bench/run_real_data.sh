#!/usr/bin/env bash
# The diagnosis on real arm logs (../shared/real-data/, when present; never copied into the
# project). Franka Panda (Gaz et al. 2019): the log is converted to CSV in a temporary folder and
# diagnosed twice, against robots/panda.yaml (friction approximated by Coulomb = phi1/2) and
# against the same description with its friction removed, where the published model says the
# diagnosis must find friction.
# Usage: bench/run_real_data.sh [DYNCC] [DATA_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
dyncc=${1:-build/release/dyncc}
data=${2:-../shared/real-data}
[[ -x $dyncc ]] || { echo "run_real_data: $dyncc not built" >&2; exit 2; }
if [[ ! -d $data/panda_gaz2019 ]]; then
  echo "run_real_data: $data/panda_gaz2019 not present; nothing to do"
  exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 bench/panda_log_to_csv.py "$data/panda_gaz2019" "$work/panda.csv"
# The description without its friction block and the friction parameters' values.
python3 - robots/panda.yaml "$work/panda_nofriction.yaml" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
s = re.sub(r'\nfriction:.*?\n\n', '\n\n', s, flags=re.S)
s = re.sub(r'\n  f[cv][1-7]: [^\n]*', '', s)
open(sys.argv[2], 'w').write(s)
PY
for robot in robots/panda.yaml "$work/panda_nofriction.yaml"; do
  echo "=== dyncc diagnose $(basename "$robot") panda_gaz2019 exciting trajectory ==="
  "$dyncc" diagnose "$robot" "$work/panda.csv" 2>/dev/null | sed -n '/held-out gap/,$p'
done
