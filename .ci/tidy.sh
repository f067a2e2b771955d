#!/usr/bin/env bash
# Runs clang-tidy (policy: .clang-tidy at the repo root) over the project's own .cpp files and
# fails when there is any finding.
#
# Usage: .ci/tidy.sh [-j N] [-p BUILD_DIR] [--fix] [FILE_REGEX...]
#   -p BUILD_DIR   where compile_commands.json is (default build/release; configured with the
#                  `release` preset when missing)
#   -j N           parallel clang-tidy processes (default 2)
#   --fix          apply the fix-its clang-tidy offers (review the diff!)
#   --all          also tests/ and bench/
#   --changed-since COMMIT
#                  only the translation units that changed since COMMIT or include a header that
#                  did (from ninja's dependency log); all of them when .clang-tidy changed or
#                  COMMIT is not in the history. CI passes .ci/tidy-clean-at: a commit with the
#                  whole tree at zero findings (bump it only to a commit at which a full `.ci/run`
#                  on a clean clone passed, CI's or the same run locally, and say which in the
#                  commit message), so every landing keeps the tree clean without re-tidying what has not changed (a
#                  full run takes about 20 minutes on 2 cores).
#   FILE_REGEX     only files whose path matches one of these (e.g. gen/sym/)
# Environment: CLANG_TIDY (binary, default clang-tidy-14 or clang-tidy).
#
# Scope: the shipped code, gen/, runtime/, sim/ and plot/ sources as listed in compile_commands.json (so only
# what is actually built); with --all also tests/ and bench/ (about twice the time: GoogleTest and
# Eigen make every test file a large translation unit). Never fuzz/ or third-party code.
# Output: the findings, then a count per check, then a count per file. The full log is kept in
# BUILD_DIR/clang-tidy.log. Exit status: 0 clean, 1 findings, 2 usage/setup error.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build/release"
jobs=2
scope='gen|runtime|sim|plot'
fix=()
filters=()
since=
while (($#)); do
  case "$1" in
    -p) build=$(cd "$2" && pwd); shift 2 ;;
    -j) jobs=$2; shift 2 ;;
    --fix) fix=(-fix); shift ;;
    --all) scope='gen|runtime|sim|plot|tests|bench'; shift ;;
    --changed-since) since=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    -*) echo "tidy.sh: unknown option $1" >&2; exit 2 ;;
    *) filters+=("$1"); shift ;;
  esac
done

tidy=${CLANG_TIDY:-}
if [[ -z $tidy ]]; then
  for candidate in clang-tidy-14 clang-tidy; do
    if command -v "$candidate" >/dev/null; then tidy=$candidate; break; fi
  done
fi
[[ -n $tidy ]] || { echo "tidy.sh: clang-tidy not found (apt-get install clang-tidy-14)" >&2; exit 2; }

if [[ ! -f $build/compile_commands.json ]]; then
  echo "tidy.sh: no compile_commands.json in $build; configuring the release preset" >&2
  (cd "$root" && cmake --preset release >/dev/null)
fi

