#!/usr/bin/env python3
"""Compares the firmware's output (float bits in hex) with the host reference (decimal doubles).

Every line is "label index value". A value passes when
    |target - host| <= 1e-4 * max(|host|, 0.05 * largest |host| of the same label),
i.e. relative error below 1e-4, except that values within 5 % of zero (a torque crossing zero)
are measured against 5 % of the label's scale: there the difference of float and double
rounding of terms of the full scale is what remains, and a pure relative error is meaningless
(measured: 0.0045 N m computed from terms of 2 N m differs by 3.4e-6 N m, 2.5e-6 of the scale).
The plain relative error and the error relative to the scale are printed too.
"""
import struct
import sys


def read(path, hex_floats):
    values = {}
    done = False
    for line in open(path):
        parts = line.split()
        if parts == ["done"]:
            done = True
            continue
        if len(parts) != 3:
            continue
        label, index, text = parts
        value = struct.unpack(">f", bytes.fromhex(text[2:]))[0] if hex_floats else float(text)
        values[(label, int(index))] = value
    return values, done


def main():
    target, target_done = read(sys.argv[1], True)
    host, host_done = read(sys.argv[2], False)
    if not target_done or not host_done:
        print(f"incomplete output: firmware done={target_done}, host done={host_done}")
        return 1
    if set(target) != set(host):
        print(f"different outputs: firmware {len(target)}, host {len(host)}")
        return 1
    scale = {}
    for (label, _), v in host.items():
        scale[label] = max(scale.get(label, 0.0), abs(v))
    worst, worst_key = 0.0, None
    for key, h in host.items():
        denominator = max(abs(h), 0.05 * scale[key[0]], 1e-30)
        error = abs(target[key] - h) / denominator
        if error > worst:
            worst, worst_key = error, key
    plain = max(abs(target[k] - h) / abs(h) for k, h in host.items() if h != 0)
    of_scale = max(abs(target[k] - h) / max(scale[k[0]], 1e-30) for k, h in host.items())
    print(f"{len(host)} values compared; largest relative error {worst:.3g} at {worst_key} "
          f"(plain relative {plain:.3g}, relative to the quantity's scale {of_scale:.3g})")
    return 0 if worst < 1e-4 else 1


if __name__ == "__main__":
    sys.exit(main())
