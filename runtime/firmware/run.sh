#!/usr/bin/env bash
# Builds the Kraft controller firmware (Cortex-M4F) and runs it under QEMU: prints its size,
# the last outputs (the adapted parameter estimates, as float bits) and its exit status.
# Usage: runtime/firmware/run.sh [BUILD_DIR]   (default build/firmware)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../../build/firmware}
cmake -S "$here" -B "$build" --toolchain "$here/arm-none-eabi.cmake" -G Ninja >/dev/null
cmake --build "$build" --target kraft_controller.elf | grep -A1 -E '^\s+text' || true
out=$(mktemp)
trap 'rm -f "$out"' EXIT
status=0
timeout 120 qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
  -semihosting-config enable=on,target=native -kernel "$build/kraft_controller.elf" >"$out" 2>&1 || status=$?
echo "firmware on QEMU mps2-an386: $(grep -c '^tau' "$out") torques at 81 Hz, final estimate:"
grep '^p ' "$out" | python3 -c "
import struct, sys
values = [struct.unpack('>f', bytes.fromhex(line.split()[2][2:]))[0] for line in sys.stdin]
print('  ' + ' '.join(format(v, '.4g') for v in values))"
echo "exit status $status"
exit $status
