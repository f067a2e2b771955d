// Kinetic energy of a serial chain of revolute links, built symbolically with dyncc's engine.
//
// This is the workload of bench/expr_bench.cpp. bench/sympy_expr_bench.py builds the same chain
// with the same formulas in SymPy; change both files together.
//
// The chain (modified / Craig D-H; link i = 1..N, k = i - 1):
//   alpha_k = 0 for even k, +pi/2 for k = 1 mod 4, -pi/2 for k = 3 mod 4
//             (N = 6: 0, +pi/2, 0, -pi/2, 0, +pi/2, like a PUMA-style arm)
//   a_k     = symbol "a<k>" when alpha_k = 0 and k > 0 (a link length between parallel axes), else 0
//   d_i     = symbol "d<i>" when alpha_k != 0 (an offset along a twisted axis), else 0
//   theta_i = q_i
//   ^{i-1}R_i = RotX(alpha_k) RotZ(q_i),   ^{i-1}p_i = (a_k, -sin(alpha_k) d_i, cos(alpha_k) d_i)
// Inertial parameters of link i, barycentric (so T is linear in them), all symbols, in frame i:
//   m<i>; first moment h = (mx<i>, my<i>, mz<i>) = m * centre of mass;
//   inertia about the link origin (xx<i>, xy<i>, xz<i>, yy<i>, yz<i>, zz<i>).
// Kinetic energy of link i, with v the velocity of origin i and w the angular velocity:
//   T_i = 1/2 m v.v + v.(w x h) + 1/2 w^T I w
//
// Two ways to get the velocities:
//   kinetic_energy_body:  recursive propagation in link coordinates (the Newton-Euler style)
//       w_i = R^T w_{i-1} + qd_i z,   v_i = R^T (v_{i-1} + w_{i-1} x p_i)
//   kinetic_energy_world: forward kinematics in base coordinates (the Jacobian style)
//       w0_i = sum_{k<=i} qd_k z0_k,  v0_i = sum_{k<=i} qd_k z0_k x (p0_i - p0_k),
//       h0 = R0_i h,  I0 = R0_i I R0_i^T
// They are equal as functions, but only because R^T R = 1, i.e. sin^2 + cos^2 = 1: their
// difference is a trigonometric (not a polynomial) identity, which is what the zero test proves.
//
// Every symbol name carries `suffix`, so a benchmark can build a chain whose nodes are not yet in
// dyncc's process-wide intern pool (fresh work), or reuse one suffix to measure the warm pool.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "sym/expr.hpp"

namespace dyncc::bench {

using sym::Expr;

using Vec3 = std::array<Expr, 3>;
using Mat3 = std::array<Vec3, 3>;  // row-major

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 operator*(Expr s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline Expr dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline Vec3 mul(const Mat3& m, const Vec3& v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }
inline Vec3 mul_transposed(const Mat3& m, const Vec3& v) {  // m^T v
  return {m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2], m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
          m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2]};
}
inline Mat3 mul(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  }
  return r;
}
inline Mat3 transposed(const Mat3& m) {
  return {Vec3{m[0][0], m[1][0], m[2][0]}, Vec3{m[0][1], m[1][1], m[2][1]}, Vec3{m[0][2], m[1][2], m[2][2]}};
}

struct Link {
  int alpha_quarter_turns = 0;  // alpha in units of pi/2: 0, +1 or -1
  Expr a;                       // a_{i-1}
  Expr d;                       // d_i
  Expr q, qd;
  Expr m;
  Vec3 h;  // first moment of mass, m * centre of mass, in link coordinates
  Mat3 I;  // inertia about the link origin, in link coordinates (symmetric)
};

inline std::vector<Link> make_chain(int n, const std::string& suffix) {
  auto s = [&](const std::string& base, int i) { return sym::symbol(base + std::to_string(i) + suffix); };
  std::vector<Link> chain;
  for (int i = 1; i <= n; ++i) {
    const int k = i - 1;
    Link l;
    l.alpha_quarter_turns = k % 2 == 0 ? 0 : (k % 4 == 1 ? 1 : -1);
    l.a = (l.alpha_quarter_turns == 0 && k > 0) ? s("a", k) : Expr(0);
    l.d = l.alpha_quarter_turns != 0 ? s("d", i) : Expr(0);
    l.q = s("q", i);
    l.qd = s("qd", i);
    l.m = s("m", i);
    l.h = {s("mx", i), s("my", i), s("mz", i)};
    const Expr xx = s("xx", i);
    const Expr xy = s("xy", i);
    const Expr xz = s("xz", i);
    const Expr yy = s("yy", i);
    const Expr yz = s("yz", i);
    const Expr zz = s("zz", i);
    l.I = {Vec3{xx, xy, xz}, Vec3{xy, yy, yz}, Vec3{xz, yz, zz}};
    chain.push_back(l);
  }
  return chain;
}

