#!/usr/bin/env bash
# The firmware test: build the Cortex-M4F image, run it under QEMU (mps2-an386, semihosting),
# and compare every number it prints with the host's double-precision run of the same loop.
# Usage: run_qemu_test.sh BUILD_DIR HOST_REFERENCE_BINARY
# Exit: 0 pass, 1 mismatch or failure, 77 skipped (no arm-none-eabi toolchain or QEMU).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$1
reference=$2
for tool in arm-none-eabi-g++ qemu-system-arm python3; do
  command -v "$tool" >/dev/null || { echo "firmware test skipped: $tool not installed"; exit 77; }
done
cmake -S "$here" -B "$build" --toolchain "$here/arm-none-eabi.cmake" -G Ninja >/dev/null
cmake --build "$build"
target_out=$(mktemp)
host_out=$(mktemp)
trap 'rm -f "$target_out" "$host_out"' EXIT
timeout 120 qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
  -semihosting-config enable=on,target=native -kernel "$build/kraft_controller.elf" >"$target_out" 2>&1
# (QEMU writes semihosting output to its standard error.)
"$reference" >"$host_out"
python3 "$here/compare_outputs.py" "$target_out" "$host_out"
