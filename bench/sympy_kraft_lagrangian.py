#!/usr/bin/python3
"""The Kraft arm's H, Christoffel C and gravity, derived the way a SymPy user would.

A plain Lagrangian derivation with Debian's python3-sympy, as the baseline for `dyncc derive` /
`dyncc verify` in docs/performance.md: the same five bodies and modified D-H rows as
robots/kraft.yaml (link 3 at the absolute angle q3, the parallelogram's crank and coupler),
symbolic masses, centres of mass and inertias, the reflected actuator inertias on the diagonal.

Stages (each timed): kinematics (D-H products), H = sum(Jv' m Jv + Jw' R I R' Jw) with each
entry trigsimp'ed (what one does to read it against a paper), C from Christoffel symbols of that
H, gravity from the potential energy. Prints one JSON object with the stage times in seconds and
a numeric spot check (H, C, g at a state for the robots/kraft.yaml nominal values), which
bench/run_derive_comparison.sh holds against `dyncc eval`.

usage: bench/sympy_kraft_lagrangian.py [robots/kraft.yaml] [--no-trigsimp]
  --no-trigsimp  keep H expanded but not trigsimp'ed (C and g then come from the expanded H)
Each stage's time is also printed to stderr as soon as it ends (trigsimp can take very long).
"""
import json
import sys
import time

import sympy as sp
import yaml

q = sp.symbols("q1:4")
qd = sp.symbols("qd1:4")
l2, b1, b2, l5, b3 = sp.symbols("l2 b1 b2 l5 b3")


def dh_modified(a, alpha, d, theta):
    """Craig's modified D-H transform: Rx(alpha) Tx(a) Rz(theta) Tz(d)."""
    ca, sa, ct, st = sp.cos(alpha), sp.sin(alpha), sp.cos(theta), sp.sin(theta)
    return sp.Matrix([[ct, -st, 0, a],
                      [st * ca, ct * ca, -sa, -sa * d],
                      [st * sa, ct * sa, ca, ca * d],
                      [0, 0, 0, 1]])


def body(name_index, com, inertia):
    m = sp.Symbol(f"m{name_index}")
    c = sp.Matrix([sp.Symbol(s) if isinstance(s, str) else s for s in com])
    names = {k: sp.Symbol(f"i{name_index}{k}") for k in inertia}
    get = lambda k: names.get(k, 0)
    I = sp.Matrix([[get("xx"), get("xy"), get("xz")],
                   [get("xy"), get("yy"), get("yz")],
                   [get("xz"), get("yz"), get("zz")]])
    return m, c, I


def report(stage, times):
    print(f"{stage}: {times[stage]:.2f} s", file=sys.stderr, flush=True)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    simplify = "--no-trigsimp" not in sys.argv
    path = args[0] if args else "robots/kraft.yaml"
    doc = yaml.safe_load(open(path))
    times = {}
    t0 = time.perf_counter()

    # Frames (base -> yaw -> upper_arm -> forearm; yaw -> crank -> coupler), as in the YAML.
    T1 = dh_modified(0, 0, 0, q[0])
    T2 = T1 * dh_modified(0, -sp.pi / 2, b1, q[1])
    T3 = T2 * dh_modified(l2, 0, b2 - b1, q[2] - q[1])
    T5 = T1 * dh_modified(0, -sp.pi / 2, b3, q[2])
    T4 = T5 * dh_modified(l5, 0, b1 - b3, q[1] - q[2])
    bodies = [
        (T1, body(1, [0, "y1", "z1"], ["xx", "yy", "zz", "yz"])),
        (T2, body(2, ["x2", 0, 0], ["xx", "yy", "zz"])),
        (T3, body(3, ["x3", "y3", "z3"], ["xx", "yy", "zz", "xy", "xz", "yz"])),
        (T4, body(4, ["x4", 0, 0], ["xx", "yy", "zz"])),
        (T5, body(5, ["x5", 0, 0], ["xx", "yy", "zz"])),
    ]
    times["kinematics"] = time.perf_counter() - t0

    # Mass matrix from the kinetic energy, and the potential energy.
    t = time.perf_counter()
    H = sp.zeros(3, 3)
    V = 0
    g = sp.Matrix([0, 0, -9.81])
    qv = sp.Matrix(q)
    for T, (m, c, I) in bodies:
        R = T[:3, :3]
        p = T[:3, 3] + R * c
        Jv = p.jacobian(qv)
        # Angular velocity from Rdot R^T (skew), per coordinate.
        Jw = sp.zeros(3, 3)
        for k in range(3):
            W = sp.diff(R, q[k]) * R.T
            Jw[:, k] = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
        H += m * Jv.T * Jv + Jw.T * (R * I * R.T) * Jw
        V += -m * (g.T * p)[0]
    for j in range(3):
        H[j, j] += sp.Symbol(f"jm{j + 1}")
    times["H_raw"] = time.perf_counter() - t
    report("H_raw", times)
    t = time.perf_counter()
    H = H.applyfunc(lambda e: sp.trigsimp(sp.expand(e)) if simplify else sp.expand(e))
    times["H_trigsimp" if simplify else "H_expand"] = time.perf_counter() - t
    report("H_trigsimp" if simplify else "H_expand", times)

    # Christoffel C and gravity.
    t = time.perf_counter()
    C = sp.zeros(3, 3)
    dH = [sp.diff(H, q[k]) for k in range(3)]
    for i in range(3):
        for j in range(3):
            C[i, j] = sum(sp.Rational(1, 2) * (dH[k][i, j] + dH[j][i, k] - dH[i][j, k]) * qd[k] for k in range(3))
    C = C.applyfunc(sp.expand)
    times["C"] = time.perf_counter() - t
    report("C", times)
    t = time.perf_counter()
    G = sp.Matrix([sp.expand(sp.diff(V, q[k])) for k in range(3)])
    times["g"] = time.perf_counter() - t
    times["total"] = time.perf_counter() - t0

    # Numeric spot check at one state, nominal values.
    values = {sp.Symbol(k): v for k, v in doc["constants"].items()}
    values.update({sp.Symbol(k): v for k, v in doc["parameters"].items()})
    state = {q[0]: 0.3, q[1]: -0.4, q[2]: 0.5, qd[0]: 0.7, qd[1]: -0.2, qd[2]: 0.9}
    values.update(state)
    num = lambda M: [[float(M[i, j].subs(values)) for j in range(M.shape[1])] for i in range(M.shape[0])]
    print(json.dumps({"times": times, "H": num(H), "C": num(C), "g": [r[0] for r in num(G)],
                      "state": {"q": [0.3, -0.4, 0.5], "qd": [0.7, -0.2, 0.9]}}))


if __name__ == "__main__":
    main()