// ^{i-1}R_i = RotX(alpha) RotZ(q), with cos/sin(alpha) exact integers.
inline Mat3 joint_rotation(const Link& l) {
  const int ca = l.alpha_quarter_turns == 0 ? 1 : 0;
  const int sa = l.alpha_quarter_turns;  // sin(+-pi/2) = +-1, sin(0) = 0
  const Expr c = sym::cos(l.q);
  const Expr s = sym::sin(l.q);
  return {Vec3{c, -s, Expr(0)}, Vec3{Expr(ca) * s, Expr(ca) * c, Expr(-sa)},
          Vec3{Expr(sa) * s, Expr(sa) * c, Expr(ca)}};
}

// ^{i-1}p_i
inline Vec3 joint_offset(const Link& l) {
  const int ca = l.alpha_quarter_turns == 0 ? 1 : 0;
  const int sa = l.alpha_quarter_turns;
  return {l.a, Expr(-sa) * l.d, Expr(ca) * l.d};
}

inline Expr link_energy(const Link& l, const Vec3& v, const Vec3& w, const Vec3& h, const Mat3& I) {
  const Expr half(sym::Rational(1, 2));
  return half * l.m * dot(v, v) + dot(v, cross(w, h)) + half * dot(w, mul(I, w));
}

/// T from velocities propagated link to link in link coordinates.
inline Expr kinetic_energy_body(const std::vector<Link>& chain) {
  Vec3 w{Expr(0), Expr(0), Expr(0)};
  Vec3 v{Expr(0), Expr(0), Expr(0)};
  Expr T(0);
  for (const Link& l : chain) {
    const Mat3 R = joint_rotation(l);
    const Vec3 p = joint_offset(l);
    const Vec3 v_new = mul_transposed(R, v + cross(w, p));
    Vec3 w_new = mul_transposed(R, w);
    w_new[2] = w_new[2] + l.qd;
    v = v_new;
    w = w_new;
    T = T + link_energy(l, v, w, l.h, l.I);
  }
  return T;
}

/// T from base-frame velocities of the forward kinematics, inertial parameters rotated to the base.
inline Expr kinetic_energy_world(const std::vector<Link>& chain) {
  Mat3 R0{Vec3{Expr(1), Expr(0), Expr(0)}, Vec3{Expr(0), Expr(1), Expr(0)}, Vec3{Expr(0), Expr(0), Expr(1)}};
  Vec3 p0{Expr(0), Expr(0), Expr(0)};
  std::vector<Vec3> axes;     // z0_k
  std::vector<Vec3> origins;  // p0_k
  Expr T(0);
  for (const Link& l : chain) {
    p0 = p0 + mul(R0, joint_offset(l));
    R0 = mul(R0, joint_rotation(l));
    axes.push_back({R0[0][2], R0[1][2], R0[2][2]});
    origins.push_back(p0);
    Vec3 w{Expr(0), Expr(0), Expr(0)};
    Vec3 v{Expr(0), Expr(0), Expr(0)};
    for (std::size_t k = 0; k < axes.size(); ++k) {
      const Expr qd = chain[k].qd;
      w = w + qd * axes[k];
      v = v + qd * cross(axes[k], p0 - origins[k]);
    }
    const Vec3 h0 = mul(R0, l.h);
    const Mat3 I0 = mul(mul(R0, l.I), transposed(R0));
    T = T + link_energy(l, v, w, h0, I0);
  }
  return T;
}

/// Number of terms of a sum (1 for a single non-zero term, 0 for zero); counts the constant.
inline std::size_t term_count(Expr e) {
  if (e.is_zero()) return 0;
  if (e.kind() != sym::Kind::Add) return 1;
  return e.args().size() + (e.value().is_zero() ? 0 : 1);
}

}  // namespace dyncc::bench
