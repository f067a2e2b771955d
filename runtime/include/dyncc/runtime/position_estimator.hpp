// Joint position, velocity and acceleration from quantised, noisy position samples only (the
// paper's arm had potentiometers and nothing else): a critically damped alpha-beta-gamma
// tracking filter per joint.
//
// Why this filter: it differentiates and filters in one recursion (no stored history, O(1) per
// sample, any fixed rate); it follows a constant acceleration without lag (a plain
// alpha-beta filter lags a sinusoid by acceleration / bandwidth^2); and its one parameter, the
// bandwidth, trades noise for lag the way a control engineer reasons about it. Gains of the
// critically damped filter, all three poles of the error dynamics at x = exp(-bandwidth * h):
//   alpha = 1 - x^3,  beta = 1.5 (1 - x)^2 (1 + x),  gamma = 0.5 (1 - x)^3.
#pragma once

#include <cmath>
#include <cstddef>

#include "dyncc/runtime/small_matrix.hpp"

namespace dyncc::runtime {

template <int N, typename S>
class PositionEstimator {
 public:
  using Joints = Vector<S, N>;

  /// period: sample period (s); bandwidth: rad/s.
  PositionEstimator(S period, S bandwidth) : period_(period) {
    const S x = std::exp(-bandwidth * period);
    alpha_ = S(1) - x * x * x;
    beta_ = S(1.5) * (S(1) - x) * (S(1) - x) * (S(1) + x);
    gamma_ = S(0.5) * (S(1) - x) * (S(1) - x) * (S(1) - x);
  }

  /// Feeds one position sample (the first one initialises the position, at rest).
  void update(const Joints& measured) {
    if (!started_) {
      position_ = measured;
      started_ = true;
      return;
    }
    const S h = period_;
    for (std::size_t k = 0; k < static_cast<std::size_t>(N); ++k) {
      const S predicted = position_[k] + h * velocity_[k] + S(0.5) * h * h * acceleration_[k];
      const S predicted_rate = velocity_[k] + h * acceleration_[k];
      const S residual = measured[k] - predicted;
      position_[k] = predicted + alpha_ * residual;
      velocity_[k] = predicted_rate + beta_ / h * residual;
      acceleration_[k] += S(2) * gamma_ / (h * h) * residual;
    }
  }

  [[nodiscard]] const Joints& position() const { return position_; }
  [[nodiscard]] const Joints& velocity() const { return velocity_; }
  [[nodiscard]] const Joints& acceleration() const { return acceleration_; }

 private:
  S period_;
  S alpha_ = S(0), beta_ = S(0), gamma_ = S(0);
  Joints position_{}, velocity_{}, acceleration_{};
  bool started_ = false;
};

}  // namespace dyncc::runtime
