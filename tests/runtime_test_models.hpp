// Test support for the runtime: a textbook model written by hand in the generated-model
// interface (so the controller is tested on a model dyncc did not generate), and a plant that
// integrates the forward dynamics of any such model with classic RK4.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "dyncc/runtime/small_matrix.hpp"

namespace dyncc::test {

/// A pendulum on a horizontal axis: J qdd + m g l sin(q) + b qd = tau, linear in
/// p = (J, m g l, b). Y(q, qd, v, a) = (a, sin q, v).
struct Pendulum {
  static constexpr int dof = 1;
  static constexpr int parameters = 3;
  template <typename S>
  static void mass_matrix(const S*, const S* p, S* H) {
    H[0] = p[0];
  }
  template <typename S>
  static void inverse_dynamics(const S* q, const S* qd, const S* qdd, const S* p, S* tau) {
    tau[0] = p[0] * qdd[0] + p[1] * std::sin(q[0]) + p[2] * qd[0];
  }
  template <typename S>
  static void control_step(const S* q, const S*, const S* v, const S* a, const S* p, const S* e, S* tau, S* ytE) {
    const S y[3] = {a[0], std::sin(q[0]), v[0]};
    tau[0] = y[0] * p[0] + y[1] * p[1] + y[2] * p[2];
    for (int b = 0; b < 3; ++b) ytE[b] = y[b] * e[0];
  }
};

/// The true arm: qdd = H(q)^-1 (tau - C qd - g - friction), with the true parameters, by RK4.
template <typename Model>
struct Plant {
  static constexpr int n = Model::dof;
  using Joints = std::array<double, n>;
  std::array<double, Model::parameters> p{};
  Joints q{}, qd{};

  [[nodiscard]] Joints acceleration(const Joints& x, const Joints& v, const Joints& tau) const {
    std::array<double, n * n> h{};
    Model::template mass_matrix<double>(x.data(), p.data(), h.data());
    const Joints zero{};
    Joints bias{};
    Model::template inverse_dynamics<double>(x.data(), v.data(), zero.data(), p.data(), bias.data());
    Joints rhs{};
    for (int k = 0; k < n; ++k) rhs[k] = tau[k] - bias[k];
    Joints qdd{};
    runtime::solve_positive_definite<double, n>(h, rhs, qdd);
    return qdd;
  }

  void step(const Joints& tau, double dt) {
    auto add = [](const Joints& a, const Joints& b, double s) {
      Joints out{};
      for (int k = 0; k < n; ++k) out[k] = a[k] + s * b[k];
      return out;
    };
    const Joints k1v = acceleration(q, qd, tau);
    const Joints k1q = qd;
    const Joints q2 = add(q, k1q, dt / 2), v2 = add(qd, k1v, dt / 2);
    const Joints k2v = acceleration(q2, v2, tau);
    const Joints q3 = add(q, v2, dt / 2), v3 = add(qd, k2v, dt / 2);
    const Joints k3v = acceleration(q3, v3, tau);
    const Joints q4 = add(q, v3, dt), v4 = add(qd, k3v, dt);
    const Joints k4v = acceleration(q4, v4, tau);
    for (int k = 0; k < n; ++k) {
      q[k] += dt / 6 * (k1q[k] + 2 * v2[k] + 2 * v3[k] + v4[k]);
      qd[k] += dt / 6 * (k1v[k] + 2 * k2v[k] + 2 * k3v[k] + k4v[k]);
    }
  }
};

}  // namespace dyncc::test
