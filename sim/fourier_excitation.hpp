// The exciting trajectory of an identification experiment: per joint a Fourier series (a few
// harmonics, random phases and amplitudes from a seed) about the middle of a safe part of the
// joint's range. Its velocities pass through zero and reverse many times, so friction, inertia
// and gravity all leave their mark on the torque. It starts at rest: the series is faded in over
// the first seconds (a minimum-jerk window), so the arm needs no jump in torque at t = 0.
#pragma once

#include <vector>

#include "arm.hpp"
#include "operator.hpp"

namespace dyncc::sim {

class FourierExcitation {
 public:
  /// scale multiplies every joint's reach (1: the ranges below).
  explicit FourierExcitation(unsigned seed, double scale = 1.0);

  [[nodiscard]] TrajectoryPoint at(double t) const;

  /// The middle of the excited ranges (rad) and the largest excursion from it on each joint. Inside
  /// the description's limits (|q2|, |q3| <= 1.5) with margin, the elbow (q3 - q2) never below
  /// 0.3 rad (the stretched arm is the hook Jacobian's singularity), the hook between about 0.36 m
  /// and 0.03 m below the shoulder, and the gravity and inertia torques well inside the actuators'
  /// 6 / 12 / 12 N m.
  static constexpr Joints kMiddle{0.0, -0.30, 0.70};
  static constexpr Joints kReach{0.80, 0.35, 0.35};
  static constexpr int kHarmonics = 4;
  static constexpr double kBaseFrequency = 0.1;  // Hz, the identification standard (the bench's too)
  static constexpr double kFadeIn = 2.0;         // s

 private:
  struct Wave {
    double amplitude, omega, phase;
  };
  std::vector<Wave> waves_;  // kHarmonics per joint, joint-major
  double scale_;
};

}  // namespace dyncc::sim
