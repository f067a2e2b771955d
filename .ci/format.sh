#!/usr/bin/env bash
# Checks that every project C++ file follows .clang-format; with --fix, rewrites them in place.
#
# Usage: .ci/format.sh [--fix] [PATH...]
#   PATH   files or directories to check (default: gen runtime sim plot tests bench fuzz)
# Environment: CLANG_FORMAT (binary, default clang-format-14 or clang-format). The version
# matters: different clang-format releases format some constructs differently.
# Exit status: 0 all formatted (or fixed), 1 some file would change, 2 setup error.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
fix=0
paths=()
while (($#)); do
  case "$1" in
    --fix) fix=1; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    -*) echo "format.sh: unknown option $1" >&2; exit 2 ;;
    *) paths+=("$1"); shift ;;
  esac
done
((${#paths[@]})) || paths=(gen runtime sim plot tests bench fuzz)

format=${CLANG_FORMAT:-}
if [[ -z $format ]]; then
  for candidate in clang-format-14 clang-format; do
    if command -v "$candidate" >/dev/null; then format=$candidate; break; fi
  done
fi
[[ -n $format ]] || { echo "format.sh: clang-format not found (apt-get install clang-format-14)" >&2; exit 2; }

cd "$root"
existing=()
for p in "${paths[@]}"; do [[ -e $p ]] && existing+=("$p"); done
((${#existing[@]})) || { echo "format.sh: nothing to check" >&2; exit 0; }
mapfile -t files < <(find "${existing[@]}" -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.cc' \) \
                       -not -path '*/build/*' | sort)
((${#files[@]})) || { echo "format.sh: no C++ files under ${existing[*]}" >&2; exit 0; }

if ((fix)); then
  printf '%s\0' "${files[@]}" | xargs -0 "$format" -i --style=file
  echo "format.sh: formatted ${#files[@]} files" >&2
  exit 0
fi

bad=()
for f in "${files[@]}"; do
  if ! "$format" --dry-run -Werror --style=file "$f" >/dev/null 2>&1; then bad+=("$f"); fi
done
if ((${#bad[@]})); then
  for f in "${bad[@]}"; do
    n=$("$format" --style=file "$f" | diff "$f" - | grep -c '^[<>]' || true)
    echo "needs formatting: $f ($n changed lines)"
  done
  echo "format.sh: ${#bad[@]} of ${#files[@]} files need formatting; run .ci/format.sh --fix (see one diff: $format FILE | diff FILE -)" >&2
  exit 1
fi
echo "format.sh: ${#files[@]} files formatted" >&2
