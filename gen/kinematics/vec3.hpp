// Small fixed-size symbolic vectors and matrices for kinematics (3-vectors, 3x3 rotations).
#pragma once

#include <array>

#include "sym/expr.hpp"

namespace dyncc::kin {

using Vec3 = std::array<sym::Expr, 3>;
using Mat3 = std::array<Vec3, 3>;  // row-major: m[row][col]

inline Vec3 zero_vec() { return {sym::Expr(0), sym::Expr(0), sym::Expr(0)}; }
inline Mat3 identity() {
  return {Vec3{sym::Expr(1), sym::Expr(0), sym::Expr(0)}, Vec3{sym::Expr(0), sym::Expr(1), sym::Expr(0)},
          Vec3{sym::Expr(0), sym::Expr(0), sym::Expr(1)}};
}

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 operator*(sym::Expr s, const Vec3& v) { return {s * v[0], s * v[1], s * v[2]}; }
inline sym::Expr dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline Vec3 operator*(const Mat3& m, const Vec3& v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }
/// m^T v without forming the transpose.
inline Vec3 transpose_times(const Mat3& m, const Vec3& v) {
  Vec3 r = zero_vec();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[i] += m[j][i] * v[j];
  }
  return r;
}
inline Mat3 operator*(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  }
  return r;
}

}  // namespace dyncc::kin
