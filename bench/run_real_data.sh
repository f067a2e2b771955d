#!/usr/bin/env bash
# The diagnosis on real arm logs (../shared/real-data/, when present; never copied into the
# project). Each data set is converted to CSV in a temporary folder and diagnosed; a data set whose
# folder is absent is skipped.
#  - Franka Panda (Gaz et al. 2019), panda_gaz2019/: against robots/panda.yaml (friction
#    approximated by Coulomb = phi1/2) and against the same description with its friction removed,
#    where the published model says the diagnosis must find friction.
#  - Staubli TX40 (FIGAROH example), staubli_tx40_figaroh/: the 5 kHz motor-side log, converted by
#    bench/tx40_log_to_csv.py and decimated to 1 kHz, against robots/staubli_tx40.yaml (rigid bodies
#    only, joint side), against robots/staubli_tx40_drives.yaml (the published a priori friction and
#    rotor inertias, coupled wrist, motor-aligned sixth coordinate: its own CSV), against the rigid
#    bodies plus the published per-joint drive terms without the wrist coupling (a plain serial
#    model; joint side), and against the drives description with one published term removed at a
#    time (Coulomb, viscous, rotor inertia), where the diagnosis must find that term and its values
#    can be compared with the published ones.
# Usage: bench/run_real_data.sh [DYNCC] [DATA_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
dyncc=${1:-build/release/dyncc}
data=${2:-../shared/real-data}
[[ -x $dyncc ]] || { echo "run_real_data: $dyncc not built" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
found=0

if [[ -d $data/panda_gaz2019 ]]; then
  found=1
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
else
  echo "run_real_data: $data/panda_gaz2019 not present; skipped"
fi

if [[ -d $data/staubli_tx40_figaroh ]]; then
  found=1
  python3 bench/tx40_log_to_csv.py "$data/staubli_tx40_figaroh" "$work/tx40_joint.csv" --wrist joint --rate 1000
  python3 bench/tx40_log_to_csv.py "$data/staubli_tx40_figaroh" "$work/tx40_motor.csv" --wrist motor --rate 1000
  # The plain serial model: the rigid bodies plus FIGAROH's per-joint Ia, fs, fv (T40X_config.yaml)
  # on joints 1..6 in joint coordinates, without motor 6's coupling terms (Iam6, fvm6, fsm6).
  python3 - robots/staubli_tx40.yaml "$work/staubli_tx40_serial_drives.yaml" <<'PY'
import sys
s = open(sys.argv[1]).read()
ia = [0.362, 0.362, 0.0988, 0.0313, 0.0468, 0.0105]
fs = [7.14, 8.26, 6.34, 2.48, 3.03, 0.282]
fv = [8.05, 5.53, 1.97, 1.11, 1.86, 0.65]
rotor = "rotor:\n" + "".join(f"  q{j}: {{inertia: {ia[j - 1]}}}\n" for j in range(1, 7))
friction = "friction:\n" + "".join(f"  q{j}: {{coulomb: {fs[j - 1]}, viscous: {fv[j - 1]}}}\n" for j in range(1, 7))
s = s.replace("name: staubli_tx40\n", "name: staubli_tx40_serial_drives\n", 1)
s = s.replace("\njoint_limits:", "\n" + rotor + "\n" + friction + "\njoint_limits:", 1)
open(sys.argv[2], 'w').write(s)
PY
  # The drives description with one published term removed: Coulomb, viscous, rotor inertia.
  python3 - robots/staubli_tx40_drives.yaml "$work" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
without = {
    "coulomb": re.sub(r'\n  fc[1-6]: [^\n]*', '', re.sub(r'coulomb: fc[1-6], ', '', s)),
    "viscous": re.sub(r'\n  fv[1-6]: [^\n]*', '', re.sub(r', viscous: fv[1-6]', '', s)),
    "rotor": re.sub(r'\n  ia[1-6]: [^\n]*', '', re.sub(r'\nrotor:.*?\n\n', '\n\n', s, flags=re.S)),
}
for term, text in without.items():
    open(f"{sys.argv[2]}/staubli_tx40_drives_no_{term}.yaml", "w").write(text)
PY
  for run in "robots/staubli_tx40.yaml tx40_joint" "robots/staubli_tx40_drives.yaml tx40_motor" \
             "$work/staubli_tx40_serial_drives.yaml tx40_joint" "$work/staubli_tx40_drives_no_coulomb.yaml tx40_motor" \
             "$work/staubli_tx40_drives_no_viscous.yaml tx40_motor" "$work/staubli_tx40_drives_no_rotor.yaml tx40_motor"; do
    read -r robot log <<<"$run"
    echo "=== dyncc diagnose $(basename "$robot") staubli_tx40_figaroh ($log.csv, 1 kHz) ==="
    "$dyncc" diagnose "$robot" "$work/$log.csv" 2>/dev/null | sed -n '/held-out gap/,$p'
  done
else
  echo "run_real_data: $data/staubli_tx40_figaroh not present; skipped"
fi

[[ $found == 1 ]] || echo "run_real_data: no real-data folder in $data; nothing to do"