# The project's own translation units, in a stable order.
mapfile -t files < <(python3 - "$build/compile_commands.json" "$root" "$scope" "${filters[@]}" <<'EOF'
import json, os, re, sys
db, root, scope, filters = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
own = re.compile(r'^(' + scope + r')/.*\.(cc|cpp|cxx)$')
seen = set()
for entry in json.load(open(db)):
    path = os.path.normpath(os.path.join(entry.get('directory', ''), entry['file']))
    rel = os.path.relpath(path, root)
    if own.match(rel) and os.path.exists(path) and rel not in seen and (not filters or any(re.search(f, rel) for f in filters)):
        seen.add(rel)
        print(path)
EOF
)
((${#files[@]})) || { echo "tidy.sh: no matching sources in $build/compile_commands.json" >&2; exit 2; }
# The `test` preset (what CI builds) compiles the test executables as unity builds, whose compile
# commands name the batches, not the test files: --all would then skip tests/ without a word.
if [[ $scope == *tests* ]] && grep -q '/tests/CMakeFiles/[^"]*/Unity/unity_' "$build/compile_commands.json"; then
  echo "tidy.sh: the tests in $build are unity builds (the test preset), so tests/ is not checked;" \
    "configure it with 'cmake --preset release' first" >&2
fi

if [[ -n $since ]]; then
  if ! git -C "$root" cat-file -e "$since^{commit}" 2>/dev/null; then
    echo "tidy.sh: $since is not in the history; checking every file" >&2
  elif ! git -C "$root" diff --quiet "$since" HEAD -- .clang-tidy; then
    echo "tidy.sh: the tidy policy changed since $since; checking every file" >&2
  else
    git -C "$root" diff --name-only "$since" HEAD | sed "s|^|$root/|" >"$build/tidy-changed.txt"
    ninja -C "$build" -t deps >"$build/tidy-deps.txt"
    mapfile -t files < <(python3 - "$build/tidy-changed.txt" "$build/tidy-deps.txt" "${files[@]}" <<'EOF'
import os, sys
changed_list, deps_list, wanted = sys.argv[1], sys.argv[2], sys.argv[3:]
changed = {os.path.normpath(l.strip()) for l in open(changed_list) if l.strip()}
# ninja's dependency log: per object, its source first, then every header it included.
deps, current = {}, None
for line in open(deps_list):
    if not line.startswith(' ') and ': #deps' in line:
        current = None
    elif line.strip():
        path = os.path.normpath(line.strip())
        if current is None:
            current = path
        deps.setdefault(current, set()).add(path)
for f in wanted:
    f = os.path.normpath(f)
    if f in changed or deps.get(f, set()) & changed:
        print(f)
EOF
    )
    echo "tidy.sh: ${#files[@]} translation units changed, or include a change, since $since" >&2
    ((${#files[@]})) || { echo "tidy.sh: clean (nothing changed)" >&2; exit 0; }
  fi
fi
echo "tidy.sh: $tidy on ${#files[@]} files with $jobs jobs" >&2

# A private log while running (several people may run this on one build tree); the last run's
# log is then kept as BUILD_DIR/clang-tidy.log.
log=$(mktemp "${TMPDIR:-/tmp}/dyncc-tidy.XXXXXX")
trap 'cp -f "$log" "$build/clang-tidy.log" 2>/dev/null; rm -f "$log"' EXIT
status=0
runner=$(command -v "run-${tidy}" || true)
[[ -n $runner ]] || runner=$(command -v run-clang-tidy-14 || true)
if [[ -n $runner && ${CLANG_TIDY_NO_RUNNER:-0} != 1 ]]; then
  # run-clang-tidy takes regexes; anchor each file so no other file matches.
  mapfile -t regexes < <(printf '%s\n' "${files[@]}" | sed -e 's/[.[\^$*+?(){}|]/\\&/g' -e 's/^/^/' -e 's/$/$/')
  "$runner" -quiet -clang-tidy-binary "$(command -v "$tidy")" -p "$build" -j "$jobs" "${fix[@]}" \
    "${regexes[@]}" >"$log" 2>&1 || status=$?
else
  printf '%s\0' "${files[@]}" |
    xargs -0 -n 1 -P "$jobs" "$tidy" --quiet -p "$build" "${fix[@]}" >"$log" 2>&1 || status=$?
fi

# Findings: "path:line:col: warning|error: message [check]" (compiler diagnostics included, as
# clang-diagnostic-*). A header finding is reported once per including file; keep the first.
summary=0
python3 - "$log" "$root" <<'EOF' || summary=$?
import collections, re, sys
log, root = sys.argv[1], sys.argv[2]
pat = re.compile(r'^(/[^:]+):(\d+):(\d+): (warning|error): (.*?) \[([^\]]+)\]$')
seen, findings = set(), []
ansi = re.compile(r'\x1b\[[0-9;]*m')  # run-clang-tidy asks clang-tidy for colour
for line in open(log, errors='replace'):
    m = pat.match(ansi.sub('', line).rstrip('\n'))
    if not m:
        continue
    path, ln, col, _, msg, checks = m.groups()
    check = checks.split(',')[0]
    key = (path, ln, col, check)
    if key in seen:
        continue
    seen.add(key)
    findings.append((path.replace(root + '/', ''), int(ln), int(col), check, msg))
for f in sorted(findings):
    print(f'{f[0]}:{f[1]}:{f[2]}: {f[4]} [{f[3]}]')
if findings:
    print(f'\n{len(findings)} findings by check:')
    for check, n in collections.Counter(f[3] for f in findings).most_common():
        print(f'{n:6d}  {check}')
    print('\nby file:')
    for path, n in collections.Counter(f[0] for f in findings).most_common():
        print(f'{n:6d}  {path}')
sys.exit(1 if findings else 0)
EOF
if ((summary == 0 && status != 0)); then
  # clang-tidy failed without a parsable finding (e.g. a file that does not compile): show why.
  grep -E 'error|Error' "$log" | head -20 >&2
  echo "tidy.sh: clang-tidy failed (exit $status); full log: $build/clang-tidy.log" >&2
  exit 1
fi
if ((summary != 0)); then echo "tidy.sh: findings above; full log: $build/clang-tidy.log" >&2; exit 1; fi
echo "tidy.sh: clean" >&2
