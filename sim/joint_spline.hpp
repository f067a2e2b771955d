// A trajectory through sampled joint angles: a natural cubic spline per joint, so position,
// velocity and acceleration are continuous (a controller's feed-forward H qdd then has no jumps at
// the samples, as it would with linear interpolation). Used for the tele-operation excitation,
// which tracks the master arm's angles recorded at 81 Hz at up to 1 kHz.
#pragma once

#include <vector>

#include "arm.hpp"
#include "operator.hpp"

namespace dyncc::sim {

class JointSpline {
 public:
  /// Samples at strictly increasing times (at least two); throws std::invalid_argument otherwise.
  JointSpline(std::vector<double> t, std::vector<Joints> q);

  /// Outside the samples the arm rests at the first or the last one.
  [[nodiscard]] TrajectoryPoint at(double t) const;
  [[nodiscard]] double start() const { return t_.front(); }
  [[nodiscard]] double end() const { return t_.back(); }

 private:
  std::vector<double> t_;
  std::vector<Joints> q_, curvature_;  // curvature_: the second derivative at each sample
};

}  // namespace dyncc::sim
