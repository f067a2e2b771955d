// The Slotine-Li adaptive controller of the Kraft paper (eqs. 3-10, with ERRATA.md), on any
// generated model (docs/generated-code.md: struct Model with dof, parameters, control_step,
// mass_matrix). No heap, no exceptions, no RTTI; S is float or double.
//
//   q~ = q - q_d,  eps = q~' + lambda q~,  qd_r = qd_d - lambda q~,  qdd_r = qdd_d - lambda q~'
//   tau = Y(q, qd, qd_r, qdd_r) p^ - K_D eps          = H^ qdd_r + C^ qd_r + g^ + Dc^ sgn(qd) + Dmu^ qd_r - K_D eps
//   p^' = -Gamma^-1 Y^T eps                           (6), and (9)-(10) for the friction entries
//
// With K_D = lambda H^ (feedback "lambda_H"), -lambda H^ eps folds into the regressor's
// acceleration argument: tau = Y(q, qd, qd_r, qdd_r - lambda eps) p^ (ERRATA point 2), and the
// same Y adapts. Y is never formed: the model's fused control_step returns Y p^ and Y^T eps.
//
// Safeguards a real arm needs: adaptation can be switched off at run time (the paper: during
// contact), a dead zone stops it while |eps| is at noise level, and every update is projected
// onto a box and rejected if the estimated mass matrix at the current q would lose positive
// definiteness. "simplified" drops the velocity-dependent terms (Coriolis and both friction
// terms: the paper's Fig. 8).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "dyncc/runtime/small_matrix.hpp"

namespace dyncc::runtime {

enum class Feedback { constant_gain, lambda_H };

template <typename Model, typename S>
class SlotineLiController {
 public:
  static constexpr int n = Model::dof;
  static constexpr int r = Model::parameters;
  using Joints = Vector<S, n>;
  using Parameters = Vector<S, r>;

  struct Settings {
    S lambda = S(3.14159265358979);  // rad/s (the paper: 1/2 Hz bandwidth = pi rad/s)
    Feedback feedback = Feedback::lambda_H;
    Matrix<S, n> k_d{};           // used with Feedback::constant_gain (positive definite)
    Parameters gamma_inverse{};   // diagonal of Gamma^-1 (per-parameter adaptation gains)
    S period = S(1) / S(81);      // control period (s): the paper's 81 Hz
    bool simplified = false;      // drop Coriolis and friction terms (Fig. 8)
    S dead_zone = S(0);           // no adaptation while max_k |eps_k| <= dead_zone
    Parameters lower{}, upper{};  // box for the estimate (projection)
    bool bounded = false;         // apply the box
    S mass_matrix_margin = S(0);  // smallest Cholesky pivot accepted for H^(q)
  };

  /// What one step computed (for logging and tests).
  struct Step {
    Joints tau{};      // command torque
    Joints eps{};      // sliding variable
    Parameters ytE{};  // Y^T eps
    bool adapted = false;
    bool rejected = false;  // the update would have left the box's PD region: kept the old estimate
  };

  SlotineLiController(const Settings& settings, const Parameters& initial_estimate)
      : settings_(settings), estimate_(initial_estimate) {}

  /// The command torque for the measured (q, qd) and the desired trajectory, and one Euler step
  /// of the adaptation law (when enabled).
  Step step(const Joints& q, const Joints& qd, const Joints& q_des, const Joints& qd_des, const Joints& qdd_des) {
    Step out = evaluate(q, qd, q_des, qd_des, qdd_des);
    if (!adaptation_ || !outside_dead_zone(out.eps)) return out;
    Parameters next = estimate_;
    for (std::size_t b = 0; b < static_cast<std::size_t>(r); ++b) {
      next[b] -= settings_.period * settings_.gamma_inverse[b] * out.ytE[b];
    }
    if (settings_.bounded) {
      for (std::size_t b = 0; b < static_cast<std::size_t>(r); ++b) {
        next[b] = next[b] < settings_.lower[b] ? settings_.lower[b]
                                               : (next[b] > settings_.upper[b] ? settings_.upper[b] : next[b]);
      }
    }
    Matrix<S, n> h{};
    Model::template mass_matrix<S>(q.data(), next.data(), h.data());
    if (!is_positive_definite<S, n>(h, settings_.mass_matrix_margin)) {
      out.rejected = true;
      return out;
    }
    estimate_ = next;
    out.adapted = true;
    return out;
  }

  /// Torque, eps and Y^T eps without changing the estimate (continuous-time analysis, tests).
  [[nodiscard]] Step evaluate(const Joints& q, const Joints& qd, const Joints& q_des, const Joints& qd_des,
                              const Joints& qdd_des) const {
    Step out;
    Joints qd_r{}, qdd_r{}, rate{};
    for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) {
      const S error = q[k] - q_des[k];
      const S error_rate = qd[k] - qd_des[k];
      out.eps[k] = error_rate + settings_.lambda * error;
      qd_r[k] = qd_des[k] - settings_.lambda * error;
      qdd_r[k] = qdd_des[k] - settings_.lambda * error_rate;
      if (settings_.feedback == Feedback::lambda_H) qdd_r[k] -= settings_.lambda * out.eps[k];
      rate[k] = settings_.simplified ? S(0) : qd[k];
      if (settings_.simplified) qd_r[k] = S(0);
    }
    Model::template control_step<S>(q.data(), rate.data(), qd_r.data(), qdd_r.data(), estimate_.data(), out.eps.data(),
                                    out.tau.data(), out.ytE.data());
    if (settings_.feedback == Feedback::constant_gain) {
      const Joints feedback = multiply<S, n>(settings_.k_d, out.eps);
      for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) out.tau[k] -= feedback[k];
    }
    return out;
  }

  /// Adaptation on or off (the paper: off while the arm is in contact with the environment).
  void set_adaptation(bool on) { adaptation_ = on; }
  [[nodiscard]] bool adaptation() const { return adaptation_; }
  [[nodiscard]] const Parameters& estimate() const { return estimate_; }
  void set_estimate(const Parameters& p) { estimate_ = p; }
  [[nodiscard]] const Settings& settings() const { return settings_; }

 private:
  [[nodiscard]] bool outside_dead_zone(const Joints& eps) const {
    for (const S e : eps) {
      if (std::fabs(e) > settings_.dead_zone) return true;
    }
    return false;
  }

  Settings settings_;
  Parameters estimate_;
  bool adaptation_ = true;
};

}  // namespace dyncc::runtime
