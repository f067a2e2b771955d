#!/usr/bin/env bash
# Flash and RAM of the Kraft controller firmware (arm-none-eabi-size), the stack frames of the
# control path (-fstack-usage), and the instructions of one control step counted by QEMU
# (one instruction per translation block, every execution logged; 100 steps minus 0 steps).
# Usage: runtime/firmware/report.sh [BUILD_DIR]   (default build/firmware)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../../build/firmware}
cmake -S "$here" -B "$build" --toolchain "$here/arm-none-eabi.cmake" -G Ninja >/dev/null
cmake --build "$build" >/dev/null
echo "== size (bytes): flash = text + data, RAM = data + bss + stack"
arm-none-eabi-size "$build/kraft_controller.elf"
echo "== largest stack frames of the control path (bytes)"
find "$build" -name '*.su' -path '*kraft_controller*' -exec cat {} + | sort -t$'\t' -k2 -n -r | head -5
count() {
  local log
  log=$(mktemp)
  timeout 300 qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native -singlestep -d exec,nochain -D "$log" \
    -kernel "$build/kraft_steps_$1.elf" >/dev/null 2>&1
  grep -c Trace "$log"
  rm -f "$log"
}
zero=$(count 0)
hundred=$(count 100)
echo "== instructions per control step (controller step: fused Y p and Y^T eps, adaptation, H^ check)"
echo "$(( (hundred - zero) / 100 )) (QEMU $(qemu-system-arm --version | head -1 | awk '{print $4}'), $(arm-none-eabi-gcc --version | head -1))"
