#!/usr/bin/env bash
# Builds the libFuzzer targets (the `fuzz` CMake preset, clang) and fuzzes each for a bounded
# time. Fails (exit 1) on any crash, sanitizer report, timeout or out-of-memory.
#
# Usage: fuzz/run.sh [--seconds N] [--jobs N] [--no-build] [--crashes] [TARGET...]
#   --seconds N  fuzzing time per target (default $FUZZ_SECONDS or 60)
#   --runs N     instead of a time, N inputs per target from a fixed seed (-seed=1): a bounded,
#                mostly repeatable run (node addresses can steer coverage; see fuzz/README.md)
#   --jobs N     build parallelism (default 2)
#   --no-build   use the existing build/asan/fuzz binaries
#   --crashes    instead of fuzzing, replay the reproducers in fuzz/crashes/ and fail if any
#                still crashes (for whoever fixes them)
#   TARGET       fuzz_expression and/or fuzz_robot_yaml (default: both)
# Environment passed through to the targets: DYNCC_FUZZ_WEAK_ROUNDTRIP=1 and
# DYNCC_FUZZ_NO_ZERO_TEST=1 (fuzz_expression), DYNCC_FUZZ_ALLOW_CATCH_ALL=1 (fuzz_robot_yaml);
# see fuzz/README.md.
#
# The seeds in fuzz/corpus/<name>/ (and robots/*.yaml for the YAML target) are read-only inputs;
# what the fuzzer discovers goes to build/asan/fuzz/corpus/<target>/ and is reused by the next run.
# A failing input is written to build/asan/fuzz/artifacts/ and the command to reproduce it printed.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${FUZZ_SECONDS:-60}
runs=0
jobs=2
build=1
replay=0
targets=()
while (($#)); do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --no-build) build=0; shift ;;
    --crashes) replay=1; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    fuzz_expression|fuzz_robot_yaml) targets+=("$1"); shift ;;
    *) echo "run.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
((${#targets[@]})) || targets=(fuzz_expression fuzz_robot_yaml)

bin="$root/build/asan/fuzz"
if ((build)); then
  (cd "$root" && cmake --preset asan >/dev/null && cmake --build build/asan -j "$jobs" --target "${targets[@]}")
fi

# Per target: seed directories, dictionary, crash-file prefix, extra options.
seeds_of() {
  case "$1" in
    fuzz_expression) echo "$root/fuzz/corpus/expression" ;;
    fuzz_robot_yaml) echo "$root/fuzz/corpus/robot_yaml $root/robots" ;;
  esac
}
dict_of() {
  case "$1" in
    fuzz_expression) echo "$root/fuzz/expression.dict" ;;
    fuzz_robot_yaml) echo "$root/fuzz/robot_yaml.dict" ;;
  esac
}
crash_prefix_of() {
  case "$1" in
    fuzz_expression) echo "expression-" ;;
    fuzz_robot_yaml) echo "robot_yaml-" ;;
  esac
}
options_of() {
  case "$1" in
    fuzz_expression) echo "-max_len=512" ;;
    fuzz_robot_yaml) echo "-max_len=16384" ;;
  esac
}

failed=()
if ((replay)); then
  for t in "${targets[@]}"; do
    shopt -s nullglob
    repros=("$root/fuzz/crashes/$(crash_prefix_of "$t")"*)
    shopt -u nullglob
    for f in "${repros[@]}"; do
      [[ $f == *.md ]] && continue
      if "$bin/$t" -runs=1 -timeout=5 -rss_limit_mb=2048 "$f" >/dev/null 2>&1; then
        echo "fixed:       $t ${f#"$root"/}"
      else
        echo "still fails: $t ${f#"$root"/}   (run: build/asan/fuzz/$t ${f#"$root"/})"
        failed+=("$t:${f#"$root"/}")
      fi
    done
  done
  ((${#failed[@]} == 0)) || exit 1
  exit 0
fi

for t in "${targets[@]}"; do
  corpus="$root/build/asan/fuzz/corpus/$t"
  artifacts="$root/build/asan/fuzz/artifacts"
  mkdir -p "$corpus" "$artifacts"
  log="$root/build/asan/fuzz/$t.log"
  seeds=()
  for d in $(seeds_of "$t"); do [[ -d $d ]] && seeds+=("$d"); done
  read -ra options <<<"$(options_of "$t")"
  # Interned expression nodes are never freed, so one process grows ~5 MB/s at full speed; long
  # runs use a worker process that libFuzzer restarts (stops at the first failure all the same).
  ((seconds > 300 && runs == 0)) && options+=(-fork=1)
  if ((runs > 0)); then
    options+=(-runs="$runs" -seed=1)
    rm -rf "$corpus" && mkdir -p "$corpus"  # start from the committed seeds only, as CI does
  else
    options+=(-max_total_time="$seconds")
  fi
  status=0
  "$bin/$t" -timeout=5 -rss_limit_mb=2048 -print_final_stats=1 \
    -dict="$(dict_of "$t")" "${options[@]}" -artifact_prefix="$artifacts/$t-" \
    "$corpus" "${seeds[@]}" >"$log" 2>&1 || status=$?
  stats=$(grep -E '^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)' "$log" |
          sed 's/^stat:://' | tr -s ' ' | tr '\n' ' ')
  if ((status == 0)); then
    echo "ok:     $t $( ((runs > 0)) && echo "${runs} runs" || echo "${seconds}s")  $stats"
  else
    echo "FAILED: $t (exit $status)  $stats"
    grep -E '^(fuzz_|==[0-9]+==ERROR|SUMMARY|.*runtime error|terminate called|  what\(\))' "$log" | head -10 | sed 's/^/  /'
    artifact=$(grep -oE "Test unit written to [^ ]+" "$log" | tail -1 | sed 's/Test unit written to //')
    [[ -n $artifact ]] && echo "  reproduce: $bin/$t $artifact"
    echo "  full log: $log"
    failed+=("$t")
  fi
done
((${#failed[@]} == 0)) || exit 1
