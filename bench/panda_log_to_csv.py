#!/usr/bin/env python3
"""Converts the Franka Panda excitation log of Gaz et al. 2019 (../shared/real-data/panda_gaz2019,
one number per line, blocks of 7 per sample) into the CSV `dyncc diagnose` reads:
t, q1..q7, qd1..qd7, tau1..tau7. Writes to the path given (never into the project: the data is GPL).

Usage: bench/panda_log_to_csv.py DATA_DIR OUT.csv
"""
import sys
from pathlib import Path


def column(path: Path, width: int):
    values = [float(line) for line in path.read_text().split()]
    if len(values) % width:
        sys.exit(f"{path}: {len(values)} numbers, not a multiple of {width}")
    return [values[i:i + width] for i in range(0, len(values), width)]


def main() -> None:
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    log = Path(sys.argv[1]) / "rbt_log"
    t = [row[0] for row in column(log / "exciting_traj_time.txt", 1)]
    q = column(log / "exciting_traj_positions.txt", 7)
    qd = column(log / "exciting_traj_velocity.txt", 7)
    tau = column(log / "exciting_traj_torques.txt", 7)
    if not len(t) == len(q) == len(qd) == len(tau):
        sys.exit("the four logs differ in length")
    with open(sys.argv[2], "w") as out:
        out.write("t," + ",".join(f"q{j}" for j in range(1, 8)) + "," + ",".join(f"qd{j}" for j in range(1, 8)) + ","
                  + ",".join(f"tau{j}" for j in range(1, 8)) + "\n")
        last = None
        for k, time in enumerate(t):
            if last is not None and time <= last:
                continue  # repeated time stamps: keep the first
            last = time
            out.write(",".join(repr(v) for v in [time] + q[k] + qd[k] + tau[k]) + "\n")


if __name__ == "__main__":
    main()
