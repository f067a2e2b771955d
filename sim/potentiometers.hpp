// The Kraft arm's only joint sensors: potentiometers, read as noise on the true angle and then the
// ADC's quantisation (the noise is on the analogue side, so the samples stay whole multiples of
// the quantum). Shared by the tele-operation runs (scenario.cpp) and the excitation logs
// (joint_sensors.cpp), so both read their arms alike.
#pragma once

#include <cmath>
#include <random>

#include "arm.hpp"

namespace dyncc::sim {

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
