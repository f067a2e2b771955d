// The Eigen baseline's tree from a robot description, with nominal parameter values: D-H rows
// to body frames, inertias into body axes, joint couplings from the joint expressions.
//
// Written independently of gen/export (which builds MJCF/URDF bodies the same way), so that a
// test comparing either with dyncc's symbolic model checks one conversion, not a shared one.
#pragma once

#include "eigen_rbd.hpp"
#include "robot/description.hpp"

namespace dyncc::bench {

/// Throws std::invalid_argument when a joint expression is not affine in the coordinates.
RigidBodyTree tree_from_description(const robot::RobotDescription& robot);

}  // namespace dyncc::bench
