// The Kraft arm's only joint sensors: potentiometers, read as noise on the true angle and then the
// ADC's quantisation (the noise is on the analogue side, so the samples stay whole multiples of
// the quantum). Shared by the tele-operation runs (scenario.cpp) and the excitation logs
// (joint_sensors.cpp), so both read their arms alike.
#pragma once

#include <cmath>
#include <numbers>
#include <random>

#include "arm.hpp"

namespace dyncc::sim {

/// The Kraft's potentiometers, the runs' default: a 12-bit ADC over a turn (rad per count), and
/// the analogue noise on the reading (rad, standard deviation).
inline constexpr double kPotentiometerQuantum = 2 * std::numbers::pi / 4096;
inline constexpr double kPotentiometerNoise = 3e-4;

class Potentiometers {
 public:
  /// quantum: rad per ADC count (0 = not quantised); noise: rad, standard deviation (0 = none).
  Potentiometers(double quantum, double noise, unsigned seed) : quantum_(quantum), noise_(0.0, noise), random_(seed) {}

  Joints read(const Joints& q) {
    Joints out{};
    for (int k = 0; k < kDof; ++k) {
      const double x = q[k] + (noise_.stddev() > 0 ? noise_(random_) : 0.0);
      out[k] = quantum_ > 0 ? quantum_ * std::round(x / quantum_) : x;
    }
    return out;
  }

 private:
  double quantum_;
  std::normal_distribution<double> noise_;
  std::mt19937 random_;
};

}  // namespace dyncc::sim
