#!/usr/bin/env python3
"""Converts the Staubli TX40 identification log of the FIGAROH example
(../shared/real-data/staubli_tx40_figaroh: data/pos_read_data.csv, motor encoder angles in rad, and
data/curr_data.csv, motor torques, 45000 rows each at 5 kHz) into the CSV `dyncc diagnose` reads:
t, q1..q6, tau1..tau6. Writes to the path given (never into the project: the data is licensed
separately).

Motor side to joint side, with the gear ratios N = 32, 32, 45, -48, 45, 32 and the coupled wrist
(motor 6 turns with joints 5 and 6: q_motor6 = N6 (q5 + q6)), as the FIGAROH example does:

  --wrist joint (default; robots/staubli_tx40.yaml):
      q_i = q_motor_i / N_i (i = 1..5),  q6 = q_motor6 / N6 - q5,
      tau_i = N_i y_i (i = 1..4, 6),     tau5 = N5 y5 + N6 y6;
  --wrist motor (robots/staubli_tx40_drives.yaml, sixth coordinate q56 = q5 + q6):
      q_i = q_motor_i / N_i,  tau_i = N_i y_i  (no coupling matrix: it is in the description);

then q2 -= pi/2 and q3 += pi/2, the shift from the controller's zero to the URDF's (and the
descriptions') D-H zero (the log starts at rest there: q = 0 with the upper arm horizontal, where
the logged tau2, about -24 N m, is close to the model's gravity torque, -23.7 N m).

--rate HZ decimates by averaging blocks of 5000/HZ samples (a boxcar: the arm moves below 3 Hz, and
the motor-current noise is averaged rather than just sampled), time stamped at each block's centre
(zero phase). HZ must divide 5000; default 5000 (no decimation). bench/run_real_data.sh uses 1000:
`dyncc diagnose` filters at 4 Hz and evaluates at 100 Hz whatever the rate, and prints the same
figures from 5 kHz, 1 kHz or 500 Hz logs. Standard library only.

Usage: bench/tx40_log_to_csv.py DATA_DIR OUT.csv [--wrist joint|motor] [--rate HZ]
"""
import csv
import math
import sys
from pathlib import Path

GEAR = [32.0, 32.0, 45.0, -48.0, 45.0, 32.0]
SAMPLE_TIME = 0.0002  # s, 5 kHz
JOINTS = 6


def read(path: Path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    if len(header) != JOINTS:
        sys.exit(f"{path}: {len(header)} columns, expected {JOINTS}")
    return [[float(v) for v in row] for row in body]


def options(args):
    wrist, rate = "joint", 5000
    positional = []
    i = 0
    while i < len(args):
        if args[i] == "--wrist" and i + 1 < len(args):
            wrist = args[i + 1]
            i += 2
        elif args[i] == "--rate" and i + 1 < len(args):
            rate = int(args[i + 1]) if args[i + 1].isdigit() else 0
            i += 2
        else:
            positional.append(args[i])
            i += 1
    if len(positional) != 2 or wrist not in ("joint", "motor") or rate <= 0 or 5000 % rate:
        sys.exit(__doc__)
    return positional[0], positional[1], wrist, 5000 // rate


def main() -> None:
    data_dir, out_path, wrist, block = options(sys.argv[1:])
    data = Path(data_dir) / "data"
    motor_q = read(data / "pos_read_data.csv")
    motor_tau = read(data / "curr_data.csv")
    if len(motor_q) != len(motor_tau):
        sys.exit("positions and torques differ in length")
    with open(out_path, "w") as out:
        out.write("t," + ",".join(f"q{j}" for j in range(1, 7)) + "," + ",".join(f"tau{j}" for j in range(1, 7))
                  + "\n")
        for start in range(0, len(motor_q) - block + 1, block):
            qm = [sum(motor_q[k][j] for k in range(start, start + block)) / block for j in range(JOINTS)]
            y = [sum(motor_tau[k][j] for k in range(start, start + block)) / block for j in range(JOINTS)]
            q = [qm[j] / GEAR[j] for j in range(JOINTS)]
            tau = [GEAR[j] * y[j] for j in range(JOINTS)]
            if wrist == "joint":
                q[5] -= q[4]
                tau[4] += GEAR[5] * y[5]
            q[1] -= math.pi / 2
            q[2] += math.pi / 2
            t = SAMPLE_TIME * (start + (block - 1) / 2)
            out.write(",".join(repr(v) for v in [t] + q + tau) + "\n")


if __name__ == "__main__":
    main()
