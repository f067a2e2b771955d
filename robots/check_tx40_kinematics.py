#!/usr/bin/env python3
"""Checks robots/staubli_tx40*.yaml against the FIGAROH URDF of the TX40 (in the real-data folder,
never copied into the project): at q = 0 and at random configurations it composes

  (a) the URDF's own chain, Trans(xyz) * RPY(rpy) * RotZ(q) per joint,
  (b) the modified D-H rows of the description, RotX(alpha) * TransX(a) * RotZ(theta) * TransZ(d),
  (c) optionally the URDF that `dyncc export --format urdf` wrote from the description (dyncc's own
      reading of the rows),

and prints the largest difference of every link frame (position, rotation), of every link's mass,
centre of mass in the base frame and inertia tensor in base axes, (b) and (c) against (a). With
--dyncc=BINARY it also compares the mass matrix H and the gravity torques g that `dyncc eval`
derives from the description with H and g composed independently: the URDF's frames, the
description's masses, centres of mass and inertias placed in them, Jacobians of the centres of
mass, and the description's rotor inertias (gear_ratio^2 * inertia) on the diagonal. With
--motor-wrist (the _drives description: coordinate 6 is the motor-6 angle over N6, theta6 = q6 -
q5 + pi) the URDF's q6 is the description's q6 - q5, and H, g are mapped to the description's
coordinates. Exit 1 when a frame, mass, centre-of-mass, H or g difference exceeds 1e-9, or an
inertia entry differs by 5e-4 or more (the URDF prints inertias to 3 decimals; the descriptions
replace link 6's printed 0.000 by a small cylinder's tensor).

Usage (Debian's python3 with numpy and yaml):
  /usr/bin/python3 robots/check_tx40_kinematics.py URDF ROBOT.yaml [EXPORTED.urdf] [--motor-wrist] [--dyncc=BINARY]
"""
import json
import math
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import yaml


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def homogeneous(r, p):
    t = np.eye(4)
    t[:3, :3] = r
    t[:3, 3] = p
    return t


def rpy(r, p, y):
    return rot_z(y) @ rot_y(p) @ rot_x(r)


def numbers(text):
    return [float(v) for v in text.split()]


