#include "export/orientation.hpp"

#include <cmath>

namespace dyncc::exporting {

Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& r) {
  // R(2,0) = -sin(pitch); cos(pitch) >= 0 by choice, so it is the length of the first column's
  // xy part.
  const double cos_pitch = std::hypot(r(0, 0), r(1, 0));
  const double pitch = std::atan2(-r(2, 0), cos_pitch);
  if (cos_pitch > 1e-12) return {std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0))};
  // Gimbal lock: only yaw -/+ roll is defined; with roll = 0, R(0,1) = -sin(yaw), R(1,1) = cos(yaw).
  return {0.0, pitch, std::atan2(-r(0, 1), r(1, 1))};
}

bool is_identity(const Eigen::Matrix3d& rotation) { return rotation == Eigen::Matrix3d::Identity(); }

}  // namespace dyncc::exporting
