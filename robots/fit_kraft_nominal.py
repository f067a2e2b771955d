#!/usr/bin/python3
"""Fits the nominal link values of robots/kraft.yaml to the paper's identified p0..p14.

Why: the paper gives only the grouped values p0..p14 (its Table/appendix), not link masses and
inertias. A controller that starts from the paper's estimate, and a simulation that should behave
like the paper's arm, need link values whose groupings reproduce them. Physical consistency is
built into the parameterisation, so every candidate is a real rigid body:
  - mass = exp(u) > 0;
  - centre of mass inside a box of +-COM_BOUND metres (tanh), a plausible size for this arm;
  - inertia about the centre of mass from a positive semi-definite second-moment matrix S
    (I = trace(S)*1 - S), which satisfies the triangle inequalities by construction.
  - reflected actuator inertias jm1..jm3 >= 0 (squares): the paper's identified p0, p6 and p8
    (the constant parts of H11, H22, H33) include them, and without them p3 + p5 >= p6, the
    triangle inequality of links 2 and 4 about the shoulder, fails for the paper's values
    (0.0521 + 0.0973 < 0.3449), so no set of rigid links alone can reproduce them.
The residual is relative, r_i = (p_i - p_i*) / max(|p_i*|, 0.01), plus a small pull towards the
hand-made guesses so that the (under-determined) fit picks plausible links.

Usage: robots/fit_kraft_nominal.py [robots/kraft.yaml]   (prints the values and the fit; it
does not edit the YAML). Needs python3-numpy, python3-sympy, python3-yaml (Debian).
"""
import sys

import numpy as np
import sympy as sp
import yaml

PAPER = [0.0489, 0.0021, -0.0214, 0.0521, 0.0807, 0.0973, 0.3449, 0.3999, 0.5819, -0.0209,
         0.0523, 0.0827, 0.0088, 0.0650, 0.0996]
COM_BOUND = 0.4
REGULARISATION = 1e-4

# Which second-moment entries each link may have (the YAML's inertia keys for that link).
LINKS = {
    1: dict(com=["y1", "z1"], full=False, yz=True),
    2: dict(com=["x2"], full=False, yz=False),
    3: dict(com=["x3", "y3", "z3"], full=True, yz=True),
    4: dict(com=["x4"], full=False, yz=False),
    5: dict(com=["x5"], full=False, yz=False),
}


def second_moments(link, v):
    """Positive semi-definite S (3x3) from the link's free numbers v."""
    spec = LINKS[link]
    if spec["full"]:
        L = np.array([[v[0], 0, 0], [v[1], v[2], 0], [v[3], v[4], v[5]]])
        return L @ L.T, 6
    if spec["yz"]:
        a = v[0] ** 2
        L = np.array([[v[1], 0], [v[2], v[3]]])
        B = L @ L.T
        return np.array([[a, 0, 0], [0, B[0, 0], B[0, 1]], [0, B[1, 0], B[1, 1]]]), 4
    return np.diag([v[0] ** 2, v[1] ** 2, v[2] ** 2]), 3


def unpack(theta):
    """Link values (a dict of the YAML's parameter names) from the free vector theta."""
    values, k = {}, 0
    for j in (1, 2, 3):
        values[f"jm{j}"] = float(theta[k] ** 2)
        k += 1
    for link, spec in LINKS.items():
        values[f"m{link}"] = float(np.exp(theta[k]))
        k += 1
        for name in spec["com"]:
            values[name] = COM_BOUND * float(np.tanh(theta[k]))
            k += 1
        S, used = second_moments(link, theta[k:])
        k += used
        inertia = np.trace(S) * np.eye(3) - S  # tensor entries: off-diagonals are -S
        values[f"i{link}xx"], values[f"i{link}yy"], values[f"i{link}zz"] = inertia[0, 0], inertia[1, 1], inertia[2, 2]
        if spec["full"]:
            values[f"i{link}xy"], values[f"i{link}xz"] = inertia[0, 1], inertia[0, 2]
        if spec["yz"]:
            values[f"i{link}yz"] = inertia[1, 2]
    return values, k


def initial_theta(guess):
    theta = [np.sqrt(guess.get(f"jm{j}", 0.01)) for j in (1, 2, 3)]
    for link, spec in LINKS.items():
        theta.append(np.log(guess[f"m{link}"]))
        for name in spec["com"]:
            theta.append(np.arctanh(np.clip(guess.get(name, 0.0) / COM_BOUND, -0.99, 0.99)))
        theta.extend([0.03] * (6 if spec["full"] else 4 if spec["yz"] else 3))
    return np.array(theta)


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "robots/kraft.yaml"
    doc = yaml.safe_load(open(path))
    constants = {sp.Symbol(k): v for k, v in doc["constants"].items()}
    names = [f"p{i}" for i in range(15)]
    exprs = [sp.sympify(str(doc["base_parameters"][n]).replace("^", "**")).subs(constants) for n in names]
    symbols = sorted({s for e in exprs for s in e.free_symbols}, key=lambda s: s.name)
    groupings = sp.lambdify(symbols, exprs, "numpy")

    def p_of(values):
        return np.array(groupings(*[values.get(s.name, 0.0) for s in symbols]), dtype=float)

    target = np.array(PAPER)
    scale = np.maximum(np.abs(target), 0.01)
    theta0 = initial_theta(doc["parameters"])

    def residual(theta):
        values, _ = unpack(theta)
        return np.concatenate([(p_of(values) - target) / scale, REGULARISATION * (theta - theta0)])

    # Levenberg-Marquardt with a finite-difference Jacobian (35 unknowns, 15 groupings).
    theta, lam = theta0.copy(), 1e-2
    r = residual(theta)
    for _ in range(5000):
        J = np.empty((r.size, theta.size))
        for j in range(theta.size):
            step = np.zeros_like(theta)
            step[j] = 1e-7
            J[:, j] = (residual(theta + step) - r) / 1e-7
        A = J.T @ J
        delta = np.linalg.solve(A + lam * np.diag(np.diag(A) + 1e-12), -J.T @ r)
        r_new = residual(theta + delta)
        if r_new @ r_new < r @ r:
            theta, r, lam = theta + delta, r_new, max(lam / 3, 1e-12)
            if np.linalg.norm(delta) < 1e-12:
                break
        else:
            lam *= 4
            if lam > 1e12:
                break

    values, _ = unpack(theta)
    fitted = p_of(values)
    print("# fitted nominal link values (paste into parameters:)")
    print("  " + ", ".join(f"jm{j}: {values[f'jm{j}']:.6g}" for j in (1, 2, 3)))
    for link, spec in LINKS.items():
        keys = [f"m{link}"] + spec["com"] + [k for k in values if k.startswith(f"i{link}")]
        print("  " + ", ".join(f"{k}: {values[k]:.6g}" for k in keys))
    print("# grouping   paper      fitted     relative error")
    for n, t, f in zip(names, target, fitted):
        print(f"  {n:<5} {t:10.4f} {f:10.6f} {abs(f - t) / abs(t):10.2e}")
    print(f"# largest relative error: {np.max(np.abs(fitted - target) / np.abs(target)):.2e}")


if __name__ == "__main__":
    main()