class UrdfChain:
    """A serial URDF chain of revolute joints about z (as both URDFs here are)."""

    def __init__(self, path):
        root = ET.parse(path).getroot()
        self.joints = []  # (origin transform, child link name)
        self.inertials = {}  # link -> (mass, com, inertia in link axes)
        for link in root.findall("link"):
            inertial = link.find("inertial")
            if inertial is None:
                continue
            origin = inertial.find("origin")
            xyz = numbers(origin.get("xyz", "0 0 0")) if origin is not None else [0, 0, 0]
            r = rpy(*numbers(origin.get("rpy", "0 0 0"))) if origin is not None else np.eye(3)
            i = inertial.find("inertia")
            g = {k: float(i.get(k)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
            tensor = np.array([[g["ixx"], g["ixy"], g["ixz"]], [g["ixy"], g["iyy"], g["iyz"]],
                               [g["ixz"], g["iyz"], g["izz"]]])
            self.inertials[link.get("name")] = (float(inertial.find("mass").get("value")), np.array(xyz),
                                                r @ tensor @ r.T)
        for joint in root.findall("joint"):
            if joint.get("type") != "revolute":
                continue
            axis = numbers(joint.find("axis").get("xyz"))
            if axis != [0, 0, 1]:
                sys.exit(f"{path}: joint {joint.get('name')} turns about {axis}, not z")
            origin = joint.find("origin")
            t = homogeneous(rpy(*numbers(origin.get("rpy", "0 0 0"))), numbers(origin.get("xyz", "0 0 0")))
            self.joints.append((t, joint.find("child").get("link")))

    def frames(self, q):
        t, out = np.eye(4), []
        for (origin, _), angle in zip(self.joints, q):
            t = t @ origin @ homogeneous(rot_z(angle), [0, 0, 0])
            out.append(t)
        return out

    def links(self):
        return [child for _, child in self.joints]


class DhChain:
    """The modified D-H rows of a dyncc description (expressions evaluated numerically)."""

    def __init__(self, path):
        d = yaml.safe_load(open(path))
        if d["convention"] != "modified":
            sys.exit(f"{path}: expected convention: modified")
        self.coordinates = d["coordinates"]
        self.constants = {k: float(v) for k, v in (d.get("constants") or {}).items()}
        values = {k: float(v) for k, v in (d.get("parameters") or {}).items()}
        self.rotor = np.zeros(len(self.coordinates))
        for name, entry in (d.get("rotor") or {}).items():
            inertia = entry["inertia"]
            inertia = values[inertia] if isinstance(inertia, str) else float(inertia)
            self.rotor[self.coordinates.index(name)] = float(entry.get("gear_ratio", 1)) ** 2 * inertia
        self.rows, self.inertials = [], []
        for link in d["links"]:
            self.rows.append({k: str(link.get(k, 0)) for k in ("a", "alpha", "d", "theta")})
            value = lambda x: values[x] if isinstance(x, str) else float(x)
            i = {k: value(v) for k, v in (link.get("inertia") or {}).items()}
            tensor = np.array([[i.get("xx", 0), i.get("xy", 0), i.get("xz", 0)],
                               [i.get("xy", 0), i.get("yy", 0), i.get("yz", 0)],
                               [i.get("xz", 0), i.get("yz", 0), i.get("zz", 0)]])
            self.inertials.append((value(link["mass"]), np.array([value(c) for c in link.get("com", [0, 0, 0])]),
                                   tensor))

    def evaluate(self, text, q):
        scope = dict(self.constants, pi=math.pi, sin=math.sin, cos=math.cos, sqrt=math.sqrt, atan2=math.atan2)
        scope.update(zip(self.coordinates, q))
        return float(eval(text.replace("^", "**"), {"__builtins__": {}}, scope))

    def frames(self, q):
        t, out = np.eye(4), []
        for row in self.rows:
            a, alpha, d, theta = (self.evaluate(row[k], q) for k in ("a", "alpha", "d", "theta"))
            t = t @ homogeneous(rot_x(alpha), [0, 0, 0]) @ homogeneous(np.eye(3), [a, 0, 0]) \
                @ homogeneous(rot_z(theta), [0, 0, 0]) @ homogeneous(np.eye(3), [0, 0, d])
            out.append(t)
        return out


def compare(name, frames, inertials, ref_frames, ref_inertials):
    """Largest frame-position, frame-rotation, world-com and world-inertia differences."""
    dp = dr = dc = di = dm = 0.0  # position, rotation, com, inertia, mass
    for t, (m, c, i), tr, (mr, cr, ir) in zip(frames, inertials, ref_frames, ref_inertials):
        dp = max(dp, np.abs(t[:3, 3] - tr[:3, 3]).max())
        dr = max(dr, np.abs(t[:3, :3] - tr[:3, :3]).max())
        dm = max(dm, abs(m - mr))
        dc = max(dc, np.abs((t @ np.append(c, 1))[:3] - (tr @ np.append(cr, 1))[:3]).max())
        di = max(di, np.abs(t[:3, :3] @ i @ t[:3, :3].T - tr[:3, :3] @ ir @ tr[:3, :3].T).max())
    print(f"  {name:<34} frame position {dp:.1e} m, rotation {dr:.1e}, mass {dm:.1e} kg, "
          f"com {dc:.1e} m, inertia {di:.1e} kg m^2")
    return max(dp, dr, dm, dc), di


def urdf_dynamics(frames, inertials, gravity=9.81):
    """H and g of the URDF chain from the centre-of-mass Jacobians (all joints revolute about z)."""
    n = len(frames)
    h, g = np.zeros((n, n)), np.zeros(n)
    for k, (m, c, inertia) in enumerate(inertials):
        p = (frames[k] @ np.append(c, 1))[:3]
        jv, jw = np.zeros((3, n)), np.zeros((3, n))
        for j in range(k + 1):
            z, o = frames[j][:3, 2], frames[j][:3, 3]
            jv[:, j] = np.cross(z, p - o)
            jw[:, j] = z
        r = frames[k][:3, :3]
        h += m * jv.T @ jv + jw.T @ (r @ inertia @ r.T) @ jw
        g += m * gravity * jv[2, :]
    return h, g


def dyncc_dynamics(binary, robot, q):
    out = subprocess.run([binary, "eval", robot, "--q", ",".join(repr(float(v)) for v in q), "--json"],
                         check=True, capture_output=True, text=True).stdout
    d = json.loads(out)
    return np.array(d["H"], dtype=float), np.array(d["g"], dtype=float)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    motor_wrist = "--motor-wrist" in sys.argv
    binary = next((a.split("=", 1)[1] for a in sys.argv[1:] if a.startswith("--dyncc=")), None)
    if len(args) not in (2, 3):
        sys.exit(__doc__)
    source = UrdfChain(args[0])
    dh = DhChain(args[1])
    exported = UrdfChain(args[2]) if len(args) == 3 else None
    source_inertials = [source.inertials[name] for name in source.links()]
    rng = np.random.default_rng(40)
    configurations = [np.zeros(6)] + [rng.uniform(-math.pi, math.pi, 6) for _ in range(9)]
    worst = worst_inertia = worst_dynamics = 0.0
    # q_urdf = A q: the motor-aligned wrist coordinate u6 = q5 + q6.
    a = np.eye(6)
    if motor_wrist:
        a[5, 4] = -1
    for q in configurations:
        joint_q = q.copy()
        if motor_wrist:
            joint_q[5] = q[5] - q[4]  # the description's q6 is q5 + q6 of the URDF
        ref = source.frames(joint_q)
        tool = ref[-1][:3, 3]
        print(f"q = [{', '.join(f'{v:+.3f}' for v in q)}]: URDF flange at "
              f"[{tool[0]:+.4f}, {tool[1]:+.4f}, {tool[2]:+.4f}] m")
        geometry, inertia = compare("D-H rows of the description", dh.frames(q), dh.inertials, ref, source_inertials)
        worst, worst_inertia = max(worst, geometry), max(worst_inertia, inertia)
        if exported:
            exported_inertials = [exported.inertials[name] for name in exported.links()]
            geometry, inertia = compare("dyncc export --format urdf", exported.frames(joint_q), exported_inertials,
                                        ref, source_inertials)
            worst, worst_inertia = max(worst, geometry), max(worst_inertia, inertia)
        if binary:
            h_ref, g_ref = urdf_dynamics(ref, dh.inertials)
            h_ref, g_ref = a.T @ h_ref @ a + np.diag(dh.rotor), a.T @ g_ref
            h, g = dyncc_dynamics(binary, args[1], q)
            dh_max, dg_max = np.abs(h - h_ref).max(), np.abs(g - g_ref).max()
            print(f"  {'dyncc eval H, g (URDF frames)':<34} H {dh_max:.1e} kg m^2 (largest entry "
                  f"{np.abs(h_ref).max():.3f}), g {dg_max:.1e} N m (largest {np.abs(g_ref).max():.2f})")
            worst_dynamics = max(worst_dynamics, dh_max, dg_max)
    ok = worst < 1e-9 and worst_inertia < 5e-4 and worst_dynamics < 1e-9
    print(f"largest difference: frames, masses, centres of mass {worst:.1e}, inertia {worst_inertia:.1e}"
          + (f", H and g {worst_dynamics:.1e}" if binary else "") + f": {'ok' if ok else 'MISMATCH'}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
