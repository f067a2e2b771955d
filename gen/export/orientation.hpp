// Rotation matrices in the forms the two formats write.
#pragma once

#include <Eigen/Dense>

namespace dyncc::exporting {

/// URDF's rpy: R = RotZ(yaw) * RotY(pitch) * RotX(roll), returned as (roll, pitch, yaw). At
/// pitch = +-pi/2 (gimbal lock) roll is taken as 0.
Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& rotation);

/// True when the rotation is the identity to the last bit (the attribute can be left out).
bool is_identity(const Eigen::Matrix3d& rotation);

}  // namespace dyncc::exporting
