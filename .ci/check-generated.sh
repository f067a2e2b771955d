#!/usr/bin/env bash
# Fails when generated/ is not exactly what today's generator writes: every generated/<robot>/
# folder is regenerated from robots/<robot>.yaml in --check mode (nothing is written).
# Usage: .ci/check-generated.sh [DYNCC_BINARY]   (default build/release/dyncc)
set -euo pipefail
cd "$(dirname "$0")/.."
dyncc=${1:-build/release/dyncc}
[[ -x $dyncc ]] || { echo "check-generated: $dyncc not built" >&2; exit 2; }
status=0
for dir in generated/*/; do
  robot=$(basename "$dir")
  if [[ ! -f robots/$robot.yaml ]]; then
    echo "check-generated: $dir has no description robots/$robot.yaml" >&2
    status=1
    continue
  fi
  "$dyncc" generate "robots/$robot.yaml" -o "generated/$robot" --check 2>/dev/null || {
    echo "check-generated: generated/$robot is stale; run: $dyncc generate robots/$robot.yaml -o generated/$robot" >&2
    status=1
  }
done
exit $status
